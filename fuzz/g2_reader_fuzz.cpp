// libFuzzer target for the g2 reader: any input must read or throw trivar::Error, and every spline read must
// evaluate and round-trip (spline_checks.hpp). Build and run: see fuzz/CMakeLists.txt.
#include <cstddef>
#include <cstdint>
#include <string>

#include "spline_checks.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/g2_format.hpp"

using namespace trivar;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    for (const AnySpline& s : io::parse_g2(std::string(reinterpret_cast<const char*>(data), size), "fuzz.g2"))
      fuzz::check_spline(s);
  } catch (const Error&) {
  }
  return 0;
}
