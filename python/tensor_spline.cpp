// Curve, Surface, Volume: TensorSpline<1, 2, 3> with NumPy in and out. Batches run in the library's threaded
// batch calls with the GIL released, on the caller's parameter array itself when it is C-contiguous float64.
#include <Eigen/Core>
#include <pybind11/eigen.h>

#include "bindings.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/spline/affine_transform.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/derivative_index.hpp"
#include "trivar/spline/jacobian.hpp"
#include "trivar/spline/knot_insertion.hpp"
#include "trivar/spline/measure.hpp"
#include "trivar/spline/point_inversion.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar::python {

namespace {

const char* kNames[] = {"", "Curve", "Surface", "Volume"};

// The control values in storage order (first direction fastest) from (N, dim) or (n_0, ..., n_{D-1}, dim).
template <int D>
std::vector<double> storage_order(const Array& p, const Ints<D>& counts, int& dim) {
  int n = 1;
  for (int c : counts) n *= c;
  if (p.ndim() == 2 && p.shape(0) == n) {
    dim = static_cast<int>(p.shape(1));
    return {p.data(), p.data() + p.size()};
  }
  bool grid = p.ndim() == D + 1;
  for (int k = 0; grid && k < D; ++k) grid = p.shape(k) == counts[k];
  require(grid, [&] {
    std::string want;
    for (int k = 0; k < D; ++k) want += std::to_string(counts[k]) + ", ";
    return std::string("control_points: expected shape (") + std::to_string(n) + ", dim) or (" + want +
           "dim) for these knots and degrees, got an array of " + std::to_string(p.ndim()) + " dimensions";
  });
  dim = static_cast<int>(p.shape(D));
  std::vector<double> out(static_cast<std::size_t>(p.size()));
  // p is C order (last index fastest): (i_0, ..., i_{D-1}) -> storage index i_0 + n_0 (i_1 + ...).
  std::array<int, D> i{};
  for (int c = 0; c < n; ++c) {
    int linear = 0, stride = 1, cpos = 0, cstride = 1;
    for (int k = D - 1; k >= 0; --k) {
      cpos += i[k] * cstride;
      cstride *= counts[k];
    }
    for (int k = 0; k < D; ++k) {
      linear += i[k] * stride;
      stride *= counts[k];
    }
    std::copy_n(p.data() + static_cast<std::size_t>(cpos) * dim, dim,
                out.data() + static_cast<std::size_t>(linear) * dim);
    for (int k = D - 1; k >= 0 && ++i[k] == counts[k]; --k) i[k] = 0;
  }
  return out;
}

// A C array of shape (n_{D-1}, ..., n_0, extra...) seen as (n_0, ..., n_{D-1}, extra...): a view, no copy.
py::array ij_view(py::array a, int D) {
  std::vector<py::ssize_t> axes;
  for (int k = D - 1; k >= 0; --k) axes.push_back(k);
  for (py::ssize_t k = D; k < a.ndim(); ++k) axes.push_back(k);
  return a.attr("transpose")(axes);
}

template <int D>
TensorSpline<D> make(const std::vector<Array>& knots, const py::object& degrees, const Array& points,
                     const std::optional<Array>& weights) {
  require(knots.size() == D, [&] {
    return std::string(kNames[D]) + ": expected " + std::to_string(D) + " knot vectors, got " +
           std::to_string(knots.size());
  });
  const Ints<D> p = ints_of<D>(degrees, "degrees");
  std::array<KnotVector, D> kv;
  Ints<D> counts{};
  for (int k = 0; k < D; ++k) {
    require(knots[k].ndim() == 1, "knots: each knot vector must be a 1-D array");
    kv[k] = KnotVector(p[k], std::vector<double>(knots[k].data(), knots[k].data() + knots[k].size()));
    counts[k] = kv[k].size();
  }
  int dim = 0;
  const std::vector<double> pts = storage_order<D>(points, counts, dim);
  std::vector<double> w;
  if (weights && weights->ndim() == D && D > 1) {
    // Weights indexed like the control net, [i_0, ..., i_{D-1}]: reordered as the points are.
    std::vector<py::ssize_t> shape(weights->shape(), weights->shape() + D);
    shape.push_back(1);
    int one = 0;
    w = storage_order<D>(Array(weights->attr("reshape")(shape)), counts, one);
  } else if (weights) {
    w.assign(weights->data(), weights->data() + weights->size());
  }
  return TensorSpline<D>::from_cartesian(std::move(kv), dim, pts, w);
}

template <int D>
py::array evaluate(const TensorSpline<D>& s, const Array& u, int threads) {
  return evaluate_batch<D>(u, s.dim(), [&](auto params, auto out) { s.eval_batch(params, out, threads); });
}

template <int D>
py::array derivatives(const TensorSpline<D>& s, const Array& u, int order, int threads) {
  require(order >= 0 && order <= kMaxDerivativeOrder,
          "derivatives: order must be in 0.." + std::to_string(kMaxDerivativeOrder) + ", got " + std::to_string(order));
  bool single = false;
  const auto params = params_of<D>(u, single);
  const int count = derivative_count(D, order);
  auto out = new_array({static_cast<py::ssize_t>(params.size()), count, s.dim()});
  {
    py::gil_scoped_release release;
    s.eval_derivs_batch(params, order, span_of(out), threads);
  }
  if (single) return out.attr("reshape")(count, s.dim());
  return out;
}

template <int D>
py::array grid(const TensorSpline<D>& s, const std::vector<Array>& params, int threads) {
  require(params.size() == D, [&] {
    return "grid: expected " + std::to_string(D) + " parameter lists, got " + std::to_string(params.size());
  });
  std::array<std::vector<double>, D> lists;
  std::vector<py::ssize_t> shape;
  for (int k = D - 1; k >= 0; --k) {
    require(params[k].ndim() == 1, "grid: each parameter list must be a 1-D array");
    lists[k].assign(params[k].data(), params[k].data() + params[k].size());
    shape.push_back(params[k].size());
  }
  shape.push_back(s.dim());
  auto out = new_array(shape);
  {
    py::gil_scoped_release release;
    s.eval_grid(lists, span_of(out), threads);
  }
  return ij_view(out, D);
}

template <int D>
py::tuple invert(const TensorSpline<D>& s, const Array& x, double tolerance, int max_newton, int max_depth,
                 int threads) {
  require(s.dim() == D, [&] {
    return "invert: needs control dimension " + std::to_string(D) + " (a " + kNames[D] + " in " + std::to_string(D) +
           "-space), got " + std::to_string(s.dim());
  });
  bool single = false;
  const auto points = params_of<D>(x, single);
  const std::size_t n = points.size();
  auto params = new_array({static_cast<py::ssize_t>(n), D});
  py::array_t<bool> found(static_cast<py::ssize_t>(n));
  auto residual = new_array({static_cast<py::ssize_t>(n)});
  {
    py::gil_scoped_release release;
    const PointInverter<D> inverter(s, {.tolerance = tolerance, .max_newton = max_newton, .max_depth = max_depth});
    double* u = params.mutable_data();
    bool* f = found.mutable_data();
    double* r = residual.mutable_data();
    parallel_for(static_cast<std::ptrdiff_t>(n), threads, [&](std::ptrdiff_t i) {
      const InversionResult<D> res = inverter.invert(points[static_cast<std::size_t>(i)].data());
      std::copy_n(res.param.data(), D, u + i * D);
      f[i] = res.found && res.converged;
      r[i] = res.residual;
    });
  }
  if (single)
    return py::make_tuple(params.attr("reshape")(D), found.attr("__getitem__")(0), residual.attr("__getitem__")(0));
  return py::make_tuple(params, found, residual);
}

template <int D>
py::list knot_list(const TensorSpline<D>& s) {
  py::list l;
  for (int k = 0; k < D; ++k) l.append(py::array_t<double>(s.knots(k).knots().size(), s.knots(k).knots().data()));
  return l;
}

template <int D>
std::string repr(const TensorSpline<D>& s) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, bug 105329) on "literal" + std::string here.
  std::string degrees, counts;
  for (int k = 0; k < D; ++k) {
    degrees.append(k ? ", " : "").append(std::to_string(s.degree(k)));
    counts.append(k ? ", " : "").append(std::to_string(s.count(k)));
  }
  return std::string("<trivar.") + kNames[D] + " degrees (" + degrees + "), control points (" + counts + "), dim " +
         std::to_string(s.dim()) + (s.is_rational() ? ", rational" : "") + ">";
}

