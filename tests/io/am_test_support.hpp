#pragma once
// Support for the AM output tests (3MF, AMF): ZIP archives read and XML checked by independent readers
// (Python's zipfile and xml.etree), elements picked by name from a checked document, and a closed test mesh.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "trivar/model/triangle_mesh.hpp"

namespace trivar::test {

inline std::string read_binary(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// The standard output of `command`; fails the test when the command exits with a non-zero status.
inline std::string command_output(const std::string& command) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[1 << 16];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << command;
  return status == 0 ? out : std::string();
}

// Entries of a ZIP archive by name, read by Python's zipfile (tests/support/read_zip.py), which checks each CRC.
inline std::map<std::string, std::string> read_zip(const std::string& path) {
  const std::string out = command_output("python3 " TRIVAR_TEST_DATA "/../support/read_zip.py '" + path + "'");
  if (out.empty()) return {};
  return nlohmann::json::parse(out).get<std::map<std::string, std::string>>();
}

struct XmlElement {
  std::map<std::string, std::string> attributes;
  std::string text;  // raw content up to the matching end tag (empty for <x/>)
};

// True when Python's XML parser (xml.etree) accepts the document.
inline bool well_formed(const std::string& xml) {
  FILE* pipe = popen("python3 -c 'import sys, xml.etree.ElementTree as E; E.parse(sys.stdin.buffer)'", "w");
  std::fwrite(xml.data(), 1, xml.size(), pipe);
  return pclose(pipe) == 0;
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
