#pragma once
// trivar::Error: the one exception type of the library. Its message is a single line that names what was
// wrong and where (file, line, entity, direction, index), so the CLI can print it verbatim.
#include <stdexcept>
#include <string>
#include <type_traits>

namespace trivar {

class Error : public std::runtime_error {
public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// Throws Error(message) when the condition is false; used for input validation, never for internal logic.
inline void require(bool condition, const std::string& message) {
  if (!condition) throw Error(message);
}

// As above with the message built only on failure, for checks on paths that run per element or per point.
template <class MakeMessage>
  requires std::is_invocable_r_v<std::string, MakeMessage>
inline void require(bool condition, MakeMessage&& make_message) {
  if (!condition) throw Error(make_message());
}

// Throws unless dir is a parametric direction of a D-variate object, naming the operation `what`.
inline void require_direction(int dir, int D, const char* what) {
  require(dir >= 0 && dir < D, [&] {
    return std::string(what) + ": direction " + std::to_string(dir) + " out of range [0, " + std::to_string(D) + ")";
  });
}

}  // namespace trivar
