#pragma once
// VTK's cell type numbers and the point order of its higher-order (Lagrange and Bezier) curves, quadrilaterals
// and hexahedra.
#include <array>
#include <cstdint>

namespace trivar::io {

// VTK cell type numbers (vtkCellType.h), indexed by the cell's dimension - 1.
inline constexpr std::array<std::uint8_t, 3> kVtkLinearCell = {3, 9, 12};    // VTK_LINE, _QUAD, _HEXAHEDRON
inline constexpr std::array<std::uint8_t, 3> kVtkBezierCell = {75, 77, 79};  // VTK_BEZIER_CURVE, _QUADRILATERAL, _HEXAHEDRON
inline constexpr std::uint8_t kVtkTriangle = 5;

// Position of Bezier node i (0 <= i_k <= p_k) in VTK's higher-order cell point order: corners, then edge
// interiors, then face interiors, then the body, with VTK's edge and face numbering (vtkHigherOrder*
// ::PointIndexFromIJK; hexahedra in the VTK >= 9 edge order, i.e. XML file version >= 2.1).
template <int D>
int vtk_node_index(const std::array<int, D>& i, const std::array<int, D>& p) {
  if constexpr (D == 1) {
    return i[0] == 0 ? 0 : i[0] == p[0] ? 1 : i[0] + 1;
  } else {
    std::array<bool, D> bdy{};
    int nbdy = 0;
    for (int k = 0; k < D; ++k) nbdy += (bdy[k] = (i[k] == 0 || i[k] == p[k])) ? 1 : 0;
    const bool hi0 = i[0] == p[0], hi1 = i[1] == p[1];
    const int corner = hi0 ? (hi1 ? 2 : 1) : (hi1 ? 3 : 0);  // counter-clockwise in the (u, v) plane
    const int a = p[0] - 1, b = p[1] - 1;                    // interior nodes per edge along u, v
    if constexpr (D == 2) {
      if (nbdy == 2) return corner;
      if (nbdy == 1) return 4 + (bdy[1] ? (i[0] - 1) + (hi1 ? a + b : 0) : (i[1] - 1) + (hi0 ? a : 2 * a + b));
      return 4 + 2 * (a + b) + (i[0] - 1) + a * (i[1] - 1);
    } else {
      const bool hi2 = i[2] == p[2];
      const int c = p[2] - 1;
      if (nbdy == 3) return corner + (hi2 ? 4 : 0);
      if (nbdy == 2) {
        if (!bdy[0]) return 8 + (i[0] - 1) + (hi1 ? a + b : 0) + (hi2 ? 2 * (a + b) : 0);
        if (!bdy[1]) return 8 + (i[1] - 1) + (hi0 ? a : 2 * a + b) + (hi2 ? 2 * (a + b) : 0);
        return 8 + 4 * (a + b) + (i[2] - 1) + c * corner;
      }
      int offset = 8 + 4 * (a + b + c);
      if (nbdy == 1) {
        if (bdy[0]) return offset + (i[1] - 1) + b * (i[2] - 1) + (hi0 ? b * c : 0);
        offset += 2 * b * c;
        if (bdy[1]) return offset + (i[0] - 1) + a * (i[2] - 1) + (hi1 ? c * a : 0);
        offset += 2 * c * a;
        return offset + (i[0] - 1) + a * (i[1] - 1) + (hi2 ? a * b : 0);
      }
      offset += 2 * (b * c + c * a + a * b);
      return offset + (i[0] - 1) + a * ((i[1] - 1) + b * (i[2] - 1));
    }
  }
}

}  // namespace trivar::io
