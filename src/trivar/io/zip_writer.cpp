#include "trivar/io/zip_writer.hpp"

#include <zlib.h>

#include <limits>

#include "trivar/core/error.hpp"

namespace trivar::io {

namespace {

constexpr std::uint64_t max32 = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint16_t dos_date_1980_01_01 = (0 << 9) | (1 << 5) | 1;

void le16(std::string& b, std::uint32_t v) {
  b.push_back(static_cast<char>(v & 0xff));
  b.push_back(static_cast<char>((v >> 8) & 0xff));
}
void le32(std::string& b, std::uint32_t v) {
  le16(b, v & 0xffff);
  le16(b, v >> 16);
}

// Raw deflate (no zlib header), as ZIP method 8 stores it.
std::string deflate_raw(std::string_view data, const std::string& name) {
  z_stream zs{};
  require(deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) == Z_OK,
          "zip: cannot start deflate for '" + name + "'");
  std::string out(deflateBound(&zs, static_cast<uLong>(data.size())), '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  require(rc == Z_STREAM_END, "zip: deflate failed for '" + name + "'");
  return out;
}

}  // namespace

void ZipWriter::put(const void* data, std::size_t n) {
  out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
  require(static_cast<bool>(out_), "zip: write failed");
  position_ += n;
}

void ZipWriter::add(const std::string& name, std::string_view data, bool compress) {
  require(!finished_, "zip: entry '" + name + "' added after finish");
  require(!name.empty() && name.front() != '/' && name.size() <= 0xffff, "zip: bad entry name '" + name + "'");
  for (const auto& e : entries_) require(e.name != name, "zip: entry '" + name + "' added twice");
  require(entries_.size() < 0xffff, "zip: more than 65535 entries need ZIP64");
  // uInt (zlib's length type) is 32-bit, the same bound ZIP without ZIP64 has.
  require(data.size() < max32 && position_ < max32, "zip: entry '" + name + "' needs ZIP64 (over 4 GiB)");

  Entry e;
  e.name = name;
  e.size = static_cast<std::uint32_t>(data.size());
  e.crc = static_cast<std::uint32_t>(crc32(0L, reinterpret_cast<const Bytef*>(data.data()), static_cast<uInt>(data.size())));
  e.offset = static_cast<std::uint32_t>(position_);
  std::string packed;
  if (compress) {
    packed = deflate_raw(data, name);
    // Incompressible data is stored: deflate would only grow it.
    if (packed.size() >= data.size()) {
      packed.clear();
      compress = false;
    }
  }
  e.method = compress ? 8 : 0;
  const std::string_view body = compress ? std::string_view(packed) : data;
  require(body.size() < max32 && position_ + 30 + name.size() + body.size() < max32,
          "zip: entry '" + name + "' needs ZIP64 (over 4 GiB)");
  e.compressed = static_cast<std::uint32_t>(body.size());

  std::string h;
  le32(h, 0x04034b50);
  le16(h, 20);  // version needed: 2.0 (deflate)
  le16(h, 0);   // flags
  le16(h, e.method);
  le16(h, 0);  // time 00:00
  le16(h, dos_date_1980_01_01);
  le32(h, e.crc);
  le32(h, e.compressed);
  le32(h, e.size);
  le16(h, static_cast<std::uint32_t>(name.size()));
  le16(h, 0);  // extra length
  h += name;
  put(h.data(), h.size());
  put(body.data(), body.size());
  entries_.push_back(std::move(e));
}

void ZipWriter::finish() {
  require(!finished_, "zip: finish called twice");
  finished_ = true;
  const std::uint64_t start = position_;
  for (const auto& e : entries_) {
    std::string h;
    le32(h, 0x02014b50);
    le16(h, 20);  // made by: MS-DOS attributes, version 2.0
    le16(h, 20);
    le16(h, 0);
    le16(h, e.method);
    le16(h, 0);
    le16(h, dos_date_1980_01_01);
    le32(h, e.crc);
    le32(h, e.compressed);
    le32(h, e.size);
    le16(h, static_cast<std::uint32_t>(e.name.size()));
    le16(h, 0);  // extra
    le16(h, 0);  // comment
    le16(h, 0);  // disk
    le16(h, 0);  // internal attributes
    le32(h, 0);  // external attributes
    le32(h, e.offset);
    h += e.name;
    put(h.data(), h.size());
  }
  require(position_ < max32, "zip: central directory beyond 4 GiB needs ZIP64");
  std::string end;
  le32(end, 0x06054b50);
  le16(end, 0);
  le16(end, 0);
  le16(end, static_cast<std::uint32_t>(entries_.size()));
  le16(end, static_cast<std::uint32_t>(entries_.size()));
  le32(end, static_cast<std::uint32_t>(position_ - start));
  le32(end, static_cast<std::uint32_t>(start));
  le16(end, 0);  // comment length
  put(end.data(), end.size());
}

}  // namespace trivar::io
