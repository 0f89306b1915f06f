#pragma once
// Reading test outputs back: the values of one DataArray of an ASCII .vtu file.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace trivar::test {

// The values of the first DataArray named `name` ("" for the points), parsed as doubles.
inline std::vector<double> vtu_array(const std::string& xml, const std::string& name) {
  const std::string tag = name.empty() ? "<Points>" : "Name=\"" + name + "\"";
  std::size_t at = xml.find(tag);
  EXPECT_NE(at, std::string::npos) << name;
  if (at == std::string::npos) return {};
  at = xml.find('>', name.empty() ? xml.find("<DataArray", at) : at) + 1;
  std::istringstream in(xml.substr(at, xml.find("</DataArray>", at) - at));
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

}  // namespace trivar::test
