// Isogeometric analysis from Python: Poisson, linear elasticity and eigenmodes on the built-in benchmark
// problems of `trivar solve` (exact solutions known: errors reported) or on a given volume / planar surface
// (Poisson: f = 1, u = 0 on the boundary; Laplace modes with u = 0 on the boundary). The solution comes back as
// its coefficients and as a spline field over the geometry's parameters.
#include "bindings.hpp"
#include "trivar/iga/adaptive_loop.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/lr_solution_field.hpp"
#include "trivar/iga/eigen_modes.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/solution_field.hpp"

namespace trivar::python {

namespace {

py::object namespace_of(const py::dict& d) { return py::module_::import("types").attr("SimpleNamespace")(**d); }

py::array_t<double> array_of(const Eigen::VectorXd& v) { return py::array_t<double>(v.size(), v.data()); }

// Solves one static problem on one patch and reports as `trivar solve` does.
template <int D>
py::object static_result(const MultipatchSpace<D>& space, int components, const ExactSolution<D>& exact,
                         const std::function<SolveResult(LinearSolver&)>& run, const std::string& solver, int threads) {
  SolveResult r;
  ErrorNorms e;
  TensorSpline<D> field;
  {
    py::gil_scoped_release release;
    auto s = make_solver(solver);
    r = run(*s);
    if (exact) e = error_norms(space, r.coefs, components, exact, threads);
    field = solution_field(space.patches.front(), patch_coefs(space, 0, r.coefs, components), components);
  }
  py::dict d(py::arg("dofs") = r.dofs, py::arg("coefficients") = array_of(r.coefs), py::arg("field") = field,
             py::arg("geometry") = space.patches.front().geometry, py::arg("assembly_seconds") = r.assembly_seconds,
             py::arg("solve_seconds") = r.solve_seconds, py::arg("iterations") = r.stats.iterations);
  d["l2_error"] = exact ? py::object(py::float_(e.l2)) : py::none();
  d["h1_error"] = exact ? py::object(py::float_(e.h1)) : py::none();
  return namespace_of(d);
}

template <int D>
py::object poisson(const MultipatchSpace<D>& space, const PoissonProblem<D>& pb, const ExactSolution<D>& exact,
                   const std::string& solver, int threads) {
  return static_result<D>(
      space, 1, exact, [&](LinearSolver& s) { return solve_poisson(space, pb, s, threads); }, solver, threads);
}

template <int D>
py::object poisson_on(const TensorSpline<D>& geometry, int degree, int refine, const std::string& solver, int threads) {
  const MultipatchSpace<D> space = single_patch_space(make_tensor_space(geometry, degree, refine));
  PoissonProblem<D> pb;
  pb.source = [](const double*) { return 1.0; };
  pb.dirichlet.push_back({space.boundary, {}, nullptr});
  return poisson<D>(space, pb, nullptr, solver, threads);
}

// -lap u = 1 on the cells of a glued model as one multipatch space (shared faces numbered once), u = 0 on its
// boundary; the solution as one field per cell.
py::object poisson_on_model(const VModel& model, int degree, int refine, const std::string& solver, int threads) {
  for (const VCell& c : model.cells())
    require(!c.is_trimmed(), "solve_poisson_on: analysis on trimmed cells is not supported");
  const MultipatchSpace<3> space = multipatch_space(model, degree, refine);
  PoissonProblem<3> pb;
  pb.source = [](const double*) { return 1.0; };
  pb.dirichlet.push_back({space.boundary, {}, nullptr});
  SolveResult r;
  std::vector<SplineVolume> fields;
  {
    py::gil_scoped_release release;
    auto s = make_solver(solver);
    r = solve_poisson(space, pb, *s, threads);
    fields = solution_fields(space, r.coefs, 1);
  }
  return namespace_of(py::dict(py::arg("dofs") = r.dofs, py::arg("coefficients") = array_of(r.coefs),
                               py::arg("fields") = fields, py::arg("assembly_seconds") = r.assembly_seconds,
                               py::arg("solve_seconds") = r.solve_seconds, py::arg("iterations") = r.stats.iterations));
}

template <int D>
py::object elasticity(const ElasticityBenchmark<D>& b, const std::string& solver, int threads) {
  const MultipatchSpace<D> space = single_patch_space(b.space);
  return static_result<D>(
      space, D, b.exact, [&](LinearSolver& s) { return solve_elasticity(space, b.problem, s, threads); }, solver,
      threads);
}

// Linear elasticity on one patch: clamped on the given parametric faces (direction, side), under a body force.
template <int D>
py::object elasticity_on(const TensorSpline<D>& geometry, const std::vector<std::pair<int, int>>& clamp,
                         const std::vector<double>& body_force, int degree, int refine, double youngs,
                         double poisson_ratio, const std::string& solver, int threads) {
  require(static_cast<int>(body_force.size()) == D,
          "solve_elasticity_on: body_force needs " + std::to_string(D) + " values");
  require(!clamp.empty(), "solve_elasticity_on: static elasticity needs supports (clamp)");
  const MultipatchSpace<D> space = single_patch_space(make_tensor_space(geometry, degree, refine));
  ElasticityProblem<D> pb;
  pb.material = {youngs, poisson_ratio, 1.0};
  require(pb.material.valid(), "solve_elasticity_on: youngs must be positive, poisson_ratio in (-1, 0.5)");
  std::vector<Face> faces;
  for (const auto& [dir, side] : clamp) {
    require(dir >= 0 && dir < D && (side == 0 || side == 1),
            "solve_elasticity_on: a clamped face is (direction 0.." + std::to_string(D - 1) + ", side 0 or 1)");
    faces.push_back({dir, side, 0});
  }
  pb.displacement.push_back({faces, {}, nullptr});
  pb.body_force = [body_force](const double*, double* b) { std::copy(body_force.begin(), body_force.end(), b); };
  return static_result<D>(
      space, D, nullptr, [&](LinearSolver& s) { return solve_elasticity(space, pb, s, threads); }, solver, threads);
}

// Adaptive refinement (solve, estimate, mark by Dorfler, refine) from a benchmark's tensor space on an LR, HB or
// THB space, as `trivar solve poisson --adaptive`: the table of steps and, on LR, the final mesh and solution.
template <int D>
py::object adaptive(const PoissonBenchmark<D>& b, int steps, double beta, const std::string& space,
                    const std::string& solver, int threads) {
  require(space == "lr" || space == "hb" || space == "thb",
          "solve_poisson_adaptive: space is lr, hb or thb, got " + space);
  AdaptiveOptions o;
  o.steps = steps;
  o.beta = beta;
  o.solver = solver;
  std::vector<ConvergenceRow> rows;
  Eigen::VectorXd coefs;
  std::optional<LRSpline<D>> lr;
  std::optional<LRSpline<D>> field;
  {
    py::gil_scoped_release release;
    if (space == "lr") {
      lr.emplace(b.space.geometry);
      rows = adaptive_poisson<D>(*lr, b.problem, b.exact, o, {}, &coefs, threads);
      field.emplace(lr_solution_field(*lr, coefs));
    } else {
      HierarchicalSpline<D> h(b.space.geometry, space == "hb" ? HierarchicalBasis::hb : HierarchicalBasis::thb);
      rows = adaptive_poisson<D>(h, b.problem, b.exact, o, {}, &coefs, threads);
    }
  }
  const auto n = static_cast<py::ssize_t>(rows.size());
  py::array_t<int> dofs(n), elements(n);
  auto l2 = new_array({n}), h1 = new_array({n}), estimate = new_array({n});
  for (std::size_t i = 0; i < rows.size(); ++i) {
    dofs.mutable_data()[i] = rows[i].dofs;
    elements.mutable_data()[i] = rows[i].elements;
    l2.mutable_data()[i] = rows[i].l2;
    h1.mutable_data()[i] = rows[i].h1;
    estimate.mutable_data()[i] = rows[i].estimate;
  }
  py::dict d(py::arg("dofs") = dofs, py::arg("elements") = elements, py::arg("l2_error") = l2, py::arg("h1_error") = h1,
             py::arg("estimate") = estimate, py::arg("coefficients") = array_of(coefs));
  d["geometry"] = lr ? py::cast(*lr) : py::none();
  d["field"] = field ? py::cast(*field) : py::none();
  return namespace_of(d);
}

MultipatchSpace<3> unit_cube(int degree, int elements) {
  return single_patch_space(TensorSpace<3>{box_geometry<3>({0, 0, 0}, {1, 1, 1}, degree, elements)});
}

}  // namespace

py::object modes_result(const ModesResult& r, const std::vector<double>& exact) {
  py::dict d(py::arg("values") = array_of(r.values), py::arg("dofs") = r.dofs,
             py::arg("assembly_seconds") = r.assembly_seconds, py::arg("solve_seconds") = r.solve_seconds);
  d["exact"] = exact.empty() ? py::object(py::none())
                             : py::object(py::array_t<double>(static_cast<py::ssize_t>(exact.size()), exact.data()));
  auto vectors = new_array({r.vectors.cols(), r.vectors.rows()});
  for (Eigen::Index c = 0; c < r.vectors.cols(); ++c)
    std::copy_n(r.vectors.col(c).data(), r.vectors.rows(), vectors.mutable_data() + c * r.vectors.rows());
  d["vectors"] = vectors;
  return namespace_of(d);
}

void bind_solve(py::module_& m) {
  m.def(
      "solve_poisson",
      [](const std::string& problem, int degree, int refine, const std::string& solver, int threads) {
        if (problem == "sine-cube") {
          const auto b = sine_box<3>(degree, refine);
          return poisson<3>(single_patch_space(b.space), b.problem, b.exact, solver, threads);
        }
        if (problem == "sine-square") {
          const auto b = sine_box<2>(degree, refine);
          return poisson<2>(single_patch_space(b.space), b.problem, b.exact, solver, threads);
        }
        require(problem == "l-shape",
                "solve_poisson: unknown problem '" + problem + "' (sine-cube, sine-square, l-shape)");
        const auto b = l_shape(degree, refine);
        return poisson<2>(single_patch_space(b.space), b.problem, b.exact, solver, threads);
      },
      py::arg("problem") = "sine-cube", py::arg("degree") = 2, py::arg("refine") = 8, py::arg("solver") = "cg",
      py::arg("threads") = 0,
      "Poisson benchmark of `trivar solve poisson --problem`: returns dofs, l2_error, h1_error, coefficients,\n"
      "field (the solution as a spline over the parameters: field(u)), geometry, timings.");
  m.def(
      "solve_poisson_on", &poisson_on<3>, py::arg("geometry"), py::arg("degree") = 2, py::arg("refine") = 8,
      py::arg("solver") = "cg", py::arg("threads") = 0,
      "-lap u = 1 on a volume with u = 0 on its boundary (degree raised to `degree`, elements split `refine` times).");
  m.def("solve_poisson_on", &poisson_on<2>, py::arg("geometry"), py::arg("degree") = 2, py::arg("refine") = 8,
        py::arg("solver") = "cg", py::arg("threads") = 0, "The same on a planar surface (control dimension 2).");
  m.def("solve_poisson_on", &poisson_on_model, py::arg("model"), py::arg("degree") = 2, py::arg("refine") = 8,
        py::arg("solver") = "cg", py::arg("threads") = 0,
        "The same on a glued V-model (one multipatch space, shared faces numbered once): one field per cell.");
  m.def(
      "solve_elasticity",
      [](const std::string& problem, int degree, int refine, const std::string& solver, int threads) {
        if (problem == "lame-cylinder") return elasticity<3>(lame_cylinder<3>(degree, refine), solver, threads);
        if (problem == "lame-ring") return elasticity<2>(lame_cylinder<2>(degree, refine), solver, threads);
        require(problem == "plate-hole",
                "solve_elasticity: unknown problem '" + problem + "' (lame-cylinder, lame-ring, plate-hole)");
        return elasticity<2>(plate_with_hole(degree, refine), solver, threads);
      },
      py::arg("problem") = "lame-cylinder", py::arg("degree") = 2, py::arg("refine") = 8, py::arg("solver") = "cg",
      py::arg("threads") = 0,
      "Linear elasticity benchmark of `trivar solve elasticity --problem`: displacement field (dim = D) and\n"
      "errors against the exact solution.");
  m.def("solve_elasticity_on", &elasticity_on<3>, py::arg("geometry"),
        py::arg("clamp") = std::vector<std::pair<int, int>>{{0, 0}},
        py::arg("body_force") = std::vector<double>{0, 0, -1}, py::arg("degree") = 2, py::arg("refine") = 8,
        py::arg("youngs") = 1000.0, py::arg("poisson_ratio") = 0.3, py::arg("solver") = "cg", py::arg("threads") = 0,
        "Linear elasticity on a volume clamped on the parametric faces `clamp` [(direction, side), ...] (default\n"
        "u = 0) under a constant body force (default: unit along -z, as `trivar solve elasticity`).");
  m.def("solve_elasticity_on", &elasticity_on<2>, py::arg("geometry"),
        py::arg("clamp") = std::vector<std::pair<int, int>>{{0, 0}}, py::arg("body_force") = std::vector<double>{0, -1},
        py::arg("degree") = 2, py::arg("refine") = 8, py::arg("youngs") = 1000.0, py::arg("poisson_ratio") = 0.3,
        py::arg("solver") = "cg", py::arg("threads") = 0, "The same on a planar surface (plane strain).");
  m.def(
      "solve_poisson_adaptive",
      [](const std::string& problem, int degree, int refine, int steps, double beta, const std::string& space,
         const std::string& solver, int threads) {
        if (problem == "sine-cube")
          return adaptive<3>(sine_box<3>(degree, refine), steps, beta, space, solver, threads);
        if (problem == "sine-square")
          return adaptive<2>(sine_box<2>(degree, refine), steps, beta, space, solver, threads);
        require(problem == "l-shape",
                "solve_poisson_adaptive: unknown problem '" + problem + "' (l-shape, sine-square, sine-cube)");
        return adaptive<2>(l_shape(degree, refine), steps, beta, space, solver, threads);
      },
      py::arg("problem") = "l-shape", py::arg("degree") = 2, py::arg("refine") = 8, py::arg("steps") = 5,
      py::arg("beta") = 0.3, py::arg("space") = "lr", py::arg("solver") = "cg", py::arg("threads") = 0,
      "Adaptive refinement as `trivar solve poisson --adaptive`: per step dofs, elements, l2_error, h1_error,\n"
      "estimate (arrays); on LR (space='lr') the final geometry and the solution `field` as LR splines.");
  m.def(
      "solve_modes",
      [](const std::string& problem, int degree, int refine, int modes, double youngs, double poisson_ratio,
         double density, int threads) {
        const MultipatchSpace<3> space = unit_cube(degree, refine);
        ModesResult r;
        std::vector<double> exact;
        if (problem == "cube-modes") {
          exact = unit_box_laplace_eigenvalues(3, modes);
          py::gil_scoped_release release;
          r = laplace_modes(space, space.boundary, modes, threads);
        } else {
          require(problem == "elastic-cube-modes",
                  "solve_modes: unknown problem '" + problem + "' (cube-modes, elastic-cube-modes)");
          const ElasticMaterial mat{youngs, poisson_ratio, density};
          require(mat.valid(), "solve_modes: youngs and density must be positive, poisson_ratio in (-1, 0.5)");
          ElasticityProblem<3> pb;
          pb.material = mat;
          for (const Face& f : space.boundary) pb.displacement.push_back({{f}, {f.dir}, nullptr});
          exact = roller_cube_eigenvalues(mat, modes);
          py::gil_scoped_release release;
          r = elastic_modes(space, pb, modes, threads);
        }
        return modes_result(r, exact);
      },
      py::arg("problem") = "cube-modes", py::arg("degree") = 2, py::arg("refine") = 8, py::arg("modes") = 4,
      py::arg("youngs") = 1000.0, py::arg("poisson_ratio") = 0.3, py::arg("density") = 1.0, py::arg("threads") = 0,
      "Eigenvalues of `trivar solve modes --problem`: values (ascending), exact, dofs, vectors (modes, dofs).");
  m.def(
      "laplace_modes_on",
      [](const SplineVolume& geometry, int degree, int refine, int modes, int threads) {
        const MultipatchSpace<3> space = single_patch_space(make_tensor_space(geometry, degree, refine));
        ModesResult r;
        {
          py::gil_scoped_release release;
          r = laplace_modes(space, space.boundary, modes, threads);
        }
        return modes_result(r, {});
      },
      py::arg("geometry"), py::arg("degree") = 2, py::arg("refine") = 8, py::arg("modes") = 4, py::arg("threads") = 0,
      "Dirichlet Laplace eigenvalues on a volume.");
}

}  // namespace trivar::python
