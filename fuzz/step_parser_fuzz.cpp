// libFuzzer target for the ISO 10303-21 reader and the Part 42 geometry mapping on top of it: any input must
// parse (and map) or throw trivar::Error, and what parses must write and read back, the mapped geometry
// included. Crashes, sanitizer reports, hangs and other exceptions are findings.
// Build and run: see fuzz/CMakeLists.txt and docs/step.md.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include "trivar/core/error.hpp"
#include "trivar/io/step/geometry_writer.hpp"
#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/step_file.hpp"
#include "trivar/io/step/writer.hpp"

using namespace trivar::io::step;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  ReadOptions options;
  // The first byte picks the path: whole text, chunked stream, stream with a keyword filter (skip path), or
  // the geometry mapping; and whether the reading is strict.
  const int mode = size ? data[0] % 4 : 0;
  if (mode == 2) options.keep = [](std::string_view k) { return k.size() % 2 == 0; };
  options.chunk_size = 7;
  options.strict = size && (data[0] & 4);
  try {
    if (mode == 3) {
      const StepContents c = parse_step(text, "fuzz.stp", options.strict);
      if (c.splines.empty() && c.lr_splines.empty()) return 0;
      std::ostringstream out;
      WriteOptions w;
      w.time_stamp = "2026-01-01T00:00:00";
      write_exchange_file(out, geometry_exchange_file(c.splines, c.lr_splines), w);
      const StepContents back = parse_step(out.str(), "rewritten.stp");
      if (back.splines.size() != c.splines.size() || back.lr_splines.size() != c.lr_splines.size()) __builtin_trap();
      return 0;
    }
    ExchangeFile file;
    if (mode == 0) {
      file = parse_exchange_file(text, "fuzz.stp", options);
    } else {
      std::istringstream in{std::string(text)};
      file = read_exchange_file(in, "fuzz.stp", options);
    }
    if (!file.header.schemas.empty() && file.skipped_total() == 0) {
      std::ostringstream out;
      WriteOptions w;
      w.time_stamp = "2026-01-01T00:00:00";
      write_exchange_file(out, file, w);
      if (parse_exchange_file(out.str(), "rewritten.stp").size() != file.size()) __builtin_trap();
    }
  } catch (const trivar::Error&) {
  }
  return 0;
}
