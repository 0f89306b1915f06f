#pragma once
// Reading test outputs back with an independent reader: tests/support/read_vtu.py (Python's xml, zlib and
// struct) checks the binary .vtu format and prints every array, which this parses.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace trivar::test {

struct VtuPiece {
  long long points = 0, cells = 0;
  std::map<std::string, std::vector<double>> arrays;  // by Name; the coordinates under "Points"
  std::map<std::string, int> components;
  std::string point_data_tag, cell_data_tag;  // the attributes of <PointData> / <CellData>, "key=value ..."
};

// Every piece of the file; fails the test (and returns none) when the reader rejects the file.
inline std::vector<VtuPiece> read_vtu_pieces(const std::string& path) {
  const std::string command = "python3 " TRIVAR_TEST_DATA "/../support/read_vtu.py '" + path + "'";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string text;
  char buffer[1 << 16];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe.get())) > 0;) text.append(buffer, n);
  const int status = pclose(pipe.release());
  EXPECT_EQ(status, 0) << "read_vtu.py rejects " << path;
  if (status != 0) return {};
  std::vector<VtuPiece> pieces;
  std::istringstream in(text);
  for (std::string word; in >> word;) {
    if (word == "piece") {
      in >> pieces.emplace_back().points >> pieces.back().cells;
    } else if (word == "PointData" || word == "CellData") {
      std::string rest;
      std::getline(in, rest);
      (word == "PointData" ? pieces.back().point_data_tag : pieces.back().cell_data_tag) = rest;
    } else if (word == "array") {
      std::string name;
      std::size_t count = 0;
      in >> name >> pieces.back().components[name] >> count;
      std::vector<double>& v = pieces.back().arrays[name];
      v.resize(count);
      for (double& x : v) in >> x;
    }
  }
  return pieces;
}

// The one piece of a file written from one object.
inline VtuPiece read_vtu(const std::string& path) {
  std::vector<VtuPiece> pieces = read_vtu_pieces(path);
  EXPECT_EQ(pieces.size(), 1u) << path;
  return pieces.empty() ? VtuPiece{} : pieces.front();
}

// The values of the array `name` ("" for the points) of the first piece.
inline std::vector<double> vtu_array(const std::string& path, const std::string& name) {
  const std::vector<VtuPiece> pieces = read_vtu_pieces(path);
  if (pieces.empty()) return {};
  const auto it = pieces.front().arrays.find(name.empty() ? "Points" : name);
  EXPECT_NE(it, pieces.front().arrays.end()) << name;
  return it == pieces.front().arrays.end() ? std::vector<double>{} : it->second;
}

}  // namespace trivar::test
