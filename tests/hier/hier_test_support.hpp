#pragma once
// Fixtures of the hierarchical-spline tests: tensor splines with generic coefficients and random refinements.
#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "trivar/hier/hierarchical_spline.hpp"

namespace trivar::test {

// A tensor spline on [0, 1]^D with `elements` uniform spans of degree p per direction and control values that
// are generic (pseudo-random), `dim` per point, rational with positive weights when asked.
template <int D>
TensorSpline<D> generic_spline(int p, int elements, int dim, bool rational, unsigned seed = 1) {
  std::array<KnotVector, D> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(p, elements);
  int n = 1;
  for (const auto& k : kv) n *= k.size();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> x(-1.0, 1.0), w(0.5, 2.0);
  const int st = dim + (rational ? 1 : 0);
  std::vector<double> c(static_cast<std::size_t>(n) * st);
  for (int i = 0; i < n; ++i) {
    const double wi = rational ? w(rng) : 1.0;
    for (int d = 0; d < dim; ++d) c[static_cast<std::size_t>(i) * st + d] = wi * x(rng);
    if (rational) c[static_cast<std::size_t>(i) * st + dim] = wi;
  }
  return TensorSpline<D>(kv, dim, rational, c);
}

template <int D>
std::vector<Param<D>> random_points(int n, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Param<D>> pts(static_cast<std::size_t>(n));
  for (auto& p : pts)
    for (auto& x : p) x = u(rng);
  return pts;
}

// Refines `steps` times a random fifth of the elements (at least one), always including the element at the
// corner u = 0, so the hierarchy gets deep there.
template <int D>
void refine_randomly(HierarchicalSpline<D>& s, int steps, unsigned seed = 3) {
  std::mt19937 rng(seed);
  for (int i = 0; i < steps; ++i) {
    const int E = s.space().num_elements();
    std::vector<int> marked{s.space().find_element(Param<D>{})};
    std::uniform_int_distribution<int> pick(0, E - 1);
    for (int j = 0; j < E / 5; ++j) marked.push_back(pick(rng));
    s.refine_elements(marked);
  }
}

// The largest number of successive levels, and of functions, acting on one element (THB: the truncated
// functions non-zero there; HB: the B-splines).
template <int D>
std::pair<int, int> levels_and_functions_per_element(const HierarchicalSpace<D>& s) {
  int levels = 0, functions = 0;
  for (int e = 0; e < s.num_elements(); ++e) {
    const auto el = s.element_operator(e);
    int lo = 1 << 20, hi = -1;
    for (int id : el.ids) {
      lo = std::min(lo, s.function(id).level);
      hi = std::max(hi, s.function(id).level);
    }
    levels = std::max(levels, hi - lo + 1);
    functions = std::max(functions, static_cast<int>(el.ids.size()));
  }
  return {levels, functions};
}

}  // namespace trivar::test
