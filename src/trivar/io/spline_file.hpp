#pragma once
// Spline files by extension (case-insensitive). One table (file_formats) names every extension trivar reads or
// writes and is what all dispatch by extension and all messages listing extensions go through, so they agree:
// .json (native, json_format.hpp), .g2 (GoTools, g2_format.hpp), .lr (LRsplines text, lr_format.hpp),
// .stp/.step/.p21 (ISO 10303-21, step/step_file.hpp), .xml (G+Smo, gismo_xml.hpp) and, for writing only, .vtu
// (VTK XML for ParaView).
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "trivar/spline/any_spline.hpp"

namespace trivar::io {

enum class FileFormat { json, g2, lr, step, gismo_xml, vtu };

struct FileFormatEntry {
  const char* extension;  // lower case, with the dot
  FileFormat format;
  bool readable;  // false: output only
};

// The extension of `path` in lower case, with the dot ("" when it has none): what every dispatch compares.
std::string file_extension(const std::string& path);
// Every extension trivar knows, in the order messages list them.
std::span<const FileFormatEntry> file_formats();
// The readable (or, with reading = false, all) extensions as a message lists them: ".json, .g2, ... or .p21".
std::string extension_list(bool reading);
// The entry of `path`'s extension, or nothing for an extension not in the table.
std::optional<FileFormat> format_of(const std::string& path);
// The format of `path` by its extension; throws trivar::Error naming the file and listing the extensions of
// extension_list(reading) for any other extension.
FileFormat file_format(const std::string& path, bool reading);

// The tensor-product splines of a .json, .g2, STEP or G+Smo file; throws trivar::Error naming the file for an
// output-only or unknown extension, for an .lr file or STEP locally refined objects (read them as LR) and for
// hierarchical splines in a G+Smo file (gismo_xml.hpp reads them).
std::vector<AnySpline> read_spline_file(const std::string& path);

// .json, .g2, .xml (surfaces and volumes) or .vtu (every object becomes one VTU piece). Nothing is written on
// error.
void write_spline_file(const std::string& path, const std::vector<AnySpline>& objects);

}  // namespace trivar::io
