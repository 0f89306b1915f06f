#pragma once
// ZipWriter: a minimal ZIP archive writer (PKWARE APPNOTE 6.3, deflate or stored, no ZIP64, no encryption),
// enough for OPC packages (3MF) and zipped AMF. Entries are held in memory by the caller and written with their
// sizes in the local header (no data descriptors). Every entry carries the same fixed time stamp
// (1980-01-01 00:00) so identical content gives byte-identical archives.
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace trivar::io {

class ZipWriter {
public:
  // Writes to `out` as entries are added; `out` must outlive the writer.
  explicit ZipWriter(std::ostream& out) : out_(out) {}

  // Appends one entry (a '/'-separated name, no leading '/'). Throws trivar::Error for an empty or repeated
  // name, sizes beyond 4 GiB, more than 65535 entries, a call after finish() or a failing stream.
  void add(const std::string& name, std::string_view data, bool compress = true);

  // Writes the central directory; no entry can be added afterwards.
  void finish();

private:
  struct Entry {
    std::string name;
    std::uint32_t crc = 0, compressed = 0, size = 0, offset = 0;
    std::uint16_t method = 0;
  };

  void put(const void* data, std::size_t n);

  std::ostream& out_;
  std::vector<Entry> entries_;
  std::uint64_t position_ = 0;
  bool finished_ = false;
};

}  // namespace trivar::io
