#pragma once
// trivar's native JSON for LR splines (schema in docs/formats.md, section "LR splines"). One object per file:
//   {"trivar": 1, "kind": "lr_surface"|"lr_volume", "dim": 3, "rational": false, "degrees": [p, q(, r)],
//    "basis": [{"knots": [[..], [..]], "gamma": g, "coef": [..]}, ..],
//    "mesh": [{"dir": k, "value": x, "lo": [..], "hi": [..], "multiplicity": m}, ..]}
// or several: {"trivar": 1, "objects": [ {..}, {..} ]}. "coef" is homogeneous when rational ((w x, w y, w z, w),
// dim + 1 values), as in the .lr format and in memory, so a round trip is bit-exact. "lo" / "hi" have one entry
// per parametric direction; their entry at "dir" must equal "value".
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "trivar/lr/any_lr_spline.hpp"

namespace trivar::io {

// The JSON object of one LR spline (with "trivar": 1).
nlohmann::json to_json(const AnyLRSpline& s);

// Validates and converts one object; `where` prefixes every error, which then names the JSON path inside the
// object (e.g. "f.json: basis[3]: knots[1][2]: expected a number, got string").
AnyLRSpline lr_spline_from_json(const nlohmann::json& j, const std::string& where);

// Reads a file holding one object or {"trivar": 1, "objects": [...]} (at least one object).
std::vector<AnyLRSpline> read_lr_json(const std::string& path);
// Writes one object, or the "objects" form for several, atomically; nothing is written when the list is empty.
void write_lr_json(const std::string& path, const std::vector<AnyLRSpline>& objects);

}  // namespace trivar::io
