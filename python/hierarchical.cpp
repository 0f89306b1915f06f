// HierarchicalSurface, HierarchicalVolume: hierarchical B-splines with the HB or the truncated (THB) basis
// (HierarchicalSpline<2, 3>), from tensor splines or G+Smo .xml files: refinement of marked elements or
// functions keeping the spline exactly, evaluation on NumPy batches, the basis change HB <-> THB.
#include "bindings.hpp"
#include "trivar/hier/hierarchical_spline.hpp"

namespace trivar::python {

namespace {

HierarchicalBasis basis_of(const std::string& name) {
  require(name == "hb" || name == "thb", "basis: hb or thb, got '" + name + "'");
  return name == "hb" ? HierarchicalBasis::hb : HierarchicalBasis::thb;
}

template <int D>
py::array evaluate(const HierarchicalSpline<D>& s, const Array& u, int threads) {
  return evaluate_batch<D>(u, s.dim(), [&](auto params, auto out) { s.eval_many(params, out, threads); });
}

template <int D>
py::array first_derivatives(const HierarchicalSpline<D>& s, const Array& u) {
  bool single = false;
  const auto params = params_of<D>(u, single);
  const auto n = static_cast<py::ssize_t>(params.size());
  auto out = new_array({n, D + 1, s.dim()});
  {
    py::gil_scoped_release release;
    const std::size_t block = static_cast<std::size_t>((D + 1) * s.dim());
    for (std::size_t i = 0; i < params.size(); ++i) s.eval_first_derivatives(params[i], out.mutable_data() + i * block);
  }
  if (single) return out.attr("reshape")(D + 1, s.dim());
  return out;
}

template <int D>
int refine(HierarchicalSpline<D>& s, const std::optional<std::vector<int>>& elements,
           const std::optional<std::vector<int>>& functions, int admissible) {
  require(elements.has_value() != functions.has_value(), "refine: give either elements or functions");
  require(admissible >= 0, "refine: admissible is a class m >= 2, or 0 for none");
  const std::vector<int>& ids = elements ? *elements : *functions;
  const int count = elements ? s.space().num_elements() : s.space().num_basis();
  for (int i : ids)
    require(i >= 0 && i < count,
            std::string("refine: no ") + (elements ? "element " : "function ") + std::to_string(i) + " (of " +
                std::to_string(count) + ")");
  require(admissible == 0 || elements.has_value(), "refine: admissible refinement marks elements");
  py::gil_scoped_release release;
  if (functions) return s.refine_functions(*functions);
  return admissible > 0 ? s.refine_elements_admissible(*elements, admissible) : s.refine_elements(*elements);
}

template <int D>
void bind_hierarchical(py::module_& m, const char* name, const char* doc) {
  using S = HierarchicalSpline<D>;
  py::class_<S>(m, name, doc)
      .def(py::init([](const TensorSpline<D>& s, const std::string& basis) { return S(s, basis_of(basis)); }),
           py::arg("spline"), py::arg("basis") = "thb",
           "Exact conversion of a tensor spline (its knots are level 0, dyadic levels follow); basis 'thb' or 'hb'.")
      .def_property_readonly(
          "parametric_dim", [](const S&) { return D; }, "2 or 3.")
      .def_property_readonly(
          "basis", [](const S& s) { return std::string(to_string(s.space().basis())); }, "'hb' or 'thb'.")
      .def_property_readonly("dim", &S::dim, "Control (model-space) dimension.")
      .def_property_readonly("rational", &S::is_rational, "True when the coefficients are homogeneous with weights.")
      .def_property_readonly(
          "degrees", [](const S& s) { return s.space().degrees(); }, "Polynomial degree per direction.")
      .def_property_readonly(
          "domain", [](const S& s) { return box_array<D>(s.domain()); }, "(D, 2) bounds.")
      .def_property_readonly(
          "num_levels", [](const S& s) { return s.space().num_levels(); }, "Levels of the hierarchy in use.")
      .def_property_readonly(
          "num_basis", [](const S& s) { return s.space().num_basis(); }, "Active functions over all levels.")
      .def_property_readonly(
          "num_basis_per_level",
          [](const S& s) {
            std::vector<int> n;
            for (int l = 0; l < s.space().num_levels(); ++l) n.push_back(s.space().num_basis(l));
            return n;
          },
          "Active functions of each level (functions are numbered by level).")
      .def_property_readonly(
          "num_elements", [](const S& s) { return s.space().num_elements(); }, "Leaf elements.")
      .def_property_readonly(
          "elements",
          [](const S& s) {
            const auto boxes = s.space().element_boxes();
            auto a = new_array({static_cast<py::ssize_t>(boxes.size()), D, 2});
            double* p = a.mutable_data();
            for (const Box<D>& e : boxes)
              for (int k = 0; k < D; ++k) *p++ = e.lo[k], *p++ = e.hi[k];
            return a;
          },
          "Leaf element boxes (E, D, 2).")
      .def_property_readonly(
          "element_levels",
          [](const S& s) {
            py::array_t<int> a(s.space().num_elements());
            for (int e = 0; e < s.space().num_elements(); ++e) a.mutable_data()[e] = s.space().element(e).level;
            return a;
          },
          "Level of every leaf element (E,).")
      .def_property_readonly(
          "coefficients",
          [](const S& s) {
            auto a = new_array({s.space().num_basis(), s.stride()});
            std::copy(s.coefs().begin(), s.coefs().end(), a.mutable_data());
            return a;
          },
          "Coefficients (N, dim [+ 1]), homogeneous (w x, ..., w) when rational; a copy.")
      .def("__call__", &evaluate<D>, py::arg("u"), py::arg("threads") = 0, "Values (N, dim) at parameters (N, D).")
      .def("evaluate", &evaluate<D>, py::arg("u"), py::arg("threads") = 0, "Same as calling the spline.")
      .def("derivatives", &first_derivatives<D>, py::arg("u"),
           "Value and first derivatives (N, D + 1, dim): f, f_u, f_v[, f_w].")
      .def("refine", &refine<D>, py::arg("elements") = py::none(), py::arg("functions") = py::none(),
           py::arg("admissible") = 0,
           "Refines marked leaf elements (dyadically, one level down) or the supports of marked functions,\n"
           "keeping the spline exactly; admissible = m >= 2 adds the elements that keep the mesh admissible of\n"
           "class m (Buffa and Giannelli). Returns the number of cells refined.")
      .def(
          "with_basis", [](const S& s, const std::string& basis) { return s.with_basis(basis_of(basis)); },
          py::arg("basis"), "The same spline in the other basis ('hb' or 'thb') over the same hierarchy.")
      .def("__repr__", [name](const S& s) {
        std::string d;
        for (int k = 0; k < D; ++k) d += (k ? ", " : "") + std::to_string(s.space().degree(k));
        return std::string("<trivar.") + name + " " + to_string(s.space().basis()) + ", degrees (" + d + "), " +
               std::to_string(s.space().num_levels()) + " levels, " + std::to_string(s.space().num_basis()) +
               " functions, " + std::to_string(s.space().num_elements()) + " elements, dim " +
               std::to_string(s.dim()) + ">";
      });
}

}  // namespace

void bind_hierarchical(py::module_& m) {
  bind_hierarchical<2>(m, "HierarchicalSurface", "A hierarchical B-spline surface, HB or THB basis (HierarchicalSpline<2>).");
  bind_hierarchical<3>(m, "HierarchicalVolume", "A hierarchical B-spline volume, HB or THB basis (HierarchicalSpline<3>).");
}

}  // namespace trivar::python
