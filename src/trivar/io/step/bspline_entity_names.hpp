#pragma once
// The STEP entity names of B-spline curves, surfaces and volumes (ISO 10303-42), indexed by dimension - 1: the
// reader and the writer must spell them alike.
#include <array>

namespace trivar::io::step {

inline constexpr std::array<const char*, 3> kBase = {"B_SPLINE_CURVE", "B_SPLINE_SURFACE", "B_SPLINE_VOLUME"};
inline constexpr std::array<const char*, 3> kWithKnots = {"B_SPLINE_CURVE_WITH_KNOTS", "B_SPLINE_SURFACE_WITH_KNOTS",
                                                          "B_SPLINE_VOLUME_WITH_KNOTS"};
inline constexpr std::array<const char*, 3> kRational = {"RATIONAL_B_SPLINE_CURVE", "RATIONAL_B_SPLINE_SURFACE",
                                                         "RATIONAL_B_SPLINE_VOLUME"};

}  // namespace trivar::io::step
