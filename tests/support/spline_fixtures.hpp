#pragma once
// Shared test fixtures: random splines with non-uniform knots and repeated interior knots, random parameters,
// and a reference evaluator by the Cox-de Boor recursion (independent of the library's triangular scheme).
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar::test {

// Knot vector of degree p with `elements` non-uniform intervals on [a, b]; one interior knot doubled when
// there is room, so repeated knots are always exercised.
inline KnotVector random_knots(int p, int elements, std::mt19937& rng, double a = 0.0, double b = 1.0,
                               bool clamped = true) {
  std::uniform_real_distribution<double> U(0.3, 1.0);
  std::vector<double> len(elements);
  double sum = 0;
  for (double& l : len) sum += (l = U(rng));
  std::vector<double> bp{a};
  for (int e = 0; e < elements; ++e) bp.push_back(e + 1 == elements ? b : bp.back() + (b - a) * len[e] / sum);
  std::vector<double> t;
  const int end_mult = clamped ? p + 1 : 1;
  if (!clamped)
    for (int i = p; i >= 1; --i) t.push_back(a - i * (b - a) / elements);
  t.insert(t.end(), end_mult, a);
  for (int e = 1; e < elements; ++e) t.insert(t.end(), (e == elements / 2 && p >= 2) ? 2 : 1, bp[e]);
  t.insert(t.end(), end_mult, b);
  if (!clamped)
    for (int i = 1; i <= p; ++i) t.push_back(b + i * (b - a) / elements);
  return KnotVector(p, t);
}

template <int D>
TensorSpline<D> random_spline(const Ints<D>& degrees, const Ints<D>& elements, int dim, bool rational,
                              unsigned seed, bool clamped = true) {
  std::mt19937 rng(seed);
  std::array<KnotVector, D> kv;
  for (int k = 0; k < D; ++k) kv[k] = random_knots(degrees[k], elements[k], rng, 0.0, 1.0 + k, clamped);
  std::size_t n = 1;
  for (int k = 0; k < D; ++k) n *= kv[k].size();
  std::uniform_real_distribution<double> X(-1.0, 1.0), W(0.5, 2.0);
  std::vector<double> pts(n * dim), w;
  for (double& x : pts) x = X(rng);
  if (rational) {
    w.resize(n);
    for (double& x : w) x = W(rng);
  }
  return TensorSpline<D>::from_cartesian(kv, dim, pts, w);
}

template <int D>
std::vector<Param<D>> random_params(const TensorSpline<D>& s, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Param<D>> u(n);
  const auto box = s.domain();
  for (auto& x : u)
    for (int k = 0; k < D; ++k) x[k] = std::uniform_real_distribution<double>(box.lo[k], box.hi[k])(rng);
  return u;
}

// B_{i,p}(u) by the recursive definition, with the right end of the domain treated as closed.
inline double cox_de_boor(const std::vector<double>& t, int i, int p, double u, double end) {
  if (p == 0) {
    if (t[i] <= u && u < t[i + 1]) return 1.0;
    // Closed right end: the last non-empty interval includes `end`.
    if (u == end && t[i] < t[i + 1] && t[i + 1] == end) return 1.0;
    return 0.0;
  }
  double v = 0;
  if (t[i + p] > t[i]) v += (u - t[i]) / (t[i + p] - t[i]) * cox_de_boor(t, i, p - 1, u, end);
  if (t[i + p + 1] > t[i + 1]) v += (t[i + p + 1] - u) / (t[i + p + 1] - t[i + 1]) * cox_de_boor(t, i + 1, p - 1, u, end);
  return v;
}

// Reference evaluation: sum over all control points with Cox-de Boor basis values.
template <int D>
std::vector<double> reference_eval(const TensorSpline<D>& s, const Param<D>& u) {
  const int st = s.stride();
  std::vector<double> acc(st, 0.0);
  for (int l = 0; l < s.num_coefs(); ++l) {
    const auto idx = s.multi_index(l);
    double b = 1;
    for (int k = 0; k < D; ++k)
      b *= cox_de_boor(s.knots(k).knots(), idx[k], s.degree(k), u[k], s.knots(k).end());
    for (int d = 0; d < st; ++d) acc[d] += b * s.coef(l)[d];
  }
  std::vector<double> x(s.dim());
  for (int d = 0; d < s.dim(); ++d) x[d] = s.is_rational() ? acc[d] / acc[s.dim()] : acc[d];
  return x;
}

// max over params of |a(u) - b(u)| (all components).
template <int D>
double max_deviation(const TensorSpline<D>& a, const TensorSpline<D>& b, const std::vector<Param<D>>& params) {
  std::vector<double> x(a.dim()), y(b.dim());
  double m = 0;
  for (const auto& u : params) {
    a.eval(u, x.data());
    b.eval(u, y.data());
    for (int d = 0; d < a.dim(); ++d) m = std::max(m, std::abs(x[d] - y[d]));
  }
  return m;
}

}  // namespace trivar::test
