#pragma once
// Built-in problems with known exact solutions, used by `trivar solve`, the tests and the benchmarks.
#include <string>
#include <vector>

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

// The smallest `count` Dirichlet eigenvalues of -Laplace on the unit box: pi^2 (i^2 + j^2 [+ k^2]), i, j, k >= 1,
// ascending with multiplicity (cube: 3 pi^2, then 6 pi^2 three times, ...).
std::vector<double> unit_box_laplace_eigenvalues(int dim, int count);

// Quarter annulus r_in <= r <= r_out, 0 <= theta <= pi/2, exact NURBS (u radial degree 1, v angular
// rational quadratic); D = 3 extrudes it to 0 <= z <= height (w degree 1).
template <int D>
TensorSpline<D> quarter_annulus(double r_in, double r_out, double height = 1.0);

}  // namespace trivar
