#pragma once
// The V-topology of trimmed cells across their trimming faces (seed 001, Defs. 3.4-3.5): which face of which
// cell a trimming face is shared with. Cells cut from one another by a Boolean (or a split) share the
// triangulation of every face between them, so a shared face's mesh triangles appear in both cells with the
// same corners (bit for bit) and opposite orientations; the faces are matched through those triangles. A face
// all of whose triangles pair with triangles of one face of another cell is an interior V-surface shared by
// exactly those two cells; a face none of whose triangles pair is a boundary V-surface; anything else (some
// triangles paired, or paired with several faces) is a non-conforming contact, reported rather than guessed.
#include <array>
#include <vector>

#include "trivar/model/vmodel.hpp"

namespace trivar {

struct TrimmedFaceRef {
  int cell = -1, face = -1;  // face: index into the cell's TrimmedBoundary::faces
  bool operator==(const TrimmedFaceRef&) const = default;
};

struct TrimmedInterfaces {
  // Per cell, per trimming face: the face of another cell it is shared with ({-1, -1}: a boundary face or a
  // non-conforming one). Untrimmed cells have no entries.
  std::vector<std::vector<TrimmedFaceRef>> twin;
  // V-surfaces: each shared pair once (halves[0] the lower cell), then each boundary face ({face, {-1, -1}}).
  std::vector<std::array<TrimmedFaceRef, 2>> surfaces;
  int shared = 0, boundary = 0;
  // Faces only partly covered by another cell's triangles, or covered by several faces: the first cell's face.
  std::vector<TrimmedFaceRef> non_conforming;
  // Per cell: the cells it shares a face with, ascending.
  std::vector<std::vector<int>> neighbours;
};

// Per triangle of the concatenated trimming meshes of the trimmed cells (cell by cell, in mesh order): the
// index of the triangle of another cell with the same corners in opposite orientation, -1 for none.
// `first_triangle` receives per cell the index of its first triangle (size cells + 1).
std::vector<long> paired_trimming_triangles(const VModel& model, std::vector<long>& first_triangle);

// The shared and boundary trimming faces of the model's trimmed cells.
TrimmedInterfaces trimmed_interfaces(const VModel& model);

}  // namespace trivar
