#pragma once
// The benchmark volumes: a unit cube of the given degree and elements whose Greville control points are
// moved by a smooth near-identity deformation (amplitude a, positive Jacobian for a <= 0.15), optionally made
// rational with varied weights so the homogeneous code paths are measured; and the random parameters at
// which the benchmarks evaluate them.
#include <cmath>
#include <random>
#include <vector>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar::bench {

inline SplineVolume perturbed_cube(int degree, int elements, double a = 0.05, bool rational = false) {
  std::array<KnotVector, 3> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(degree, elements);
  const int n = kv[0].size();
  const auto g = kv[0].greville();
  std::vector<double> pts, w;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = g[i], y = g[j], z = g[k];
        pts.insert(pts.end(), {x + a * std::sin(3 * y), y + a * std::sin(3 * z), z + a * std::sin(3 * x)});
        if (rational) w.push_back(1.0 + 0.2 * std::sin(0.37 * static_cast<double>(w.size())));
      }
  return SplineVolume::from_cartesian(kv, 3, pts, w);
}

// n parameters uniformly random in [0, 1]^D, the same sequence in every benchmark (seed 42).
template <int D>
std::vector<Param<D>> random_params(std::size_t n) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<Param<D>> u(n);
  for (auto& x : u)
    for (auto& c : x) c = U(rng);
  return u;
}

}  // namespace trivar::bench
