#pragma once
// Sweeping a surface along a curve with a rotation-minimising frame: the profile moves rigidly, turning
// with the path's tangent but never about it (no twist), which a Frenet frame would add where the path
// bends out of a plane or straightens.
#include <span>
#include <vector>

#include <Eigen/Core>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// Frames (columns: unit tangent t, r, s = t x r) of the rotation-minimising frame along `path` (control
// dimension 3) at the parameters `params` (non-decreasing, inside the domain), propagated from the start of
// the domain by the double reflection method (Wang, Juttler, Zheng, Liu 2008) in steps of at most max_step
// (global error O(max_step^4)). The initial r is the coordinate axis least aligned with the start tangent,
// made orthogonal to it. Throws trivar::Error on a zero tangent, unsorted or outside parameters or a
// non-positive step.
std::vector<Eigen::Matrix3d> rotation_minimizing_frames(const SplineCurve& path, std::span<const double> params,
                                                        double max_step);

struct SweepOptions {
  int degree = 3;        // along the path; raised to the path's degree when lower
  int sections = 8;      // minimum number of elements along the path
  int samples = 16;      // error samples per element along the path
  int frame_steps = 32;  // double reflection steps per element (frame accuracy, far below the fit error)
};

struct SweepResult {
  SplineVolume volume;
  // Upper bound of |V - exact sweep| over the profile, maximised over `samples` parameters per element:
  // for fixed w both are C(w) + R(w) (S(u, v) - C(w0)) with fitted or exact C and R, so the difference is
  // convex in S and bounded by its largest value at the profile's control points (attained where a control
  // point lies on the profile, e.g. at its corners).
  double max_error = 0;
};

// V(u, v, w) ~ path(w) + R(w) (profile(u, v) - path(w0)), where R(w) turns the rotation-minimising frame at
// w0 (start of the path's domain) into the one at w: the profile is given in place at the start of the path
// and slides along it without twisting. The w-direction has the path's breakpoints (continuity kept) and
// degree max(degree, path degree), each path element split uniformly to reach `sections` elements; the
// homogeneous control nets of the rigidly moved profile are interpolated at the Greville abscissae of that
// knot vector. A polynomial path in this space is reproduced exactly, so along a straight line the result is
// the extrusion. det J > 0 where profile_u x profile_v points along the path's tangent. Throws trivar::Error
// when profile or path do not have control dimension 3, on options below 1, or on a zero path tangent.
SweepResult sweep(const SplineSurface& profile, const SplineCurve& path, const SweepOptions& options = {});

}  // namespace trivar
