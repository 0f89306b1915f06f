#pragma once
// GoTools g2 text format for LR splines: LRSplineSurface (class 293) and LRSplineVolume (class 793), as
// written and read by the current GoTools master (lrsplines2D / lrsplines3D, streams of LRSplineSurface::write,
// Mesh2D/Mesh3D::write, LRBSpline2D/3D::write and BSplineUniLR::write; checked against the 2024 sources).
// Older GoTools versions (before 2013) wrote no rational flag and, later, LR B-splines with integer knot
// vectors inline; those are not supported. Whitespace-separated tokens; one object is
//   293 1 0 0                            header: class, major, minor, number of auxiliary values (skipped)
//   rat knot_tol                         rational flag 0 / 1; knot tolerance (ignored on input; 1e-08 written)
//   n_0 t_0 ... t_{n_0-1}                distinct knot values per direction (u, v[, w]), strictly increasing
//   n_0  { m  (ix mult) * m } * n_0      2D: per u-knot, runs along v: from v-knot index ix on, multiplicity
//                                        mult (0: no line), up to the next run or the last v-knot; then the
//                                        same for the v-knots (runs along u)
//   n_0  { m  (a0 b0 a1 b1 mult) * m }   3D: per knot of direction k, rectangles in the index space of the
//                                        directions (k+1) % 3 and (k+2) % 3 from (a0, b0) to (a1, b1), for
//                                        k = u, v, w (the GoTools cyclic order: v-w, w-u, u-v)
//   nbasis                               then per LR B-spline:
//   dim rat  c_1 .. c_dim  gamma  weight  (p_k + 2  knot indices) per direction
// GoTools' conventions differ from trivar's: a polynomial B-spline stores c * gamma (so its value is
// sum coef_i B_i without gamma); a rational one stores the Cartesian point and a weight that includes gamma
// (value sum c_i w_i B_i / sum w_i B_i). Reading and writing convert, so the spline evaluates identically;
// the writer picks, among the doubles nearest to the converted value, one that converts back exactly, so a
// trivar -> g2 -> trivar round trip is bit-exact whenever such a double exists (see docs/formats.md).
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "trivar/lr/any_lr_spline.hpp"

namespace trivar::io {

// Throws trivar::Error "name:line: ..." on an unsupported class type, malformed or truncated input, an
// inconsistent mesh (unsorted knots, run or rectangle indices out of range), a B-spline whose dimension,
// rational flag or degrees disagree with the others, a non-positive gamma or weight, or an LR spline the
// LRSpline constructor rejects (its message follows the position of the object's header).
std::vector<AnyLRSpline> parse_lr_g2(std::string_view text, const std::string& name);
std::vector<AnyLRSpline> read_lr_g2(const std::string& path);

void write_lr_g2(std::ostream& os, const AnyLRSpline& s);
// Nothing is written when the list is empty or on any error.
void write_lr_g2(const std::string& path, const std::vector<AnyLRSpline>& objects);

}  // namespace trivar::io
