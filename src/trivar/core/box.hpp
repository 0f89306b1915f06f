#pragma once
// Axis-aligned boxes in parameter space (Param<D>) and in model space (any dimension known at compile time).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace trivar {

// The size is cast so that D is never deduced from these aliases: functions deduce D from the spline type.
template <int D>
using Param = std::array<double, static_cast<std::size_t>(D)>;
template <int D>
using Ints = std::array<int, static_cast<std::size_t>(D)>;

template <int D>
struct Box {
  std::array<double, D> lo{};
  std::array<double, D> hi{};

  static Box empty() {
    Box b;
    b.lo.fill(std::numeric_limits<double>::infinity());
    b.hi.fill(-std::numeric_limits<double>::infinity());
    return b;
  }
  void extend(const double* p) {
    for (int k = 0; k < D; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  bool contains(const std::array<double, D>& p, double tol = 0.0) const {
    for (int k = 0; k < D; ++k)
      if (p[k] < lo[k] - tol || p[k] > hi[k] + tol) return false;
    return true;
  }
  std::array<double, D> center() const {
    std::array<double, D> c;
    for (int k = 0; k < D; ++k) c[k] = 0.5 * (lo[k] + hi[k]);
    return c;
  }
  double extent(int k) const { return hi[k] - lo[k]; }
  double diagonal() const {
    double s = 0;
    for (int k = 0; k < D; ++k) s += extent(k) * extent(k);
    return std::sqrt(s);
  }
};

}  // namespace trivar
