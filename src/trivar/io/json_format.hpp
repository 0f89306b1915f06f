#pragma once
// trivar's native JSON spline format (schema in docs/formats.md). One object per file:
//   {"trivar": 1, "kind": "curve"|"surface"|"volume", "dim": 3, "rational": false,
//    "degrees": [..], "knots": [[..], ..], "control_points": [[x, y, z], ..], "weights": [..]}
// or several: {"trivar": 1, "objects": [ {..}, {..} ]}. Control points are Cartesian, u fastest; "weights"
// is present exactly when "rational" is true. Numbers are written so that they parse back to the same double.
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "trivar/spline/any_spline.hpp"

namespace trivar::io {

// The JSON object of one spline (with "trivar": 1, so it is a valid file on its own). Throws trivar::Error
// for an empty (default-constructed) spline or a Cartesian control point that is not finite.
nlohmann::json to_json(const AnySpline& s);

// Validates and converts one object. `where` prefixes every error message (e.g. "part.json: objects[2]"),
// which then names the JSON path inside the object and what was expected.
AnySpline spline_from_json(const nlohmann::json& j, const std::string& where);

// The parsed top-level object of a trivar JSON file, with "trivar": 1 checked; throws trivar::Error naming the
// file on I/O and syntax errors.
nlohmann::json read_json_document(const std::string& path);
// The same for a document in memory; `name` stands for the file in messages.
nlohmann::json parse_json_document(std::string_view text, const std::string& name);
// Writes a document atomically in the project's layout (spline keys in schema order, numeric arrays on one line).
void write_json_document(const std::string& path, const nlohmann::json& doc);

// The objects of a trivar JSON document with the error prefix of each: the document itself, or the entries of
// its "objects" array (validated: no other keys, a non-empty array; `what` names the objects in messages).
std::vector<std::pair<nlohmann::json, std::string>> object_documents(const nlohmann::json& doc,
                                                                     const std::string& path, const char* what);
// The document for a list of objects: the single object itself, or {"trivar": 1, "objects": [...]}.
nlohmann::json document_of(std::vector<nlohmann::json> objects);

// Reads a file holding one object or {"trivar": 1, "objects": [...]} (at least one object).
std::vector<AnySpline> read_json(const std::string& path);

// Writes one object, or the "objects" form for several; nothing is written when any object is invalid.
void write_json(const std::string& path, const std::vector<AnySpline>& objects);

}  // namespace trivar::io
