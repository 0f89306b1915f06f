#include "trivar/iga/side_faces.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "trivar/core/error.hpp"
#include "trivar/iga/refined_space.hpp"

namespace trivar {

namespace side_faces {

// The faces among `candidates` (each with the functions non-zero on it) whose functions' control points all lie
// in the side plane. A face of a polynomial spline lies in the plane exactly when they do (its functions are
// independent on it). point(face, function, x): that function's control point.
template <int D, class Point>
std::vector<Face> in_plane(const std::string& side, const std::vector<std::pair<Face, std::vector<int>>>& candidates,
                           Point&& point, double lo, double hi) {
  const int axis = side[0] - 'x';
  const double plane = side[1] == '-' ? lo : hi, tol = 1e-9 * std::max(1.0, hi - lo);
  std::vector<Face> faces;
  double x[D];
  for (const auto& [f, functions] : candidates) {
    bool inside = true;
    for (int i : functions) {
      point(f, i, x);
      inside = inside && std::abs(x[axis] - plane) <= tol;
    }
    if (inside) faces.push_back(f);
  }
  require(!faces.empty(), "clamp: no boundary face lies in the plane of " + side);
  return faces;
}

int checked_axis(const std::string& side, int dimension) {
  require(side.size() == 2 && side[0] >= 'x' && side[0] <= 'z' && (side[1] == '-' || side[1] == '+'),
          "clamp: a side is x-, x+, y-, y+, z- or z+, got '" + side + "'");
  const int axis = side[0] - 'x';
  require(axis < dimension, "clamp " + side + " on a 2-D domain (x or y only)");
  return axis;
}

}  // namespace side_faces

template <int D>
std::vector<Face> faces_in_side_plane(const MultipatchSpace<D>& space, const std::string& side) {
  const int axis = side_faces::checked_axis(side, D);
  double lo = 1e300, hi = -1e300, x[D];
  for (const auto& p : space.patches)
    for (int i = 0; i < p.num_basis(); ++i) {
      p.geometry.control_point(i, x);
      lo = std::min(lo, x[axis]);
      hi = std::max(hi, x[axis]);
    }
  std::vector<std::pair<Face, std::vector<int>>> candidates;
  for (const Face& f : space.boundary) candidates.emplace_back(f, face_basis(space.patches[static_cast<std::size_t>(f.patch)], f));
  return side_faces::in_plane<D>(
      side, candidates,
      [&](const Face& f, int i, double* out) { space.patches[static_cast<std::size_t>(f.patch)].geometry.control_point(i, out); },
      lo, hi);
}

template <int D>
std::vector<Face> faces_in_side_plane(const RefinedSpace<D>& space, const std::string& side) {
  const int axis = side_faces::checked_axis(side, D);
  double lo = 1e300, hi = -1e300;
  for (int i = 0; i < space.num_basis; ++i) {
    lo = std::min(lo, space.control[static_cast<std::size_t>(D * i + axis)]);
    hi = std::max(hi, space.control[static_cast<std::size_t>(D * i + axis)]);
  }
  std::vector<std::pair<Face, std::vector<int>>> candidates;
  // A multi-block space: every block face with a part on the boundary (a face wholly on interfaces has none).
  const int blocks = std::max<int>(1, static_cast<int>(space.blocks.size()));
  for (int b = 0; b < blocks; ++b)
    for (int dir = 0; dir < D; ++dir)
      for (int s = 0; s < 2; ++s) {
        const Face f{dir, s, b};
        const std::vector<int>& ids = space.blocks.empty() ? space.face_basis[static_cast<std::size_t>(2 * dir + s)]
                                                           : space.blocks[static_cast<std::size_t>(b)].face_basis[static_cast<std::size_t>(2 * dir + s)];
        if (!space.blocks.empty() && ids.empty()) continue;
        candidates.emplace_back(f, ids);
      }
  return side_faces::in_plane<D>(
      side, candidates,
      [&](const Face&, int G, double* out) {
        for (int k = 0; k < D; ++k) out[k] = space.control[static_cast<std::size_t>(D * G + k)];
      },
      lo, hi);
}

template std::vector<Face> faces_in_side_plane(const MultipatchSpace<2>&, const std::string&);
template std::vector<Face> faces_in_side_plane(const MultipatchSpace<3>&, const std::string&);
template std::vector<Face> faces_in_side_plane(const RefinedSpace<2>&, const std::string&);
template std::vector<Face> faces_in_side_plane(const RefinedSpace<3>&, const std::string&);

}  // namespace trivar
