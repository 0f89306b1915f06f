#pragma once
// P21 reals in their shortest exactly round-tripping form (std::to_chars), reshaped to the P21 grammar:
// a decimal point always (1., 0.5, -0.), exponent as E with no '+' (1.E300, 2.5E-7).
#include <string>

namespace trivar::io::step {

// Appends the P21 text of x; throws trivar::Error for infinities and NaN, which P21 cannot express.
void append_real(std::string& out, double x);
std::string format_real(double x);

}  // namespace trivar::io::step
