#pragma once
// Point files for scattered-data fitting: rows of numbers, as plain text / CSV or as trivar's binary point
// format. Written by hand because no Debian package reads these simple layouts into memory for us (the LAS
// readers liblas and PDAL are not packaged in Debian 12).
//
// Text: one point per line, numbers separated by blanks, commas or semicolons; '#' starts a comment; blank lines
// are skipped; one header line of names (no number in it) may come first. Every row has the same count.
// Binary (.tvp): the 8 bytes "TRIVARPT", uint32 columns (1..64), uint32 0, uint64 rows, then rows * columns
// IEEE float64, all little-endian, row-major; the file size must match exactly.
#include <string>
#include <string_view>

#include "trivar/fit/scattered_data.hpp"

namespace trivar {

// Reads either format (binary when the file starts with the magic). Throws trivar::Error with a one-line message
// naming the file and line (text) or byte offset (binary): unreadable file, empty file, a token that is not a
// number, a number that is not finite, rows of different lengths, a truncated or oversized binary file, or more
// memory than available.
PointTable read_point_file(const std::string& path);

// The same from bytes in memory; `name` prefixes messages.
PointTable parse_point_bytes(std::string_view bytes, const std::string& name);

// Writes the binary format atomically (for tests, benchmarks and conversions).
void write_point_file(const std::string& path, const PointTable& table);

}  // namespace trivar
