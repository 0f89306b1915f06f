#pragma once
// TensorSpace<D>: the isogeometric discretisation space of one tensor-product patch. The geometry map
// x(u) = sum_I c_I R_I(u) (a TensorSpline<D> with D physical coordinates, polynomial or NURBS) is refined
// until its own basis is the wanted space, so the basis functions R_I are the geometry's: B-splines, or
// w_I B_I / W for NURBS. Scalar unknowns are numbered like the control points (u fastest); an unknown with m
// components is numbered component-major (component c of basis function I is c * num_basis() + I).
#include <array>
#include <vector>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// A side of the parameter domain: direction dir (0 = u, 1 = v, 2 = w) at its start (side 0) or end (side 1),
// of patch `patch` in a multipatch space (multipatch_space.hpp; 0 for a single patch).
struct Face {
  int dir = 0;
  int side = 0;
  int patch = 0;
  bool operator==(const Face&) const = default;
};

template <int D>
struct TensorSpace {
  TensorSpline<D> geometry;

  int num_basis() const { return geometry.num_coefs(); }
  int degree(int k) const { return geometry.degree(k); }
};

// The space of `geometry` with every degree raised to at least `degree` and every element split into
// `subdivisions` equal parts (knot insertion and degree elevation are exact: the geometry is unchanged).
// Throws trivar::Error when the geometry's dim is not D, degree < 1, subdivisions < 1 or a knot vector is
// not clamped (strong boundary conditions need interpolatory ends).
template <int D>
TensorSpace<D> make_tensor_space(const TensorSpline<D>& geometry, int degree, int subdivisions);

// The box [lo, hi] as a degree-p spline with n equal elements per direction (control points at the
// Greville abscissae, so the map is the identity up to scaling). Throws trivar::Error for p < 1 or n < 1.
template <int D>
TensorSpline<D> box_geometry(const Param<D>& lo, const Param<D>& hi, int degree,
                             int elements);

// Basis functions whose trace on the face is not zero: those with index 0 (side 0) or n - 1 (side 1) in the
// face's direction, ascending.
template <int D>
std::vector<int> face_basis(const TensorSpace<D>& space, const Face& face);

// All 2D faces of a D-dimensional box.
template <int D>
std::vector<Face> all_faces();

}  // namespace trivar
