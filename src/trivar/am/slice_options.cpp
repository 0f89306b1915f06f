#include "trivar/am/slice_options.hpp"

#include <utility>

#include "trivar/core/error.hpp"

namespace trivar::am {

namespace {

constexpr std::pair<Tracing, const char*> kTracingNames[] = {{Tracing::none, "none"},
                                                             {Tracing::previous_point, "previous-point"},
                                                             {Tracing::previous_line, "previous-line"},
                                                             {Tracing::full, "full"}};

}  // namespace

const char* to_string(Tracing t) {
  for (const auto& [value, name] : kTracingNames)
    if (value == t) return name;
  return "full";
}

Tracing parse_tracing(const std::string& name) {
  for (const auto& [value, text] : kTracingNames)
    if (name == text) return value;
  throw Error("slicer: unknown tracing '" + name + "' (none, previous-point, previous-line, full)");
}

}  // namespace trivar::am
