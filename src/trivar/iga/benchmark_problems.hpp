#pragma once
// Built-in problems with known exact solutions, used by `trivar solve`, the tests and the benchmarks.
#include <string>
#include <vector>

#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/tensor_space.hpp"

namespace trivar {

template <int D>
struct PoissonBenchmark {
  TensorSpace<D> space;
  PoissonProblem<D> problem;
  ExactSolution<D> exact;
};

// sine-cube (D = 3) and its 2-D analogue: unit box, u = prod_k sin(pi x_k), -lap u = D pi^2 u, u = 0 on the
// boundary; degree p, n elements per direction.
template <int D>
PoissonBenchmark<D> sine_box(int degree, int elements);

// l-shape: the L-shaped domain [-1, 1]^2 minus [0, 1] x [-1, 0] as one patch (a bilinear map from the
// inner polyline (1,0)-(0,0)-(0,-1) to the outer one (1,1)-(-1,1)-(-1,-1), with a C^0 line through the
// diagonal), -lap u = 0 with u = r^(2/3) sin(2 theta / 3) (theta in [0, 3 pi / 2] from the +x axis) as
// Dirichlet data: the re-entrant corner singularity limits uniform refinement to H1 rate 2/3 in h.
PoissonBenchmark<2> l_shape(int degree, int elements);

// The smallest `count` Dirichlet eigenvalues of -Laplace on the unit box: pi^2 (i^2 + j^2 [+ k^2]), i, j, k >= 1,
// ascending with multiplicity (cube: 3 pi^2, then 6 pi^2 three times, ...).
std::vector<double> unit_box_laplace_eigenvalues(int dim, int count);

template <int D>
struct ElasticityBenchmark {
  TensorSpace<D> space;
  ElasticityProblem<D> problem;
  ExactSolution<D> exact;  // displacement (D components)
};

// lame-cylinder: thick-walled cylinder a = 1 <= r <= b = 2 under internal pressure p = 1 (E = 1000, nu = 0.3),
// a quarter by symmetry (u_y = 0 on y = 0, u_x = 0 on x = 0), plane strain (D = 3: slab 0 <= z <= 0.5 with
// u_z = 0 on both ends). Exact Lame solution u_r = (1 + nu)/E ((1 - 2 nu) A r + B / r), A = p a^2/(b^2 - a^2),
// B = p a^2 b^2/(b^2 - a^2). Degree p, n elements per direction.
template <int D>
ElasticityBenchmark<D> lame_cylinder(int degree, int elements);

// plate-hole: Kirsch's infinite plate with a circular hole of radius a = 1 under remote tension T = 10 along x
// (E = 1e5, nu = 0.3, plane strain), the quarter x, y >= 0 of the square [-4, 4]^2 by symmetry (u_y = 0 on
// y = 0, u_x = 0 on x = 0), the exact traction sigma n on the outer edges x = 4 and y = 4, the hole free.
// Exact NURBS geometry: u runs around the hole (two rational quadratic 45-degree arcs, C0 at the corner
// (4, 4) of the outer edges), v from the hole to the edges (degree 1, raised). Exact displacement
// u_x = T a / (8 mu) [(r/a)(k+1) cos t + 2 (a/r)((1+k) cos t + cos 3t) - 2 (a/r)^3 cos 3t],
// u_y = T a / (8 mu) [(r/a)(k-3) sin t + 2 (a/r)((1-k) sin t + sin 3t) - 2 (a/r)^3 sin 3t], k = 3 - 4 nu; the
// stress concentration is sigma_xx = 3 T at (0, a). Degree p; n elements per element of the geometry (2n
// around the hole, n across).
ElasticityBenchmark<2> plate_with_hole(int degree, int elements);
// Kirsch's exact stress (sigma_xx, sigma_yy, sigma_xy) at x for remote tension T along x and hole radius a.
void kirsch_stress(double T, double a, const double* x, double* sigma);

// elastic-cube-modes: free vibration omega^2 of the unit cube with rollers on every face (normal displacement
// zero, tangential traction zero), the smallest `count` with multiplicity. For a wave number l in N^3 \ {0},
// u_k = a_k prod_j (j == k ? sin : cos)(pi l_j x_j) solves Navier's equation; a must vanish where l_k = 0, a
// parallel to l gives one dilatational mode (lambda + 2 mu) pi^2 |l|^2 / rho and a perpendicular to l, inside
// that subspace, (nonzero entries of l) - 1 shear modes mu pi^2 |l|^2 / rho.
std::vector<double> roller_cube_eigenvalues(const ElasticMaterial& m, int count);

// Quarter annulus r_in <= r <= r_out, 0 <= theta <= pi/2, exact NURBS (u radial degree 1, v angular
// rational quadratic); D = 3 extrudes it to 0 <= z <= height (w degree 1).
template <int D>
TensorSpline<D> quarter_annulus(double r_in, double r_out, double height = 1.0);

}  // namespace trivar
