#pragma once
// trivar::Error: the one exception type of the library. Its message is a single line that names what was
// wrong and where (file, line, entity, direction, index), so the CLI can print it verbatim.
#include <stdexcept>
#include <string>

namespace trivar {

class Error : public std::runtime_error {
public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// Throws Error(message) when the condition is false; used for input validation, never for internal logic.
inline void require(bool condition, const std::string& message) {
  if (!condition) throw Error(message);
}

}  // namespace trivar
