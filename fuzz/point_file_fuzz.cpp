// libFuzzer target for the point-file reader of `trivar fit` (text / CSV and the binary .tvp format): any input
// must read or throw trivar::Error; a table read must be rectangular and finite, and turning it into surface or
// volume data must succeed or throw trivar::Error. A violation traps.
// Build and run: see fuzz/CMakeLists.txt.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "trivar/core/error.hpp"
#include "trivar/fit/point_file.hpp"

using namespace trivar;

namespace {

template <int D>
void to_data(const PointTable& t) {
  try {
    const ScatteredData<D> d = scattered_data<D>(t, "fuzz");
    if (d.size() != t.rows() || d.dim != t.columns - D) __builtin_trap();
  } catch (const Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  PointTable t;
  try {
    t = parse_point_bytes(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.xyz");
  } catch (const Error&) {
    return 0;
  }
  if (t.columns < 1 || t.values.size() % static_cast<std::size_t>(t.columns) != 0) __builtin_trap();
  for (double v : t.values)
    if (!std::isfinite(v)) __builtin_trap();
  to_data<2>(t);
  to_data<3>(t);
  return 0;
}
