#pragma once
// C1 stitching of rational patches keeps the weights. When the weights w are already C1 across a seam (as they are
// for pieces of one NURBS), the rational map x = (w x) / w is C1 exactly when the homogeneous map (w x) is, because
// w is positive and continuous with a continuous derivative; the C1 conditions then act on w x alone and stay
// linear. When the weights are not C1 there, no move of the homogeneous coordinates alone can make the rational
// map C1 in general, and moving the weights would change the geometry elsewhere: refused.
#include <cmath>
#include <string>
#include <type_traits>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"

namespace trivar {

// Throws trivar::Error with one line (name() + ": the weights are not C1 across " + across + ...) naming the
// weight-derivative jump, unless the weight's derivatives across the seam on the two sides, `out_of` (leaving the
// first side, in its parameter) and `into` (entering the second, scaled to the first's parameter speed), agree to
// 1e-9 of their size and of `weight` over `extent` (the first side's parameter length across the seam).
template <class MakeName>
  requires std::is_invocable_r_v<std::string, MakeName>
void require_weights_c1(double out_of, double into, double weight, double extent, MakeName&& name, const char* across) {
  const double scale = std::abs(out_of) + std::abs(into) + std::abs(weight) / extent;
  require(std::abs(out_of - into) <= 1e-9 * scale, [&] {
    return name() + ": the weights are not C1 across " + across + " (weight-derivative jump " +
           format_number(std::abs(out_of - into)) + ": cross derivatives " + format_number(out_of) + " and " +
           format_number(into) + "); C1 stitching of rational patches keeps the weights and needs them C1 there (C0 "
           "does not)";
  });
}

}  // namespace trivar
