#pragma once
// Spline files by extension (case-insensitive): .json (native, json_format.hpp), .g2 (GoTools, g2_format.hpp)
// and, for writing only, .vtu (VTK XML for ParaView, vtk_writer.hpp, default VtkOptions).
#include <string>
#include <vector>

#include "trivar/spline/any_spline.hpp"

namespace trivar::io {

// .json or .g2; throws trivar::Error naming the file for any other extension (.vtu is output only).
std::vector<AnySpline> read_spline_file(const std::string& path);

// .json, .g2 or .vtu (every object becomes one VTU piece). Nothing is written on error.
void write_spline_file(const std::string& path, const std::vector<AnySpline>& objects);

}  // namespace trivar::io
