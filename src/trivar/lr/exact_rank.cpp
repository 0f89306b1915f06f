#include "trivar/lr/exact_rank.hpp"

#include <cmath>

namespace trivar {

ModP::ModP(double x) {
  if (x == 0.0) return;
  int e = 0;
  const double m = std::frexp(std::abs(x), &e);  // |x| = m 2^e, m in [0.5, 1)
  const auto mant = static_cast<std::uint64_t>(std::ldexp(m, 53));  // |x| = mant 2^(e - 53), exact
  int shift = (e - 53) % 61;
  if (shift < 0) shift += 61;
  v_ = reduce(static_cast<UInt128>(mant % kP) << shift);
  if (x < 0.0 && v_ != 0) v_ = kP - v_;
}

ModP ModP::inverse() const {
  if (v_ == 0) throw UnluckyPrime{};
  // Fermat: a^(p-2) = a^-1.
  ModP r(1), b = *this;
  for (std::uint64_t e = kP - 2; e; e >>= 1) {
    if (e & 1) r = r * b;
    b = b * b;
  }
  return r;
}

}  // namespace trivar
