#pragma once
// A T-spline's three layers as JSON, for inspection and scripting:
//   {"kind": "t_spline", "name", "degrees": [ps, pt], "t_image": {"vertices": [[s, t, [n, w, s, e links]], ...],
//    "edges": [[start, end], ...], "links": [[edge, sense], ...], "faces": [[links...], ...],
//    "edge_conditions": [[edge, flag], ...]}, "t_connect": [{"anchor": "vertex"|"link"|"face", "id", "point",
//    "neighbours": [n, w, s, e]}, ...], "t_pointset": [[x, y, z, w], ...]}   (-1: none)
// Reals in shortest round-trip form; read_t_spline_json reads it back exactly.
#include <string>

#include "trivar/tspline/t_spline.hpp"

namespace trivar::io {

void write_t_spline_json(const std::string& path, const TSpline& ts);
// Throws trivar::Error naming the file and the member on any malformed content or invalid T-spline.
TSpline read_t_spline_json(const std::string& path);

}  // namespace trivar::io
