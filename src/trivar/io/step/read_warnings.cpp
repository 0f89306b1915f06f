#include "trivar/io/step/read_warnings.hpp"

#include "trivar/core/error.hpp"

namespace trivar::io::step {

std::string ReadWarning::text() const {
  return count > 1 ? first + " (" + std::to_string(count) + " occurrences in the file)" : first;
}

void ReadWarnings::add(Departure kind, std::string first) {
  if (strict_) throw Error(first + " (strict reading)");
  list_.push_back({kind, std::move(first), 1});
}

}  // namespace trivar::io::step
