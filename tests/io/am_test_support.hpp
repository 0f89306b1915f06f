#pragma once
// Support for the AM output tests (3MF, AMF): an independent ZIP reader (central directory + zlib inflate),
// a minimal XML scanner (well-formedness of the tag structure, elements by name with attributes and text) and
// a closed test mesh.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "trivar/model/triangle_mesh.hpp"

namespace trivar::test {

inline std::string read_binary(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Entries of a ZIP archive by name, read through the central directory; checks each CRC.
inline std::map<std::string, std::string> read_zip(const std::string& bytes) {
  auto u16 = [&](std::size_t at) {
    return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes.at(at)) |
                                      static_cast<unsigned char>(bytes.at(at + 1)) << 8);
  };
  auto u32 = [&](std::size_t at) { return u16(at) | u16(at + 2) << 16; };
  const std::size_t eocd = bytes.rfind(std::string("PK\x05\x06", 4));
  if (eocd == std::string::npos) throw std::runtime_error("zip: no end of central directory");
  const std::uint32_t count = u16(eocd + 10);
  std::size_t at = u32(eocd + 16);
  std::map<std::string, std::string> out;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (u32(at) != 0x02014b50) throw std::runtime_error("zip: bad central directory entry");
    const std::uint32_t method = u16(at + 10), crc = u32(at + 16), csize = u32(at + 20), size = u32(at + 24);
    const std::uint32_t name_len = u16(at + 28), extra = u16(at + 30), comment = u16(at + 32), offset = u32(at + 42);
    const std::string name = bytes.substr(at + 46, name_len);
    at += 46 + name_len + extra + comment;
    if (u32(offset) != 0x04034b50 || u32(offset + 14) != crc) throw std::runtime_error("zip: bad local header " + name);
    const std::size_t data = offset + 30 + u16(offset + 26) + u16(offset + 28);
    std::string content;
    if (method == 0) {
      content = bytes.substr(data, csize);
    } else if (method == 8) {
      content.resize(size);
      z_stream zs{};
      inflateInit2(&zs, -15);
      zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + data));
      zs.avail_in = csize;
      zs.next_out = reinterpret_cast<Bytef*>(content.data());
      zs.avail_out = size;
      const int rc = inflate(&zs, Z_FINISH);
      inflateEnd(&zs);
      if (rc != Z_STREAM_END || zs.total_out != size) throw std::runtime_error("zip: inflate failed for " + name);
    } else {
      throw std::runtime_error("zip: unknown method for " + name);
    }
    if (crc32(0L, reinterpret_cast<const Bytef*>(content.data()), static_cast<uInt>(content.size())) != crc)
      throw std::runtime_error("zip: CRC mismatch for " + name);
    out[name] = content;
  }
  return out;
}

struct XmlElement {
  std::map<std::string, std::string> attributes;
  std::string text;  // raw content up to the matching end tag (empty for <x/>)
};

// True when every start tag has its end tag in order (declarations, comments and <x/> aside).
inline bool well_formed(const std::string& xml) {
  std::vector<std::string> open;
  for (std::size_t at = xml.find('<'); at != std::string::npos; at = xml.find('<', at + 1)) {
    const std::size_t end = xml.find('>', at);
    if (end == std::string::npos) return false;
    const std::string tag = xml.substr(at + 1, end - at - 1);
    if (tag.empty() || tag[0] == '?' || tag[0] == '!') continue;
    if (tag.back() == '/') continue;
    const std::string name = tag.substr(tag[0] == '/' ? 1 : 0, tag.find_first_of(" \t\n/", 1) - (tag[0] == '/' ? 1 : 0));
    if (tag[0] == '/') {
      if (open.empty() || open.back() != name) return false;
      open.pop_back();
    } else {
      open.push_back(name);
    }
  }
  return open.empty();
}

// All elements named `name` in document order; names do not nest within themselves in the tested formats.
inline std::vector<XmlElement> elements(const std::string& xml, const std::string& name) {
  std::vector<XmlElement> out;
  const std::string open = "<" + name;
  for (std::size_t at = xml.find(open); at != std::string::npos; at = xml.find(open, at + 1)) {
    const char after = xml.at(at + open.size());
    if (after != ' ' && after != '>' && after != '/' && after != '\n') continue;
    const std::size_t end = xml.find('>', at);
    XmlElement e;
    std::string attrs = xml.substr(at + open.size(), end - at - open.size());
    for (std::size_t p = attrs.find('='); p != std::string::npos; p = attrs.find('=', p + 1)) {
      const std::size_t key_start = attrs.find_last_of(" \n\t", p) + 1;
      const std::size_t q = attrs.find('"', p + 2);
      e.attributes[attrs.substr(key_start, p - key_start)] = attrs.substr(p + 2, q - p - 2);
      p = q;
    }
    if (xml.at(end - 1) != '/') {
      const std::size_t close = xml.find("</" + name + ">", end);
      e.text = xml.substr(end + 1, close - end - 1);
    }
    out.push_back(std::move(e));
  }
  return out;
}

// A closed, outward-oriented octahedron with vertices at +-1 on the axes, scaled by s (volume 4/3 s^3).
inline TriangleMesh octahedron(double s = 1) {
  TriangleMesh m;
  m.vertices = {{s, 0, 0}, {-s, 0, 0}, {0, s, 0}, {0, -s, 0}, {0, 0, s}, {0, 0, -s}};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

}  // namespace trivar::test
