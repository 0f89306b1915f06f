#include "trivar/io/step/real_format.hpp"

#include <charconv>
#include <cmath>
#include <string_view>

#include "trivar/core/error.hpp"

namespace trivar::io::step {

void append_real(std::string& out, double x) {
  require(std::isfinite(x), "a P21 real must be finite");
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  const std::string_view text(buf, static_cast<std::size_t>(r.ptr - buf));
  const std::size_t e = text.find('e');
  const std::string_view mantissa = text.substr(0, e);
  out += mantissa;
  if (mantissa.find('.') == std::string_view::npos) out += '.';
  if (e != std::string_view::npos) {
    out += 'E';
    std::string_view exponent = text.substr(e + 1);
    if (exponent.front() == '+') exponent.remove_prefix(1);
    else if (exponent.front() == '-') out += '-', exponent.remove_prefix(1);
    while (exponent.size() > 1 && exponent.front() == '0') exponent.remove_prefix(1);  // to_chars pads to 2 digits
    out += exponent;
  }
}

std::string format_real(double x) {
  std::string s;
  append_real(s, x);
  return s;
}

}  // namespace trivar::io::step
