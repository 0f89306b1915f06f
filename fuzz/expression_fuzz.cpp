// libFuzzer target for the expression compiler: any text must compile or throw trivar::Error, and a compiled
// expression must evaluate within its fixed stack (AddressSanitizer reports any access outside it).
// Build and run: see fuzz/CMakeLists.txt.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "trivar/core/error.hpp"
#include "trivar/model/expression.hpp"

using namespace trivar;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const double vars[3] = {0.25, -1.5, 3.0};
  try {
    volatile double sink = Expression::parse(text, {"x", "y", "z"}).eval(vars);
    (void)sink;
  } catch (const Error&) {
  }
  return 0;
}
