#pragma once
// Gauss quadrature on the elements of a tensor patch, and fields evaluated on one element's quadrature grid
// by sum factorisation: the geometry (points, inverse Jacobians, volume weights) and any spline field on the
// patch's basis (the discrete solution). Everything per element is a few 1-D contractions, so evaluating the
// q^D points of an element costs O(p q^D), not O(p^D q^D).
#include <array>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/iga/element_tables.hpp"
#include "trivar/iga/tensor_space.hpp"

namespace trivar {

template <int D>
struct PatchQuadrature {
  std::array<DirectionTable, D> dir;

  Ints<D> elements() const;
  int num_elements() const;
  // Points per element (product over directions), u fastest.
  int points() const;
  // Element index per direction of element e (u fastest).
  Ints<D> element_index(int e) const;
};

// points_per_dir[k] Gauss points per element in direction k.
template <int D>
PatchQuadrature<D> patch_quadrature(const TensorSpace<D>& space, const Ints<D>& points_per_dir);
// degree + extra points per direction (extra = 1 integrates the mass matrix of an affine map exactly).
template <int D>
PatchQuadrature<D> patch_quadrature(const TensorSpace<D>& space, int extra = 1);

// Geometry at the quadrature points of one element, point-major.
template <int D>
struct GridGeometry {
  std::vector<double> x;        // [q * D + c]: physical point
  std::vector<double> jinv;     // [(q * D + a) * D + c] = d u_a / d x_c
  std::vector<double> measure;  // |det J| times the quadrature weight
  std::vector<double> W;        // NURBS weight function (1 when polynomial)
  std::vector<double> dW;       // [q * D + a]: d W / d u_a
};

// Reusable per-thread buffers of the grid evaluations.
struct GridScratch {
  std::vector<double> block, a, b, fields;
  std::array<std::vector<double>, 3> level;
};

// Values and parametric first derivatives, on element e's grid, of the spline sums sum_I v_I B_I for
// `components` fields whose coefficients are coefs[I * stride + c] (B-splines, not divided by W):
// out[(a * points + q) * components + c], a = 0 value, a = 1 + k derivative in direction k.
template <int D>
void grid_fields(const TensorSpace<D>& space, const PatchQuadrature<D>& quad, const Ints<D>& e, const double* coefs,
                 int stride, int components, GridScratch& scratch, std::vector<double>& out);

template <int D>
void grid_geometry(const TensorSpace<D>& space, const PatchQuadrature<D>& quad, const Ints<D>& e,
                   GridScratch& scratch, GridGeometry<D>& out);

// The reverse contraction: element vector b_I = sum_q g(q) B_I(q) for the element's (p+1)^D B-splines (local
// order u fastest); g has points values.
template <int D>
void grid_integrate(const PatchQuadrature<D>& quad, const Ints<D>& e, const double* g, GridScratch& scratch,
                    std::vector<double>& out);

// Global index of local basis function `local` (u fastest over the element's (p+1)^D functions) of element e.
template <int D>
int global_basis(const TensorSpace<D>& space, const PatchQuadrature<D>& quad, const Ints<D>& e, int local);

}  // namespace trivar
