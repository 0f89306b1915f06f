#pragma once
// Binary STL: an 80-byte header, a little-endian uint32 triangle count, then per triangle the facet normal
// and three vertices as float32 and a zero uint16 attribute. The normal is the unit normal of the
// counter-clockwise vertex order (zero for a degenerate triangle).
#include <string>

#include "trivar/model/triangle_mesh.hpp"

namespace trivar::io {

// Throws trivar::Error when the mesh has a vertex index out of range, a non-finite coordinate, more triangles
// than the format can count, or the file cannot be written; nothing is written then.
void write_stl(const std::string& path, const TriangleMesh& mesh, const std::string& header = "trivar");

}  // namespace trivar::io
