#include "trivar/iga/side_faces.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"

namespace trivar {

template <int D>
std::vector<Face> faces_in_side_plane(const MultipatchSpace<D>& space, const std::string& side) {
  require(side.size() == 2 && side[0] >= 'x' && side[0] <= 'z' && (side[1] == '-' || side[1] == '+'),
          "clamp: a side is x-, x+, y-, y+, z- or z+, got '" + side + "'");
  const int axis = side[0] - 'x';
  require(axis < D, "clamp " + side + " on a 2-D domain (x or y only)");
  double lo = 1e300, hi = -1e300, x[D];
  for (const auto& p : space.patches)
    for (int i = 0; i < p.num_basis(); ++i) {
      p.geometry.control_point(i, x);
      lo = std::min(lo, x[axis]);
      hi = std::max(hi, x[axis]);
    }
  const double plane = side[1] == '-' ? lo : hi, tol = 1e-9 * std::max(1.0, hi - lo);
  std::vector<Face> faces;
  for (const Face& f : space.boundary) {
    const TensorSpace<D>& p = space.patches[static_cast<std::size_t>(f.patch)];
    bool in_plane = true;
    for (int i : face_basis(p, f)) {
      p.geometry.control_point(i, x);
      in_plane = in_plane && std::abs(x[axis] - plane) <= tol;
    }
    if (in_plane) faces.push_back(f);
  }
  require(!faces.empty(), "clamp: no boundary face lies in the plane of " + side);
  return faces;
}

template std::vector<Face> faces_in_side_plane(const MultipatchSpace<2>&, const std::string&);
template std::vector<Face> faces_in_side_plane(const MultipatchSpace<3>&, const std::string&);

}  // namespace trivar