template <int D>
void bind_jacobian_report(py::module_& m) {
  const char* name = D == 3 ? "JacobianReport" : "SurfaceJacobianReport";
  py::class_<JacobianReport<D>>(m, name, "Certified sign of det J (see Volume.check_jacobian).")
      .def_readonly("valid", &JacobianReport<D>::valid, "Certified: det J > 0 on the whole domain.")
      .def_readonly("invalid", &JacobianReport<D>::invalid, "Certified: det J <= 0 at `where`.")
      .def_readonly("min_lower_bound", &JacobianReport<D>::min_lower_bound, "Certified lower bound of min det J.")
      .def_readonly("min_value", &JacobianReport<D>::min_value, "Smallest det J value found.")
      .def_property_readonly(
          "where", [](const JacobianReport<D>& r) { return r.where; }, "Parameter of min_value.")
      .def_readonly("elements", &JacobianReport<D>::elements, "Bezier elements examined.")
      .def_readonly("subdivisions", &JacobianReport<D>::subdivisions, "Sub-boxes made by the branch and bound.")
      .def("__bool__", [](const JacobianReport<D>& r) { return r.valid; })
      .def("__repr__", [](const JacobianReport<D>& r) {
        return std::string("<trivar.JacobianReport ") +
               (r.valid     ? "valid"
                : r.invalid ? "invalid"
                            : "undecided") +
               ", min det J in [" + std::to_string(r.min_lower_bound) + ", " + std::to_string(r.min_value) + "]>";
      });
}

