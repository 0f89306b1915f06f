// Linear elasticity and eigenmodes on glued V-models (one multipatch space, shared faces numbered once, the
// materials from the cells' youngs_modulus / poisson_ratio / density attributes over the defaults) and
// eigenmodes on single volumes and planar surfaces, as `trivar solve elasticity|modes FILE`: supports on the
// boundary faces in one side plane of the bounding box ("x-", ...), a unit body force along -z (-y in 2-D).
#include "bindings.hpp"
#include "trivar/iga/cell_materials.hpp"
#include "trivar/iga/eigen_modes.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/side_faces.hpp"
#include "trivar/iga/solution_field.hpp"

namespace trivar::python {

namespace {

MultipatchSpace<3> model_space(const VModel& model, int degree, int refine, const char* what) {
  for (const VCell& c : model.cells())
    require(!c.is_trimmed(), std::string(what) + ": analysis on trimmed cells is not supported here");
  require(model.is_glued(), std::string(what) + ": the model is not glued (call glue())");
  return multipatch_space(model, degree, refine);
}

template <int D>
ElasticityProblem<D> elastic_problem(const MultipatchSpace<D>& space, const std::function<ElasticMaterial(int, const double*)>& at,
                                     const std::string& clamp, double youngs, double poisson_ratio, double density,
                                     const char* what) {
  ElasticityProblem<D> pb;
  pb.material = {youngs, poisson_ratio, density};
  require(pb.material.valid(),
          std::string(what) + ": youngs and density must be positive, poisson_ratio in (-1, 0.5)");
  pb.material_at = at;
  if (clamp != "none") pb.displacement.push_back({faces_in_side_plane(space, clamp), {}, nullptr});
  return pb;
}

py::object elasticity_on_model(const VModel& model, const std::string& clamp, const std::vector<double>& body_force,
                               int degree, int refine, double youngs, double poisson_ratio, double density,
                               const std::string& solver, int threads) {
  require(body_force.size() == 3, "solve_elasticity_on: body_force needs 3 values");
  require(clamp != "none", "solve_elasticity_on: static elasticity needs supports (clamp)");
  const MultipatchSpace<3> space = model_space(model, degree, refine, "solve_elasticity_on");
  ElasticityProblem<3> pb = elastic_problem<3>(space, cell_materials(model, {youngs, poisson_ratio, density}), clamp,
                                               youngs, poisson_ratio, density, "solve_elasticity_on");
  pb.body_force = [body_force](const double*, double* b) { std::copy(body_force.begin(), body_force.end(), b); };
  SolveResult r;
  std::vector<SplineVolume> fields;
  {
    py::gil_scoped_release release;
    auto s = make_solver(solver);
    r = solve_elasticity(space, pb, *s, threads);
    fields = solution_fields(space, r.coefs, 3);
  }
  py::dict d(py::arg("dofs") = r.dofs,
             py::arg("coefficients") = py::array_t<double>(r.coefs.size(), r.coefs.data()),
             py::arg("fields") = fields, py::arg("assembly_seconds") = r.assembly_seconds,
             py::arg("solve_seconds") = r.solve_seconds, py::arg("iterations") = r.stats.iterations);
  return py::module_::import("types").attr("SimpleNamespace")(**d);
}

template <int D>
py::object modes_on_space(const MultipatchSpace<D>& space, const std::function<ElasticMaterial(int, const double*)>& at,
                          const std::string& physics, const std::string& clamp, int modes, double youngs,
                          double poisson_ratio, double density, int threads) {
  require(physics == "laplace" || physics == "elastic",
          "solve_modes_on: physics is laplace or elastic, got '" + physics + "'");
  ModesResult r;
  if (physics == "laplace") {
    py::gil_scoped_release release;
    r = laplace_modes(space, space.boundary, modes, threads);
  } else {
    const ElasticityProblem<D> pb =
        elastic_problem<D>(space, at, clamp, youngs, poisson_ratio, density, "solve_modes_on");
    py::gil_scoped_release release;
    r = elastic_modes(space, pb, modes, threads);
  }
  return modes_result(r, {});
}

template <int D>
py::object modes_on_spline(const TensorSpline<D>& geometry, const std::string& physics, const std::string& clamp,
                           int modes, int degree, int refine, double youngs, double poisson_ratio, double density,
                           int threads) {
  const MultipatchSpace<D> space = single_patch_space(make_tensor_space(geometry, degree, refine));
  return modes_on_space<D>(space, nullptr, physics, clamp, modes, youngs, poisson_ratio, density, threads);
}

py::object modes_on_model(const VModel& model, const std::string& physics, const std::string& clamp, int modes,
                          int degree, int refine, double youngs, double poisson_ratio, double density, int threads) {
  const MultipatchSpace<3> space = model_space(model, degree, refine, "solve_modes_on");
  return modes_on_space<3>(space, cell_materials(model, {youngs, poisson_ratio, density}), physics, clamp, modes,
                           youngs, poisson_ratio, density, threads);
}

}  // namespace

void bind_solve_model(py::module_& m) {
  m.def("solve_elasticity_on", &elasticity_on_model, py::arg("model"), py::arg("clamp") = "x-",
        py::arg("body_force") = std::vector<double>{0, 0, -1}, py::arg("degree") = 2, py::arg("refine") = 8,
        py::arg("youngs") = 1000.0, py::arg("poisson_ratio") = 0.3, py::arg("density") = 1.0,
        py::arg("solver") = "cg", py::arg("threads") = 0,
        "Linear elasticity on a glued V-model as `trivar solve elasticity model.json`: one multipatch space,\n"
        "cell materials from the attributes youngs_modulus, poisson_ratio, density (constants or formulas in x,\n"
        "y, z) over youngs / poisson_ratio / density, clamped on the boundary faces in the side plane `clamp`\n"
        "('x-' is x = min x, ... 'z+'), under a constant body force. Returns dofs, coefficients (component-major),\n"
        "fields (one displacement volume per cell, dim 3), timings.");
  const char* doc =
      "Lowest eigenpairs as `trivar solve modes FILE`: physics 'laplace' (u = 0 on the boundary) or 'elastic'\n"
      "(free vibration, clamped on the side plane `clamp`, or 'none' for a free body: six zero modes in 3-D).\n"
      "Returns values (ascending; omega^2 for elastic), dofs, vectors (modes, dofs), timings.";
  m.def("solve_modes_on", &modes_on_model, py::arg("model"), py::arg("physics") = "laplace", py::arg("clamp") = "x-",
        py::arg("modes") = 4, py::arg("degree") = 2, py::arg("refine") = 8, py::arg("youngs") = 1000.0,
        py::arg("poisson_ratio") = 0.3, py::arg("density") = 1.0, py::arg("threads") = 0, doc);
  m.def("solve_modes_on", &modes_on_spline<3>, py::arg("geometry"), py::arg("physics") = "laplace",
        py::arg("clamp") = "x-", py::arg("modes") = 4, py::arg("degree") = 2, py::arg("refine") = 8,
        py::arg("youngs") = 1000.0, py::arg("poisson_ratio") = 0.3, py::arg("density") = 1.0, py::arg("threads") = 0,
        "The same on one volume.");
  m.def("solve_modes_on", &modes_on_spline<2>, py::arg("geometry"), py::arg("physics") = "laplace",
        py::arg("clamp") = "x-", py::arg("modes") = 4, py::arg("degree") = 2, py::arg("refine") = 8,
        py::arg("youngs") = 1000.0, py::arg("poisson_ratio") = 0.3, py::arg("density") = 1.0, py::arg("threads") = 0,
        "The same on a planar surface (plane strain).");
}

}  // namespace trivar::python
