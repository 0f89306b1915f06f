#pragma once
// Reader for ISO 10303-21 exchange structures (editions 2 and 3): header, any number of DATA sections
// (their optional section parameters are accepted and dropped; all instances share one id space), and
// edition 3 ANCHOR, REFERENCE and SIGNATURE sections, which are skipped. Written by hand: no packaged
// library covers the Part 42 volume and locally refined entities (docs/step.md).
//
// Streaming: the input is read in chunks and only the instances the filter keeps are built, so memory is
// proportional to what is kept (plus a compact set of the ids seen). Dropped instances are skipped
// without tokenising their bodies, so syntax errors inside them go unnoticed.
//
// Errors are trivar::Error with one line "file:line:column: #id: message" (the id when inside an instance).
// After reading, references are resolved: one from a kept instance to an instance that is neither kept nor
// dropped by the filter is an error. Departures from the standard that real files carry (lower-case
// keywords, stray bytes in strings, dangling references in dropped instances, reference cycles) are
// accepted with one warning line per kind in ExchangeFile::warnings, or refused in strict mode.
#include <functional>
#include <istream>
#include <string>
#include <string_view>

#include "trivar/io/step/exchange_file.hpp"

namespace trivar::io::step {

struct ReadOptions {
  // Decides by entity keyword (upper case) whether an instance is kept; a complex instance is kept when
  // any of its partial records is. Empty: keep everything.
  std::function<bool(std::string_view keyword)> keep;
  bool check_references = true;  // dangling references (and cycles, as warnings) after reading
  // Hold unnamed CARTESIAN_POINTs compactly (ExchangeFile::point) instead of as generic instances.
  bool compact_points = false;
  // Refuse what is otherwise accepted with a warning (read_warnings.hpp), at its first occurrence.
  bool strict = false;
  std::size_t chunk_size = 1 << 20;  // bytes read at a time from a stream
};

ExchangeFile read_exchange_file(const std::string& path, const ReadOptions& options = {});
ExchangeFile read_exchange_file(std::istream& in, const std::string& name, const ReadOptions& options = {});
// Parses text in memory (tests, fuzzing); `name` prefixes messages.
ExchangeFile parse_exchange_file(std::string_view text, const std::string& name = "<memory>",
                                 const ReadOptions& options = {});

}  // namespace trivar::io::step
