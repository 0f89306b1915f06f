// libFuzzer target for the JSON spline and V-model reader: any input must read or throw trivar::Error, and
// every spline read must evaluate and round-trip (spline_checks.hpp). Crashes, sanitizer reports, hangs and
// other exceptions are findings. Build and run: see fuzz/CMakeLists.txt.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "spline_checks.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/vmodel_json.hpp"

using namespace trivar;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json doc = io::parse_json_document(text, "fuzz.json");
    if (io::is_vmodel_json(doc)) {
      const VModel m = io::vmodel_from_json(doc, "fuzz.json");
      for (int c = 0; c < m.num_cells(); ++c) fuzz::check_spline(AnySpline(m.cell(c).geometry()));
      if (io::vmodel_from_json(io::to_json(m), "round trip").num_cells() != m.num_cells()) __builtin_trap();
      return 0;
    }
    for (const auto& [j, where] : io::object_documents(doc, "fuzz.json", "spline"))
      fuzz::check_spline(io::spline_from_json(j, where));
  } catch (const Error&) {
  }
  return 0;
}
