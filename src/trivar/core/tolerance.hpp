#pragma once
// Named default tolerances. Every algorithm takes its tolerance as a parameter; these are the defaults.
namespace trivar::tol {

// Two knots closer than this (relative to the knot span) are the same knot.
inline constexpr double knot = 1e-12;
// Point inversion: stop Newton when the model-space residual is below this (relative to model size).
inline constexpr double inversion = 1e-12;

}  // namespace trivar::tol
