#pragma once
// The boundary faces of a multipatch space that lie in the plane of one side of the bounding box of its control
// points ("x-" is x = min x, "z+" is z = max z): the supports named by `trivar solve --clamp` and the Python
// module's `clamp`.
#include <string>
#include <vector>

#include "trivar/iga/multipatch_space.hpp"

namespace trivar {

template <int D>
struct RefinedSpace;

// Throws trivar::Error for a side that is not x-, x+, y-, y+, z-, z+ (z only in 3-D) or has no face.
template <int D>
std::vector<Face> faces_in_side_plane(const MultipatchSpace<D>& space, const std::string& side);

// The same on a locally refined space (refined_space.hpp), whose faces are Face{dir, side, 0}, or Face{dir, side,
// block} on the block faces that reach the boundary of a multi-block space.
template <int D>
std::vector<Face> faces_in_side_plane(const RefinedSpace<D>& space, const std::string& side);
extern template std::vector<Face> faces_in_side_plane(const MultipatchSpace<2>&, const std::string&);
extern template std::vector<Face> faces_in_side_plane(const MultipatchSpace<3>&, const std::string&);
extern template std::vector<Face> faces_in_side_plane(const RefinedSpace<2>&, const std::string&);
extern template std::vector<Face> faces_in_side_plane(const RefinedSpace<3>&, const std::string&);

}  // namespace trivar
