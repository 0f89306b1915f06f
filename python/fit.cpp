// Scattered-data approximation by LR splines (fit/lr_approximation.hpp, as `trivar fit`): points (N, D) with
// values (N, m) from NumPy; the fitted LR spline, the per-iteration report and the final error per point.
#include "bindings.hpp"
#include "trivar/fit/graph_surface.hpp"
#include "trivar/fit/lr_approximation.hpp"

namespace trivar::python {

namespace {

template <int D>
py::object fit(const Array& points, const Array& values, const ApproximationOptions& o, bool height_field) {
  ScatteredData<D> data;
  bool single = false;
  const auto params = params_of<D>(points, single);
  require(!single, "fit: points must have shape (N, " + std::to_string(D) + ")");
  data.params.assign(params.begin(), params.end());
  require(values.ndim() == 1 || values.ndim() == 2, "fit: values must have shape (N,) or (N, m)");
  require(static_cast<std::size_t>(values.shape(0)) == params.size(),
          "fit: " + std::to_string(values.shape(0)) + " values for " + std::to_string(params.size()) + " points");
  data.dim = values.ndim() == 2 ? static_cast<int>(values.shape(1)) : 1;
  data.values.assign(values.data(), values.data() + values.size());
  std::optional<Approximation<D>> fitted;
  {
    py::gil_scoped_release release;
    validate(data, "fit");
    fitted.emplace(approximate(data, o));
  }
  const Approximation<D>& r = *fitted;
  const auto n = static_cast<py::ssize_t>(r.iterations.size());
  py::array_t<int> level(n), coefficients(n), elements(n);
  py::array_t<long long> outside(n);
  auto max_error = new_array({n}), mean_error = new_array({n}), rms_error = new_array({n}), seconds = new_array({n});
  py::list independence;
  for (py::ssize_t i = 0; i < n; ++i) {
    const IterationReport& it = r.iterations[static_cast<std::size_t>(i)];
    level.mutable_data()[i] = it.level;
    coefficients.mutable_data()[i] = it.coefficients;
    elements.mutable_data()[i] = it.elements;
    outside.mutable_data()[i] = static_cast<long long>(it.outside);
    max_error.mutable_data()[i] = it.max_error;
    mean_error.mutable_data()[i] = it.mean_error;
    rms_error.mutable_data()[i] = it.rms_error;
    seconds.mutable_data()[i] = it.seconds;
    independence.append(it.independence);
  }
  const auto ns = py::module_::import("types").attr("SimpleNamespace");
  py::object spline;
  if constexpr (D == 2) {
    spline = data.dim == 1 && !height_field ? py::cast(graph_surface(r.spline, r.parameters)) : py::cast(r.spline);
  } else {
    spline = py::cast(r.spline);
  }
  return ns(py::arg("spline") = spline,
            py::arg("iterations") =
                ns(py::arg("level") = level, py::arg("coefficients") = coefficients, py::arg("elements") = elements,
                   py::arg("max_error") = max_error, py::arg("mean_error") = mean_error,
                   py::arg("rms_error") = rms_error, py::arg("outside") = outside, py::arg("seconds") = seconds,
                   py::arg("independence") = independence),
            py::arg("errors") = py::array_t<double>(static_cast<py::ssize_t>(r.errors.size()), r.errors.data()),
            py::arg("converged") = r.converged, py::arg("stop_reason") = r.stop_reason,
            py::arg("tolerance") = o.tolerance);
}

py::object fit_any(const Array& points, const Array& values, double tolerance, double relative_tolerance,
                   int degree, int initial_elements, int levels, int max_coefs, const std::string& strategy,
                   const std::string& method, int mba_passes, double smoothing, bool uniform, bool check_independence, bool height_field, int threads) {
  require(points.ndim() == 2 && (points.shape(1) == 2 || points.shape(1) == 3),
          "fit: points must have shape (N, 2) (a surface) or (N, 3) (a volume)");
  ApproximationOptions o;
  if (tolerance > 0) {
    o.tolerance = tolerance;
  } else {
    require(relative_tolerance > 0, "fit: give tolerance or relative_tolerance");
    require(values.size() > 0, "fit: no values");
    const auto [lo, hi] = std::minmax_element(values.data(), values.data() + values.size());
    o.tolerance = relative_tolerance * (*hi - *lo);
    require(o.tolerance > 0, "fit: the values are constant, so a relative tolerance is 0; give tolerance");
  }
  o.degree = degree;
  o.initial_elements = initial_elements;
  o.max_levels = levels;
  o.max_coefficients = max_coefs;
  o.strategy = parse_strategy(strategy);
  o.method = parse_fit_method(method);
  o.mba_passes = mba_passes;
  o.smoothing = smoothing;
  o.uniform = uniform;
  o.check_independence = check_independence;
  o.threads = threads;
  return points.shape(1) == 2 ? fit<2>(points, values, o, height_field) : fit<3>(points, values, o, height_field);
}

}  // namespace

void bind_fit(py::module_& m) {
  m.def("fit", &fit_any, py::arg("points"), py::arg("values"), py::arg("tolerance") = 0.0,
        py::arg("relative_tolerance") = 0.0, py::arg("degree") = 2, py::arg("initial_elements") = 4,
        py::arg("levels") = 10, py::arg("max_coefs") = 0, py::arg("strategy") = "fullspan",
        py::arg("method") = "ls", py::arg("mba_passes") = 3, py::arg("smoothing") = 1e-9, py::arg("uniform") = false,
        py::arg("check_independence") = true,
        py::arg("height_field") = false, py::arg("threads") = 1,
        "Adaptive LR approximation of scattered data as `trivar fit` (Skytt, Barrowclough and Dokken 2015):\n"
        "points (N, 2) or (N, 3) are the parameters, values (N,) or (N, m) what is fitted; refines where a point\n"
        "is off by more than `tolerance` (or relative_tolerance times the value range) up to `levels` rounds;\n"
        "method 'ls' (penalised least squares) or 'mba' (multilevel B-spline approximation, mba_passes per round).\n"
        "Returns a namespace: spline (an LRSurface: the graph (x, y, h) for one value per 2-D point unless\n"
        "height_field, else the field itself; an LRVolume for 3-D points), iterations (arrays per round: level,\n"
        "coefficients, elements, max_error, mean_error, rms_error, outside, seconds, independence), errors per\n"
        "point, converged, stop_reason, tolerance.");
}

}  // namespace trivar::python
