#pragma once
// Poisson on planar T-meshes with star points (iga/t_mesh_space): the planar surfaces of hand-built meshes, a
// linear solution, and the manufactured solution u = sin(0.4 x) cos(0.3 y) + 0.05 x y.
#include <cmath>
#include <string>
#include <vector>

#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/solver.hpp"
#include "trivar/iga/t_mesh_space.hpp"
#include "trivar/io/tsm_format.hpp"

namespace trivar::test {

// A planar mesh from tsm_text. The generator puts the boundary's repeated-knot nodes on their vertices, which
// makes the surface's cross-boundary derivative vanish; moved outwards by one eighth of their radius (about one
// knot interval) the map is regular up to the boundary.
inline TMeshSurface planar_t_mesh(const std::string& tsm) {
  io::TsmModel m = io::parse_tsm(tsm, "planar.tsm");
  for (const TMeshVertex& v : m.mesh.vertices)
    for (int i : v.block)
      if (i >= 0)
        for (int k = 0; k < 2; ++k) m.mesh.points[static_cast<std::size_t>(i)].xyz[static_cast<std::size_t>(k)] *= 1.125;
  return TMeshSurface(m.mesh, 1);
}

// The errors of the solution of -lap u = f, u = exact on the boundary.
inline ErrorNorms poisson_errors(const MultipatchSpace<2>& space, const PoissonProblem<2>& source,
                                 const std::function<double(const double*)>& u, const ExactSolution<2>& exact) {
  PoissonProblem<2> pb = source;
  pb.dirichlet = {DirichletCondition<2>{space.boundary, {}, [&](const double* x, double* v) { v[0] = u(x); }}};
  auto solver = make_solver("cholmod");
  const SolveResult r = solve_poisson(space, pb, *solver, 1);
  return error_norms(space, r.coefs, 1, exact, 1);
}

// u = 0.3 + 0.7 x - 1.1 y (f = 0), which the space holds exactly.
inline ErrorNorms linear_solution_errors(const MultipatchSpace<2>& space) {
  return poisson_errors(space, {}, [](const double* x) { return 0.3 + 0.7 * x[0] - 1.1 * x[1]; },
                        [](const double* x, double* v, double* g) {
                          v[0] = 0.3 + 0.7 * x[0] - 1.1 * x[1];
                          g[0] = 0.7;
                          g[1] = -1.1;
                        });
}

// u = sin(0.4 x) cos(0.3 y) + 0.05 x y.
inline ErrorNorms manufactured_errors(const MultipatchSpace<2>& space) {
  PoissonProblem<2> pb;
  pb.source = [](const double* x) { return 0.25 * std::sin(0.4 * x[0]) * std::cos(0.3 * x[1]); };
  return poisson_errors(space, pb, [](const double* x) { return std::sin(0.4 * x[0]) * std::cos(0.3 * x[1]) + 0.05 * x[0] * x[1]; },
                        [](const double* x, double* v, double* g) {
                          v[0] = std::sin(0.4 * x[0]) * std::cos(0.3 * x[1]) + 0.05 * x[0] * x[1];
                          g[0] = 0.4 * std::cos(0.4 * x[0]) * std::cos(0.3 * x[1]) + 0.05 * x[1];
                          g[1] = -0.3 * std::sin(0.4 * x[0]) * std::sin(0.3 * x[1]) + 0.05 * x[0];
                        });
}

}  // namespace trivar::test
