#pragma once
// Shortest text that reads back as exactly the same double (std::to_chars), for messages and text formats.
#include <charconv>
#include <ostream>
#include <string>

namespace trivar {

inline std::string format_number(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

inline void write_number(std::ostream& os, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  os.write(buf, r.ptr - buf);
}

}  // namespace trivar
