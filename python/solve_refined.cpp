// Poisson on locally refined geometries, as `trivar solve poisson FILE` reads them: LR splines, HB/THB splines
// and planar T-splines (their Bezier extraction as the analysis space), -lap u = 1 with u = 0 on the boundary
// of the parameter domain. The solution comes back as a spline of the same kind over the same parameters.
#include "bindings.hpp"
#include "t_spline_object.hpp"
#include "trivar/iga/lr_solution_field.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/refined_space.hpp"
#include "trivar/iga/solver.hpp"
#include "trivar/iga/tensor_space.hpp"

namespace trivar::python {

namespace {

template <int D>
SolveResult unit_source(const RefinedSpace<D>& space, const std::string& solver, int threads) {
  PoissonProblem<D> pb;
  pb.source = [](const double*) { return 1.0; };
  pb.dirichlet.push_back({all_faces<D>(), {}, nullptr});
  auto s = make_solver(solver);
  return solve_poisson(space, pb, *s, threads);
}

py::object result(const SolveResult& r, py::object field) {
  py::dict d(py::arg("dofs") = r.dofs,
             py::arg("coefficients") = py::array_t<double>(r.coefs.size(), r.coefs.data()),
             py::arg("field") = std::move(field), py::arg("assembly_seconds") = r.assembly_seconds,
             py::arg("solve_seconds") = r.solve_seconds, py::arg("iterations") = r.stats.iterations);
  return py::module_::import("types").attr("SimpleNamespace")(**d);
}

template <int D>
py::object on_lr(const LRSpline<D>& geometry, const std::string& solver, int threads) {
  SolveResult r;
  std::optional<LRSpline<D>> field;
  {
    py::gil_scoped_release release;
    r = unit_source<D>(refined_space(geometry, threads), solver, threads);
    field.emplace(lr_solution_field(geometry, r.coefs));
  }
  return result(r, py::cast(std::move(*field)));
}

template <int D>
py::object on_hierarchical(const HierarchicalSpline<D>& geometry, const std::string& solver, int threads) {
  SolveResult r;
  std::optional<HierarchicalSpline<D>> field;
  {
    py::gil_scoped_release release;
    r = unit_source<D>(refined_space(geometry, threads), solver, threads);
    field.emplace(geometry.space(), 1, false, std::vector<double>(r.coefs.data(), r.coefs.data() + r.coefs.size()));
  }
  return result(r, py::cast(std::move(*field)));
}

// The field is the surface (x, y, u) on the same blending functions, as `trivar solve` writes it.
py::object on_t_spline(const PyTSpline& t, const std::string& solver, int threads) {
  const TSplineSurface& surf = t.spline("solve_poisson_on");
  SolveResult r;
  PyTSpline field;
  {
    py::gil_scoped_release release;
    r = unit_source<2>(refined_space(surf, threads), solver, threads);
    std::vector<LRBSpline<2>> basis(surf.basis().begin(), surf.basis().end());
    for (std::size_t i = 0; i < basis.size(); ++i) basis[i].coef[2] = r.coefs[static_cast<Eigen::Index>(i)];
    field.format = "Poisson solution (x, y, u)";
    field.surface = std::make_shared<const TSplineSurface>(surf.degrees(), std::move(basis), threads);
  }
  return result(r, py::cast(std::move(field)));
}

}  // namespace

void bind_solve_refined(py::module_& m) {
  const char* doc =
      "-lap u = 1 with u = 0 on the boundary on a locally refined geometry (its own space, as `trivar solve\n"
      "poisson FILE`): returns dofs, coefficients, field (the solution as a spline of the same kind over the\n"
      "same parameters; a T-spline's field is the surface (x, y, u)), timings.";
  m.def("solve_poisson_on", &on_lr<2>, py::arg("geometry"), py::arg("solver") = "cg", py::arg("threads") = 0, doc);
  m.def("solve_poisson_on", &on_lr<3>, py::arg("geometry"), py::arg("solver") = "cg", py::arg("threads") = 0,
        "The same on an LR volume.");
  m.def("solve_poisson_on", &on_hierarchical<2>, py::arg("geometry"), py::arg("solver") = "cg", py::arg("threads") = 0,
        "The same on a planar HB/THB surface.");
  m.def("solve_poisson_on", &on_hierarchical<3>, py::arg("geometry"), py::arg("solver") = "cg", py::arg("threads") = 0,
        "The same on an HB/THB volume.");
  m.def("solve_poisson_on", &on_t_spline, py::arg("geometry"), py::arg("solver") = "cg", py::arg("threads") = 0,
        "The same on a planar T-spline (z = 0, weights 1, blending functions summing to one).");
}

}  // namespace trivar::python
