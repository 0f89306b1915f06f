// LRSurface, LRVolume: locally refined B-splines (LRSpline<2, 3>), from tensor splines, refined by the
// strategies of `trivar refine` (FULLSPAN, MINSPAN, STRUCTURED), evaluated on NumPy batches.
#include "bindings.hpp"
#include "trivar/lr/knot_line_mesh.hpp"
#include "trivar/lr/linear_independence.hpp"
#include "trivar/lr/lr_spline.hpp"
#include "trivar/lr/refinement.hpp"

namespace trivar::python {

namespace {

template <int D>
py::array evaluate(const LRSpline<D>& s, const Array& u, int threads) {
  return evaluate_batch<D>(u, s.dim(), [&](auto params, auto out) { s.eval_many(params, out, threads); });
}

template <int D>
py::array first_derivatives(const LRSpline<D>& s, const Array& u, int threads) {
  bool single = false;
  const auto params = params_of<D>(u, single);
  auto out = new_array({static_cast<py::ssize_t>(params.size()), D + 1, s.dim()});
  {
    py::gil_scoped_release release;
    s.eval_first_derivatives_many(params, span_of(out), threads);
  }
  if (single) return out.attr("reshape")(D + 1, s.dim());
  return out;
}

template <int D>
int refine(LRSpline<D>& s, const std::optional<std::vector<int>>& elements,
           const std::optional<std::vector<int>>& functions, const std::string& strategy, int multiplicity,
           double max_aspect_ratio) {
  require(elements.has_value() != functions.has_value(), "refine: give either elements or functions");
  const RefineOptions o{parse_strategy(strategy), multiplicity, max_aspect_ratio};
  py::gil_scoped_release release;
  return elements ? refine_elements<D>(s, *elements, o) : refine_functions<D>(s, *functions, o);
}

// An LR spline from its B-splines: local knots per direction (F, p_k + 2), coefficients (F, dim [+ 1]), gammas;
// the mesh is the union of the B-splines' knot lines (the mesh of an LR spline is determined by its B-splines
// only where it holds no line a B-spline does not use, which the constructor's checks exclude).
template <int D>
LRSpline<D> from_basis(const Ints<D>& degrees, const std::vector<Array>& knots, const Array& coefficients,
                       const std::optional<Array>& gammas, bool rational) {
  require(knots.size() == D, "LR spline: knots needs " + std::to_string(D) + " arrays, one per direction");
  require(coefficients.ndim() == 2, "LR spline: coefficients must have shape (F, dim)");
  const auto n = coefficients.shape(0);
  const int stride = static_cast<int>(coefficients.shape(1));
  require(stride >= (rational ? 2 : 1), "LR spline: coefficients need at least one value (plus the weight if rational)");
  for (int k = 0; k < D; ++k) {
    const Array& t = knots[static_cast<std::size_t>(k)];
    require(degrees[k] >= 0 && t.ndim() == 2 && t.shape(0) == n && t.shape(1) == degrees[k] + 2,
            "LR spline: knots[" + std::to_string(k) + "] must have shape (" + std::to_string(n) + ", " +
                std::to_string(degrees[k] + 2) + ")");
  }
  require(!gammas || (gammas->ndim() == 1 && gammas->shape(0) == n),
          "LR spline: gammas must have shape (" + std::to_string(n) + ",)");
  std::vector<LRBSpline<D>> basis(static_cast<std::size_t>(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    LRBSpline<D>& b = basis[static_cast<std::size_t>(i)];
    for (int k = 0; k < D; ++k) {
      const double* t = knots[static_cast<std::size_t>(k)].data() + i * (degrees[k] + 2);
      b.knots[k].assign(t, t + degrees[k] + 2);
    }
    b.gamma = gammas ? gammas->data()[i] : 1.0;
    b.coef.assign(coefficients.data() + i * stride, coefficients.data() + (i + 1) * stride);
  }
  py::gil_scoped_release release;
  auto mesh = knot_line_mesh<D>(basis);
  return LRSpline<D>(degrees, stride - (rational ? 1 : 0), rational, std::move(basis), std::move(mesh));
}

template <int D>
void bind_lr(py::module_& m, const char* name, const char* doc) {
  using S = LRSpline<D>;
  py::class_<S>(m, name, doc)
      .def(py::init<const TensorSpline<D>&>(), py::arg("spline"), "Exact conversion of a tensor spline.")
      .def(py::init(&from_basis<D>), py::arg("degrees"), py::arg("knots"), py::arg("coefficients"),
           py::arg("gammas") = py::none(), py::arg("rational") = false,
           "From raw arrays: degrees (D ints), knots (D arrays (F, p_k + 2): each B-spline's local knots),\n"
           "coefficients (F, dim), homogeneous (w x, ..., w) with rational=True, gammas (F,) scaling factors\n"
           "(default 1). The mesh is the union of the knot lines; the B-splines must sum to one with their gammas.")
      .def_property_readonly(
          "parametric_dim", [](const S&) { return D; }, "2 or 3.")
      .def_property_readonly(
          "knots",
          [](const S& s) {
            py::list out;
            for (int k = 0; k < D; ++k) {
              auto a = new_array({s.num_basis(), s.degree(k) + 2});
              double* p = a.mutable_data();
              for (const LRBSpline<D>& b : s.basis_functions()) p = std::copy(b.knots[k].begin(), b.knots[k].end(), p);
              out.append(a);
            }
            return out;
          },
          "Local knot vectors of the B-splines, one array (F, p_k + 2) per direction (a copy).")
      .def_property_readonly(
          "coefficients",
          [](const S& s) {
            auto a = new_array({s.num_basis(), s.stride()});
            double* p = a.mutable_data();
            for (const LRBSpline<D>& b : s.basis_functions()) p = std::copy(b.coef.begin(), b.coef.end(), p);
            return a;
          },
          "Coefficients (F, dim [+ 1]), homogeneous when rational (a copy).")
      .def_property_readonly("dim", &S::dim, "Control (model-space) dimension.")
      .def_property_readonly("rational", &S::is_rational, "True when the control values are homogeneous with weights.")
      .def_property_readonly("degrees", &S::degrees, "Polynomial degree per direction.")
      .def_property_readonly(
          "domain", [](const S& s) { return box_array<D>(s.domain()); }, "(D, 2) bounds.")
      .def_property_readonly("num_basis", &S::num_basis, "Number of LR B-splines.")
      .def_property_readonly("num_elements", &S::num_elements, "Number of elements of the box mesh.")
      .def_property_readonly(
          "num_meshrects", [](const S& s) { return s.mesh().size(); }, "Mesh rectangles (lines in 2-D).")
      .def_property_readonly(
          "elements",
          [](const S& s) {
            auto a = new_array({s.num_elements(), D, 2});
            double* p = a.mutable_data();
            for (const Box<D>& e : s.elements())
              for (int k = 0; k < D; ++k) {
                *p++ = e.lo[k];
                *p++ = e.hi[k];
              }
            return a;
          },
          "Element boxes (E, D, 2).")
      .def_property_readonly(
          "gammas",
          [](const S& s) {
            auto a = new_array({s.num_basis()});
            for (int i = 0; i < s.num_basis(); ++i) a.mutable_data()[i] = s.basis_function(i).gamma;
            return a;
          },
          "Scaling factors of the B-splines (they sum with the B-splines to one).")
      .def(
          "element_support",
          [](const S& s, int e) {
            require(e >= 0 && e < s.num_elements(), "element_support: no element " + std::to_string(e));
            const auto v = s.element_support(e);
            return std::vector<int>(v.begin(), v.end());
          },
          py::arg("element"), "Ids of the B-splines whose support contains the element.")
      .def("__call__", &evaluate<D>, py::arg("u"), py::arg("threads") = 0, "Values (N, dim) at parameters (N, D).")
      .def("evaluate", &evaluate<D>, py::arg("u"), py::arg("threads") = 0, "Same as calling the spline.")
      .def("derivatives", &first_derivatives<D>, py::arg("u"), py::arg("threads") = 0,
           "Value and first derivatives (N, D + 1, dim): f, f_u, f_v[, f_w].")
      .def("refine", &refine<D>, py::arg("elements") = py::none(), py::arg("functions") = py::none(),
           py::arg("strategy") = "fullspan", py::arg("multiplicity") = 1, py::arg("max_aspect_ratio") = 0.0,
           "Refines marked elements (fullspan, minspan, structured) or B-splines (structured) in one batch, as\n"
           "`trivar refine`; returns the number of mesh rectangles that changed the spline.")
      .def(
          "check_independence",
          [](const S& s, const std::string& method) {
            py::gil_scoped_release release;
            require(method == "peeling" || method == "exact",
                    "check_independence: method is peeling or exact, got " + method);
            return std::string(to_string(method == "peeling" ? peeling_test(s).status : exact_test(s).status));
          },
          py::arg("method") = "peeling",
          "Linear independence of the B-splines: 'independent', 'not_independent' or 'not_tested' (peeling\n"
          "undecided).")
      .def("__repr__", [name](const S& s) {
        std::string d;
        for (int k = 0; k < D; ++k) d += (k ? ", " : "") + std::to_string(s.degree(k));
        return std::string("<trivar.") + name + " degrees (" + d + "), " + std::to_string(s.num_basis()) +
               " B-splines, " + std::to_string(s.num_elements()) + " elements, dim " + std::to_string(s.dim()) + ">";
      });
}

}  // namespace

void bind_lr_splines(py::module_& m) {
  bind_lr<2>(m, "LRSurface", "A locally refined B-spline surface (LRSpline<2>).");
  bind_lr<3>(m, "LRVolume", "A locally refined B-spline volume (LRSpline<3>).");
}

}  // namespace trivar::python
