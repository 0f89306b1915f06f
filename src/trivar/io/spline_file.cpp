#include "trivar/io/spline_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "trivar/core/error.hpp"
#include "trivar/io/g2_format.hpp"
#include "trivar/io/json_format.hpp"
#include "trivar/io/vtk_writer.hpp"

namespace trivar::io {

namespace {

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

std::vector<AnySpline> read_spline_file(const std::string& path) {
  const std::string ext = extension(path);
  if (ext == ".json") return read_json(path);
  if (ext == ".g2") return read_g2(path);
  require(ext != ".vtu", path + ": .vtu is an output-only format; read .json or .g2");
  throw Error(path + ": unknown spline file extension '" + ext + "' (expected .json or .g2)");
}

void write_spline_file(const std::string& path, const std::vector<AnySpline>& objects) {
  const std::string ext = extension(path);
  if (ext == ".json") return write_json(path, objects);
  if (ext == ".g2") return write_g2(path, objects);
  if (ext == ".vtu") return write_vtu(path, objects);
  throw Error(path + ": unknown spline file extension '" + ext + "' (expected .json, .g2 or .vtu)");
}

}  // namespace trivar::io
