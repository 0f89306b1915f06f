// KnotVector: validated knot sequences with their queries.
#include "bindings.hpp"
#include "trivar/spline/knot_vector.hpp"

namespace trivar::python {

namespace {

py::array_t<double> array_of(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

}  // namespace

void bind_knot_vector(py::module_& m) {
  py::class_<KnotVector>(m, "KnotVector", "A validated non-decreasing knot sequence of a given degree.")
      .def(py::init([](int degree, const Array& knots) {
             return KnotVector(degree, std::vector<double>(knots.data(), knots.data() + knots.size()));
           }),
           py::arg("degree"), py::arg("knots"), "Raises trivar.Error naming the offending knot.")
      .def_static("open_uniform", &KnotVector::open_uniform, py::arg("degree"), py::arg("elements"), py::arg("a") = 0.0,
                  py::arg("b") = 1.0, "Clamped knots on [a, b] with `elements` equal intervals.")
      .def_property_readonly("degree", &KnotVector::degree, "Polynomial degree.")
      .def_property_readonly(
          "knots", [](const KnotVector& k) { return array_of(k.knots()); }, "The knots (a copy).")
      .def_property_readonly("size", &KnotVector::size, "Number of B-splines.")
      .def_property_readonly(
          "domain", [](const KnotVector& k) { return py::make_tuple(k.start(), k.end()); }, "(start, end).")
      .def_property_readonly(
          "breakpoints", [](const KnotVector& k) { return array_of(k.breakpoints()); },
          "Distinct knots in the domain: the element ends.")
      .def_property_readonly(
          "greville", [](const KnotVector& k) { return array_of(k.greville()); }, "Greville abscissae.")
      .def_property_readonly("num_elements", &KnotVector::num_elements, "Non-empty knot intervals in the domain.")
      .def("find_span", &KnotVector::find_span, py::arg("u"),
           "Index s with t_s <= u < t_{s+1} (the last span at the end).")
      .def("multiplicity", &KnotVector::multiplicity, py::arg("u"), "Number of knots equal to u.")
      .def("__len__", [](const KnotVector& k) { return k.knots().size(); })
      .def("__repr__", [](const KnotVector& k) {
        return "<trivar.KnotVector degree " + std::to_string(k.degree()) + ", " + std::to_string(k.knots().size()) +
               " knots, " + std::to_string(k.num_elements()) + " elements>";
      });
}

}  // namespace trivar::python