template <int D>
void bind_spline(py::module_& m, const char* doc) {
  using S = TensorSpline<D>;
  py::class_<S> c(m, kNames[D], doc);
  c.def(py::init(&make<D>), py::arg("knots"), py::arg("degrees"), py::arg("control_points"),
        py::arg("weights") = py::none(),
        "From knot vectors (one 1-D array per direction), degrees (an int or one per direction), control points of\n"
        "shape (n_0, ..., n_{D-1}, dim) or (N, dim) with the first direction fastest, and optional positive\n"
        "weights (n_0, ..., n_{D-1}) or (N,) in the same order (a NURBS). Raises trivar.Error on invalid knots, sizes "
        "or weights.")
      .def_property_readonly(
          "parametric_dim", [](const S&) { return D; }, "1 (curve), 2 (surface) or 3 (volume).")
      .def_property_readonly("dim", &S::dim, "Control (model-space) dimension.")
      .def_property_readonly("rational", &S::is_rational, "True for a NURBS (weights stored).")
      .def_property_readonly(
          "degrees",
          [](const S& s) {
            Ints<D> p;
            for (int k = 0; k < D; ++k) p[k] = s.degree(k);
            return p;
          },
          "Polynomial degree per direction.")
      .def_property_readonly("counts", &S::counts, "Control points per direction.")
      .def_property_readonly("knots", &knot_list<D>, "One array of knots per direction.")
      .def_property_readonly(
          "domain", [](const S& s) { return box_array<D>(s.domain()); }, "(D, 2) bounds.")
      .def_property_readonly(
          "control_points",
          [](const S& s) {
            auto a = new_array({s.num_coefs(), s.dim()});
            double* p = a.mutable_data();
            for (int i = 0; i < s.num_coefs(); ++i) s.control_point(i, p + static_cast<std::ptrdiff_t>(i) * s.dim());
            return a;
          },
          "Cartesian control points (N, dim), first direction fastest (a copy).")
      .def_property_readonly(
          "control_net",
          [](const S& s) {
            std::vector<py::ssize_t> shape;
            for (int k = D - 1; k >= 0; --k) shape.push_back(s.count(k));
            shape.push_back(s.dim());
            auto a = new_array(shape);
            double* p = a.mutable_data();
            for (int i = 0; i < s.num_coefs(); ++i) s.control_point(i, p + static_cast<std::ptrdiff_t>(i) * s.dim());
            return ij_view(a, D);
          },
          "Cartesian control points indexed [i_0, ..., i_{D-1}, :].")
      .def_property_readonly(
          "weights",
          [](const S& s) {
            auto a = new_array({s.num_coefs()});
            for (int i = 0; i < s.num_coefs(); ++i) a.mutable_data()[i] = s.weight(i);
            return a;
          },
          "Weights (N,), all 1 for a polynomial spline.")
      .def("__call__", &evaluate<D>, py::arg("u"), py::arg("threads") = 0,
           "Values at parameters u (N, D) -> (N, dim); one point (D,) -> (dim,). Outside the domain: clamped.")
      .def("evaluate", &evaluate<D>, py::arg("u"), py::arg("threads") = 0, "Same as calling the spline.")
      .def("derivatives", &derivatives<D>, py::arg("u"), py::arg("order") = 1, py::arg("threads") = 0,
           "All partial derivatives up to total `order`: (N, count, dim), ordered by total order, then\n"
           "lexicographically descending in the exponents (volume, order 2: f, f_u, f_v, f_w, f_uu, f_uv, f_uw,\n"
           "f_vv, f_vw, f_ww). Rational quotient rule applied.")
      .def("grid", &grid<D>, py::arg("params"), py::arg("threads") = 0,
           "Values on the tensor grid of D parameter lists: (n_0, ..., n_{D-1}, dim), by sum factorisation.")
      .def(
          "insert_knots",
          [](const S& s, int direction, const Array& knots) {
            require(direction >= 0 && direction < D, "insert_knots: direction must be in 0.." + std::to_string(D - 1));
            return insert_knots<D>(s, direction,
                                   std::span<const double>(knots.data(), static_cast<std::size_t>(knots.size())));
          },
          py::arg("direction"), py::arg("knots"), "The same geometry with the knots inserted (Boehm).")
      .def(
          "refine",
          [](const S& s, const py::object& by) {
            const Ints<D> n = ints_of<D>(by, "refine");
            double coefs = s.stride();
            for (int k = 0; k < D; ++k)
              coefs *= static_cast<double>(s.knots(k).num_elements()) * std::max(1, n[k]) + s.degree(k);
            require_memory(8.0 * coefs, "refining " + repr<D>(s) + " by " + py::str(by).cast<std::string>());
            py::gil_scoped_release release;
            return refine_uniform<D>(s, n);
          },
          py::arg("n") = 2, "Every element split into n equal parts (an int or one per direction).")
      .def(
          "elevate", [](const S& s, const py::object& by) { return elevate_degree<D>(s, ints_of<D>(by, "elevate")); },
          py::arg("by") = 1, "Degree raised by `by` (an int or one per direction); geometry unchanged.")
      .def(
          "transform",
          [](const S& s, const Eigen::MatrixXd& A, const Eigen::VectorXd& b) { return transform<D>(s, A, b); },
          py::arg("A"), py::arg("b"), "The affine image x -> A x + b.")
      .def(
          "measure",
          [](const S& s, int n, int threads) {
            if (n == 0) {
              // det J of a polynomial map R^D -> R^D has degree D p - 1 per direction: ceil(D p / 2) Gauss points
              // are exact. Rational maps and curved lengths or areas (a square root) get 2 p + 8, whose error
              // decays spectrally (VModel::volume's rule).
              int p = 0;
              for (int k = 0; k < D; ++k) p = std::max(p, s.degree(k));
              n = s.is_rational() || s.dim() != D ? 2 * p + 8 : (D * p + 1) / 2 + 1;
            }
            py::gil_scoped_release release;
            return measure<D>(s, n, threads);
          },
          py::arg("n") = 0, py::arg("threads") = 0,
          "Length, area or volume by Gauss quadrature with n points per element and direction; n = 0: exact\n"
          "for polynomial maps of control dimension D, 2 p + 8 points otherwise.")
      .def("invert", &invert<D>, py::arg("points"), py::arg("tolerance") = 1e-10, py::arg("max_newton") = 30,
           py::arg("max_depth") = 40, py::arg("threads") = 0,
           "Point inversion of model points (N, D) (control dimension D): returns (params (N, D), found (N,),\n"
           "residual (N,)). found is False where the point is provably outside the image (or did not converge).")
      .def("__repr__", &repr<D>);
  if constexpr (D >= 2) {
    bind_jacobian_report<D>(m);
    c.def(
        "check_jacobian",
        [](const S& s, int max_depth, double relative_gap) {
          py::gil_scoped_release release;
          return check_jacobian<D>(s, {.max_depth = max_depth, .relative_gap = relative_gap});
        },
        py::arg("max_depth") = 8, py::arg("relative_gap") = 1e-3,
        "Certified validity: is det J > 0 on the whole domain (control dimension D)? As `trivar check`.");
  }
}

}  // namespace

void bind_tensor_splines(py::module_& m) {
  bind_spline<1>(m, "A B-spline or NURBS curve (TensorSpline<1>).");
  bind_spline<2>(m, "A tensor-product B-spline or NURBS surface (TensorSpline<2>).");
  bind_spline<3>(m, "A trivariate B-spline or NURBS volume (TensorSpline<3>).");
}

}  // namespace trivar::python
