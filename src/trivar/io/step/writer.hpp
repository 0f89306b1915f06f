#pragma once
// Writer for ISO 10303-21 (edition 2 syntax). Header: FILE_DESCRIPTION(..,'2;1'), FILE_NAME with an
// ISO 8601 time stamp and preprocessor_version 'trivar <version>', FILE_SCHEMA, then any extra header
// entities. Instances are written in store order; by default renumbered #1, #2, ... in that order, so the
// output does not depend on the ids an object graph happened to get. Partial records of complex instances
// are written in ASCII alphabetical order, reals in shortest round-trip form (real_format.hpp), strings
// escaped (string_codec.hpp). Lines are broken after a comma once they pass `line_width`; strings are
// never split.
#include <ostream>
#include <string>

#include "trivar/io/step/exchange_file.hpp"

namespace trivar::io::step {

struct WriteOptions {
  std::string time_stamp;      // FILE_NAME.time_stamp; empty: the current UTC time, YYYY-MM-DDThh:mm:ss
  std::string version;         // written as 'trivar <version>'; empty: this build's version
  bool renumber = true;        // false keeps the ids of the store
  std::size_t line_width = 80; // soft limit
};

// The current UTC time in ISO 8601 (2026-01-31T12:00:00).
std::string iso8601_now();

// Throws trivar::Error for non-finite reals, invalid UTF-8 in strings, keywords that are not P21 keywords,
// or references to ids that are not in the store when renumbering.
void write_exchange_file(std::ostream& out, const ExchangeFile& file, const WriteOptions& options = {});
// Atomic: nothing is left behind at `path` when writing fails.
void write_exchange_file(const std::string& path, const ExchangeFile& file, const WriteOptions& options = {});

}  // namespace trivar::io::step
