// libFuzzer target for the G+Smo XML reader: any input must read or throw trivar::Error; every tensor spline
// read must evaluate and round-trip (spline_checks.hpp), every hierarchical spline evaluate at its domain's
// corners and centre and write back. Build and run: see fuzz/CMakeLists.txt.
#include <cstddef>
#include <cstdint>
#include <string>

#include "spline_checks.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/gismo_xml.hpp"

using namespace trivar;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto all = io::parse_gismo_xml(std::string(reinterpret_cast<const char*>(data), size), "fuzz.xml");
    for (const auto& g : all)
      std::visit(
          [](const auto& s) {
            if constexpr (requires { s.space(); }) {
              std::vector<double> out(static_cast<std::size_t>(s.dim()));
              auto box = s.domain();
              s.eval(box.lo, out.data());
              s.eval(box.hi, out.data());
              s.eval(box.center(), out.data());
            } else {
              fuzz::check_spline(AnySpline(s));
            }
          },
          g);
    io::gismo_xml_text(all);
  } catch (const Error&) {
  }
  return 0;
}
