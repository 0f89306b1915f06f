#pragma once
// The T-spline side of `trivar info|eval|convert`: Rhino .tsm files.
#include <string>
#include <vector>

namespace trivar::cli {

// True for .tsm (case-insensitive).
bool is_tsm_file(const std::string& path);
void print_tspline_info(const std::string& path, bool json);
// Value (order 0) or value and first derivatives (order 1) at (s, t).
void eval_tspline(const std::string& path, const std::vector<double>& params, int order);

}  // namespace trivar::cli
