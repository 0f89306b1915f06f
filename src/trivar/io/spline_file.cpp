#include "trivar/io/spline_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>

#include "trivar/core/error.hpp"
#include "trivar/io/g2_format.hpp"
#include "trivar/io/gismo_xml.hpp"
#include "trivar/io/json_format.hpp"
#include "trivar/io/step/step_file.hpp"
#include "trivar/io/vtk_writer.hpp"

namespace trivar::io {

namespace {

constexpr std::array<FileFormatEntry, 8> kFormats{{{".json", FileFormat::json, true},
                                                   {".g2", FileFormat::g2, true},
                                                   {".lr", FileFormat::lr, true},
                                                   {".stp", FileFormat::step, true},
                                                   {".step", FileFormat::step, true},
                                                   {".p21", FileFormat::step, true},
                                                   {".xml", FileFormat::gismo_xml, true},
                                                   {".vtu", FileFormat::vtu, false}}};

}  // namespace

std::string file_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::span<const FileFormatEntry> file_formats() { return kFormats; }

std::string extension_list(bool reading) {
  std::vector<std::string> names;
  for (const FileFormatEntry& f : kFormats)
    if (f.readable || !reading) names.emplace_back(f.extension);
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i)
    s += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return s;
}

std::optional<FileFormat> format_of(const std::string& path) {
  const std::string ext = file_extension(path);
  for (const FileFormatEntry& f : kFormats)
    if (ext == f.extension) return f.format;
  return std::nullopt;
}

FileFormat file_format(const std::string& path, bool reading) {
  const std::string ext = file_extension(path);
  for (const FileFormatEntry& f : kFormats)
    if (ext == f.extension) {
      require(f.readable || !reading, [&] {
        return path + ": " + ext + " is an output-only format; read " + extension_list(true);
      });
      return f.format;
    }
  throw Error(path + ": unknown spline file extension '" + ext + "' (expected " + extension_list(reading) + ")");
}

std::vector<AnySpline> read_spline_file(const std::string& path) {
  switch (file_format(path, true)) {
    case FileFormat::json: return read_json(path);
    case FileFormat::g2: return read_g2(path);
    case FileFormat::step: {
      step::StepContents c = step::read_step(path);
      require(c.lr_splines.empty(), [&] {
        return path + ": holds " + std::to_string(c.lr_splines.size()) +
               " locally refined objects; this command reads tensor-product splines only";
      });
      return std::move(c.splines);
    }
    case FileFormat::gismo_xml: {
      std::vector<AnySpline> out;
      for (auto& g : read_gismo_xml(path)) {
        require(g.index() < 2, [&] {
          return path + ": holds hierarchical splines; this command reads tensor-product splines only";
        });
        if (g.index() == 0) out.emplace_back(std::get<0>(std::move(g)));
        else out.emplace_back(std::get<1>(std::move(g)));
      }
      return out;
    }
    case FileFormat::lr:
    case FileFormat::vtu: break;
  }
  throw Error(path + ": an LR spline file; this command reads tensor-product splines only");
}

void write_spline_file(const std::string& path, const std::vector<AnySpline>& objects) {
  switch (file_format(path, false)) {
    case FileFormat::json: return write_json(path, objects);
    case FileFormat::g2: return write_g2(path, objects);
    case FileFormat::vtu: return write_vtu(path, objects);
    case FileFormat::gismo_xml: {
      std::vector<GismoGeometry> g;
      for (const AnySpline& s : objects) {
        require(s.index() > 0, path + ": G+Smo files take surfaces and volumes, not curves");
        if (s.index() == 1) g.emplace_back(std::get<1>(s));
        else g.emplace_back(std::get<2>(s));
      }
      return write_gismo_xml(path, g);
    }
    case FileFormat::lr:
    case FileFormat::step: break;
  }
  throw Error(path + ": " + file_extension(path) + " output takes LR splines or STEP conversion; write .json, .g2, .xml or .vtu");
}

}  // namespace trivar::io
