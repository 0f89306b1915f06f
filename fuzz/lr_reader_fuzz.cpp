// libFuzzer target for the .lr reader: any input must read or throw trivar::Error; every LR spline read must
// evaluate (value and first derivatives at the corners and the centre of its domain) and come back from a
// write and a second read with the same B-spline and element counts. A violation traps.
// Build and run: see fuzz/CMakeLists.txt.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "spline_checks.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/lr_format.hpp"

using namespace trivar;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<AnyLRSpline> objects;
  try {
    objects = io::parse_lr(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.lr");
  } catch (const Error&) {
    return 0;
  }
  for (const AnyLRSpline& any : objects) {
    std::visit(
        []<int D>(const LRSpline<D>& s) {
          const Box<D> dom = s.domain();
          std::vector<double> out(static_cast<std::size_t>((D + 1) * s.dim()));
          for (int corner = 0; corner <= (1 << D); ++corner) {
            const Param<D> u = fuzz::corner_or_centre(dom, corner);
            s.eval(u, out.data());
            s.eval_first_derivatives(u, out.data());
          }
          std::ostringstream text;
          io::write_lr(text, AnyLRSpline(s));
          const std::vector<AnyLRSpline> back = io::parse_lr(text.str(), "round trip");
          const auto& b = std::get<LRSpline<D>>(back.at(0));
          if (back.size() != 1 || b.num_basis() != s.num_basis() || b.num_elements() != s.num_elements())
            __builtin_trap();
        },
        any);
  }
  return 0;
}
