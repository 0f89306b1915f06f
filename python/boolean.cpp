// Booleans of V-models (cad/boolean.hpp, OpenCASCADE underneath): union, difference and intersection with the
// attribute blend rules of `trivar boolean`, the result a V-model of trimmed cells and the report as a
// namespace. VModel's |, - and & operators call it with the default rules.
#include "bindings.hpp"
#include "trivar/cad/boolean.hpp"

namespace trivar::python {

namespace {

// A rule as a name ("a", "b", "average", "distance") or (name, weight formula) for "formula".
cad::AttributeRule rule_of(const py::handle& o, const std::string& weight) {
  if (py::isinstance<py::str>(o)) return {cad::blend_rule(o.cast<std::string>()), weight};
  const auto t = o.cast<std::pair<std::string, std::string>>();
  return {cad::blend_rule(t.first), t.second};
}

py::object boolean(const VModel& a, const VModel& b, const std::string& op, const py::object& rule,
                   const std::map<std::string, py::object>& rules, const std::string& weight, double tolerance,
                   double fuzzy, int field_degree, int field_elements) {
  cad::BooleanOptions o;
  o.default_rule = rule_of(rule, weight);
  for (const auto& [name, r] : rules) o.rules[name] = rule_of(r, weight);
  o.chordal_tolerance = tolerance;
  o.fuzzy = fuzzy;
  o.field = {field_degree, field_elements};
  const cad::BooleanOp which = cad::boolean_op(op);
  cad::BooleanReport r;
  VModel c;
  {
    py::gil_scoped_release release;
    c = cad::boolean(a, b, which, o, &r);
  }
  py::dict d(py::arg("model") = std::move(c), py::arg("cells_a") = r.cells_a, py::arg("cells_b") = r.cells_b,
             py::arg("pieces") = r.pieces, py::arg("pieces_a_only") = r.pieces_a_only,
             py::arg("pieces_b_only") = r.pieces_b_only, py::arg("pieces_both") = r.pieces_both,
             py::arg("cells") = r.cells, py::arg("exact_attributes") = r.exact_attributes,
             py::arg("fitted_attributes") = r.fitted_attributes, py::arg("interior_faces") = r.interior_faces,
             py::arg("boundary_faces") = r.boundary_faces, py::arg("neighbours") = r.neighbours);
  return py::module_::import("types").attr("SimpleNamespace")(**d);
}

VModel quick(const VModel& a, const VModel& b, cad::BooleanOp op) {
  py::gil_scoped_release release;
  return cad::boolean(a, b, op);
}

}  // namespace

void bind_boolean(py::module_& m) {
  m.def("boolean", &boolean, py::arg("a"), py::arg("b"), py::arg("op") = "union", py::arg("rule") = "a",
        py::arg("rules") = std::map<std::string, py::object>{}, py::arg("weight") = "", py::arg("tolerance") = 0.0,
        py::arg("fuzzy") = 1e-9, py::arg("field_degree") = 3, py::arg("field_elements") = 6,
        "Boolean of two V-models as `trivar boolean`: op 'union', 'difference' (a minus b) or 'intersection'.\n"
        "Attributes in the overlap follow `rule` ('a', 'b', 'average', 'distance', or 'formula' with `weight`, a\n"
        "formula in x, y, z: 0 gives a, 1 gives b), per attribute name in `rules` ({name: rule or (rule, weight)}).\n"
        "tolerance: chordal tolerance of the result's meshes (0: 1e-3 of the operands' diagonal); fuzzy: relative\n"
        "distance under which faces coincide; field_degree/field_elements: fitted attribute fields. Returns a\n"
        "namespace: model (trimmed cells), cells_a, cells_b, pieces, pieces_a_only, pieces_b_only, pieces_both,\n"
        "cells, exact_attributes, fitted_attributes, interior_faces, boundary_faces, neighbours.");
  auto cls = py::reinterpret_borrow<py::object>(m.attr("VModel"));
  cls.attr("__or__") = py::cpp_function([](const VModel& a, const VModel& b) { return quick(a, b, cad::BooleanOp::unite); },
                                        py::is_method(cls), "Union (trivar.boolean with the default rules).");
  cls.attr("__sub__") = py::cpp_function(
      [](const VModel& a, const VModel& b) { return quick(a, b, cad::BooleanOp::subtract); }, py::is_method(cls),
      "Difference (trivar.boolean with the default rules).");
  cls.attr("__and__") = py::cpp_function(
      [](const VModel& a, const VModel& b) { return quick(a, b, cad::BooleanOp::intersect); }, py::is_method(cls),
      "Intersection (trivar.boolean with the default rules).");
}

}  // namespace trivar::python
