#pragma once
// The Laplace-Beltrami problem on a curved T-mesh surface (t_mesh_surface_space):
//   -div_S(grad_S u) + c u = f - div_S g   on the surface S,   u = 0 on its boundary (if it has one),
// in weak form: integral of grad_S u . grad_S v + c u v = integral of f v + g . grad_S v, over the patches in
// space (isoparametric: the basis of each patch, the surface as the patch's map of its parameters, with metric
// G = J^T J, area element sqrt(det G), grad_S v = J G^-1 grad_(u,v) v). g is an ambient vector field whose
// tangential part counts. On a closed surface c > 0 makes the problem definite.
#include <functional>

#include <Eigen/Core>

#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/solver.hpp"
#include "trivar/iga/t_mesh_space.hpp"

namespace trivar {

struct SurfacePoissonProblem {
  double reaction = 0;                                          // c >= 0
  std::function<double(const double* x)> source;                // f (null: 0)
  std::function<void(const double* x, double* g)> flux_source;  // g, 3 values (null: 0)
};

struct SurfacePoissonResult {
  Eigen::VectorXd coefs;  // per global function (0 on the boundary)
  int dofs = 0;           // unknowns after the boundary's
  double area = 0;        // of the surface, by the same quadrature
};

// Throws trivar::Error when the surface is closed and c = 0 (u is determined only up to a constant) or a
// quadrature point has a singular metric.
SurfacePoissonResult solve_surface_poisson(const TMeshSurfaceSpace& space, const SurfacePoissonProblem& problem,
                                           LinearSolver& solver);

// L2 and H1-seminorm (surface gradient) errors against an exact solution given in space (value and ambient
// gradient; the tangential part of the gradient is compared).
ErrorNorms surface_error_norms(const TMeshSurfaceSpace& space, const Eigen::VectorXd& coefs, const ExactSolution<3>& exact);

}  // namespace trivar
