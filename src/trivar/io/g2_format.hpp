#pragma once
// GoTools g2 text format, the spline subset: SplineCurve (class 100), SplineSurface (200) and SplineVolume
// (700). Each object is
//   classType major minor nAux [nAux auxiliary values]      e.g. "700 1 0 0"
//   dim rational                                            rational is 0 or 1
//   ncoef order  followed by ncoef + order knots             once per parametric direction, u first
//   ncoef_u * ncoef_v * ... coefficients, u fastest          dim values each, or dim + 1 homogeneous
//                                                            values (w*x, w*y, w*z, w) when rational
// which is GoTools' own convention (its rational splines keep "rcoefs" in homogeneous form). Any control
// dimension is accepted; a file holds one or more objects. Reals are written in shortest round-trip form.
#include <string>
#include <vector>

#include "trivar/spline/any_spline.hpp"

namespace trivar::io {

// Throws trivar::Error "file:line: ..." on an unsupported class type, malformed header, invalid knot vector,
// non-numeric or non-finite value, non-positive weight, wrong number of coefficients or truncated file.
std::vector<AnySpline> read_g2(const std::string& path);
// The same for the text of a file; `name` stands for the file in messages.
std::vector<AnySpline> parse_g2(std::string text, const std::string& name);

// Nothing is written when an object is empty (default-constructed) or the list is empty.
void write_g2(const std::string& path, const std::vector<AnySpline>& objects);

}  // namespace trivar::io
