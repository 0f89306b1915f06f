#pragma once
// Boolean-sum (trivariate Coons) volumes: the volume spanned by six boundary faces.
#include <array>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// faces in boundary_faces() order (u = 0, u = 1, v = 0, v = 1, w = 0, w = 1), each parametrised by the
// remaining two directions in order ((v, w) for the u-faces, (u, w) for the v-faces, (u, v) for the w-faces).
// The result is P_u + P_v + P_w - P_uv - P_vw - P_uw + P_uvw with linear blends: P_u blends the two u-faces,
// P_uv the four edges along w, P_uvw the eight corners. Its boundary faces are the input faces and it
// reproduces every volume that is trilinear in the blending sense (in particular affine maps).
// The domain of u is that of face v = 0 (first direction), of v and w that of face u = 0; other faces are
// mapped affinely onto it. The sum acts on homogeneous coefficients after make_compatible, so rational faces
// must carry the same weights along shared edges (as the faces of one volume do).
// Each of the 12 edges is taken from both faces that contain it; when their coefficients differ by more than
// `tolerance` after make_compatible (homogeneous coordinates, which bounds the distance of polynomial edges),
// throws trivar::Error naming the two faces and the edge. Also throws when the control dimensions differ.
SplineVolume coons_volume(const std::array<SplineSurface, 6>& faces, double tolerance = 1e-9);

}  // namespace trivar
