// libFuzzer target for the ISO 10303-21 reader: any input must parse or throw trivar::Error, and what
// parses must write and read back. Crashes, sanitizer reports, hangs and other exceptions are findings.
// Build and run: see fuzz/CMakeLists.txt and docs/step.md.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string_view>

#include "trivar/core/error.hpp"
#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/writer.hpp"

using namespace trivar::io::step;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  ReadOptions options;
  // The first byte picks the path: whole text, chunked stream, or stream with a keyword filter (skip path).
  const int mode = size ? data[0] % 3 : 0;
  if (mode == 2) options.keep = [](std::string_view k) { return k.size() % 2 == 0; };
  options.chunk_size = 7;
  try {
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
