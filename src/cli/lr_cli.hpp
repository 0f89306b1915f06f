#pragma once
// LR splines on the command line: which files hold them, reading (with exact conversion of tensor surfaces and
// volumes), writing by extension and describing them for `info`.
//
// A file holds LR splines when it is
//   .lr                                        (LRsplines text format), always;
//   .g2  whose first object header is 293/793  (GoTools LRSplineSurface / LRSplineVolume);
//   .json whose "kind" is lr_surface/lr_volume, or whose first "objects" entry has one of those kinds.
// The first object decides: a .g2 or .json file mixing LR and tensor objects is rejected by the reader of the
// first object's kind, whose one-line error names the file, line (or JSON path) and the foreign object.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "trivar/io/lr_vtk.hpp"
#include "trivar/lr/any_lr_spline.hpp"
#include "trivar/lr/linear_independence.hpp"

namespace trivar::cli {

// The LR splines of `path` when it holds LR splines (see above), or nothing; throws trivar::Error naming the
// file when it is an LR file that does not parse.
std::optional<std::vector<AnyLRSpline>> read_lr_if_any(const std::string& path);

// The objects of `path` as LR splines: an LR file as it is, tensor surfaces and volumes converted exactly.
// Throws trivar::Error "<command>: ..." for a curve.
std::vector<AnyLRSpline> read_as_lr(const std::string& path, const std::string& command);

// True for the extensions written by write_lr_file: .lr, .g2, .json, .vtu (case-insensitive).
bool lr_output_extension(const std::string& path);
// True for .lr, the only extension that always means LR output.
bool is_lr_extension(const std::string& path);
// Writes by extension: .lr (LRsplines), .g2 (293/793), .json (lr_surface/lr_volume), .vtu (one piece per
// object, `vtk` options). Any other extension throws trivar::Error "<command>: ..."; nothing is written on error.
void write_lr_file(const std::string& path, const std::vector<AnyLRSpline>& objects, const std::string& command,
                   const io::LRVtkOptions& vtk = {});

// What `info` reports about one LR spline; `check` is "" (no test), "peeling" or "exact".
nlohmann::json describe_lr(const AnyLRSpline& s, const std::string& check);
// The text form of describe_lr's document (indented lines for one object).
void print_lr_text(const nlohmann::json& d);

}  // namespace trivar::cli
