#pragma once
// Named default tolerances. Every algorithm takes its tolerance as a parameter; these are the defaults.
namespace trivar::tol {

// Two knots closer than this (relative to the knot span) are the same knot.
inline constexpr double knot = 1e-12;

}  // namespace trivar::tol
