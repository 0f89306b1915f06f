#pragma once
// The trimming boundary of a trimmed V-cell in trivar's JSON (schema in docs/formats.md):
//   {"chordal_tolerance": t,
//    "faces": [{"surface": {<surface object>}, "reversed": false, "tolerance": 1e-7, "kind": "plane",
//               "name": "#17 ADVANCED_FACE",
//               "loops": [[{"pcurve": {<curve object, dim 2>}, "edge": 3, "edge_reversed": false}, ..], ..]}],
//    "edges": [{"curve": {<curve object, dim 3>}, "tolerance": 1e-7} | null, ..],
//    "mesh": {"vertices": [x0, y0, z0, ..], "triangles": [a0, b0, c0, ..], "triangle_face": [..],
//             "triangle_uv": [u0, v0, u1, v1, u2, v2, ..]}}
// The mesh is stored, not rebuilt, so a model reads back without the geometry kernel that made it.
#include <string>

#include <nlohmann/json.hpp>

#include "trivar/model/trimmed_boundary.hpp"

namespace trivar::io {

nlohmann::json to_json(const TrimmedBoundary& b);

// Validates the JSON structure; `where` prefixes errors with the JSON path. (The geometry is validated by
// TrimmedSolid.)
TrimmedBoundary trimmed_boundary_from_json(const nlohmann::json& j, const std::string& where);

}  // namespace trivar::io
