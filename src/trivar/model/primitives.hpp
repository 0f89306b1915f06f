#pragma once
// Volumetric primitives as complexes of non-singular trivariates (Massarwi & Elber 2016): every cell has a
// positive Jacobian everywhere, and cells that touch share a whole face with identical knots, degrees,
// control points and weights on it (up to the orientation of the face's two directions). A round section
// is a central square (cube) plus ruled cells out to exact rational arcs (sphere patches), so no cell has the
// collapsed edge or point of the usual polar parametrisation.
//
// `core` sets the size of the central square or cube as a fraction of the largest one that fits: half-side
// core * radius / sqrt(2) for a disk, core * radius / sqrt(3) for a ball. It must lie in (0, 1); every value
// tried from 0.05 to 0.99 was certified valid, and the default keeps the core and outer cells of similar size.
#include <vector>

#include <Eigen/Core>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

using CellComplex = std::vector<SplineVolume>;

inline constexpr double kDefaultCore = 0.6;

// Solid cylinder about the z-axis: base disk of `radius` centred at the origin, top at z = height.
struct CylinderSpec {
  double radius = 1;
  double height = 1;
  double core = kDefaultCore;
};

// Frustum about the z-axis: radius bottom_radius at z = 0, top_radius at z = height. A full cone
// (top_radius = 0) is not representable by non-singular cells (the apex collapses every cell's top face), so
// top_radius must be positive; a cone with its apex cut off arbitrarily close is the supported substitute.
struct ConeSpec {
  double bottom_radius = 1;
  double top_radius = 0.5;
  double height = 1;
  double core = kDefaultCore;
};

// Ball of `radius` about `center`.
struct BallSpec {
  double radius = 1;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double core = kDefaultCore;
};

// Ring torus about the z-axis centred at the origin: tube of minor_radius around the circle of major_radius
// in the plane z = 0; requires 0 < minor_radius < major_radius.
struct TorusSpec {
  double major_radius = 2;
  double minor_radius = 0.5;
  double core = kDefaultCore;
};

// Axis-aligned box [origin, origin + size].
struct BoxSpec {
  Eigen::Vector3d size = Eigen::Vector3d::Ones();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};

// One cell: the trilinear block (make_block) moved to `origin`. Throws trivar::Error unless every size is
// positive and finite and the origin is finite.
CellComplex make_box(const BoxSpec& spec);

}  // namespace trivar
