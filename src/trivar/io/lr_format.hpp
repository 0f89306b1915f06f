#pragma once
// The LRsplines text format (.lr), as written and read by SINTEF's LRsplines library and IFEM: one or more
// blocks, each
//   # LRSPLINE SURFACE                       or  # LRSPLINE VOLUME
//   #  p1  p2  Nbasis  Nline  Nel  dim  rat      (p3 after p2 for volumes; p_k are orders = degree + 1)
//      3   3   16      10     9    3    0
//   # Basis functions:
//   0: [0 0 0 1 ] x [0 0 1 2 ] x ... c_1 ... c_n (gamma)      n = dim (+ 1 homogeneous weight when rat)
//   # Mesh lines:                            (surfaces; volumes: "# Mesh rectangles:")
//   0.5 x [0, 1] (1)                          u = 0.5 for v in [0, 1], multiplicity 1; "[0, 1] x 0.5 (1)" for v
//   [0.5, 0.5] x [0, 1] x [0, 1] (1)          volumes: the constant direction has a degenerate interval
//   # Elements:
//   0 [2] : (0, 0) x (0.5, 0.5)    {0, 1, 4, 5}
// Lines starting with '#' are comments; a block whose comments do not name SURFACE or VOLUME (older LRsplines
// versions wrote a bare "# LRSPLINE") is told by its header line: 7 values for a surface, 8 for a volume. Basis
// ids are arbitrary integers (element support lists refer to them). Elements are recomputed from the mesh; the
// block must list exactly those (up to rounding of the corners), in any order, which becomes the element
// numbering (LRSpline::reorder_elements); the writer lists them in id order. Rational control
// values are homogeneous (w x, w y, w z, w), LRsplines' own convention and trivar's. Reals are written in
// shortest round-trip form.
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "trivar/lr/any_lr_spline.hpp"

namespace trivar::io {

// Throws trivar::Error "name:line: ..." on any syntax error, a wrong count, an invalid basis function or mesh
// rectangle (through the LRSpline constructor), an element block that does not list the mesh's elements, an
// unknown basis id in an element, or an empty input.
std::vector<AnyLRSpline> parse_lr(std::string_view text, const std::string& name);
std::vector<AnyLRSpline> read_lr(const std::string& path);

void write_lr(std::ostream& os, const AnyLRSpline& s);
// Nothing is written when the list is empty or on any error.
void write_lr(const std::string& path, const std::vector<AnyLRSpline>& objects);

}  // namespace trivar::io
