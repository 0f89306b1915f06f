#pragma once
// Shared helpers of the STEP tests: reading test data and a minimal valid file around a data section.
#include <fstream>
#include <sstream>
#include <string>

namespace trivar::test {

inline std::string step_data(const std::string& name) { return std::string(TRIVAR_TEST_DATA) + "/step/" + name; }

inline std::string slurp_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A complete exchange structure with the given DATA section body.
inline std::string step_file(const std::string& data) {
  return "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
         "FILE_SCHEMA(('TEST'));\nENDSEC;\nDATA;\n" +
         data + "\nENDSEC;\nEND-ISO-10303-21;\n";
}

}  // namespace trivar::test
