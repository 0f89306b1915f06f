#include "trivar/spline/compatibility.hpp"

#include <algorithm>
#include <map>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/knot_insertion.hpp"
#include "trivar/spline/reparametrization.hpp"
#include "trivar/spline/split.hpp"

namespace trivar {

namespace {

template <int D>
TensorSpline<D> as_rational(const TensorSpline<D>& s) {
  if (s.is_rational()) return s;
  const int dim = s.dim(), n = s.num_coefs();
  std::vector<double> h(static_cast<std::size_t>(n) * (dim + 1));
  for (int i = 0; i < n; ++i) {
    std::copy_n(s.coef(i), dim, h.data() + static_cast<std::size_t>(i) * (dim + 1));
    h[static_cast<std::size_t>(i) * (dim + 1) + dim] = 1.0;
  }
  return TensorSpline<D>(s.knot_vectors(), dim, true, std::move(h));
}

}  // namespace

template <int D>
std::vector<TensorSpline<D>> make_compatible(const std::vector<TensorSpline<D>>& splines) {
  std::vector<TensorSpline<D>> out(splines.begin(), splines.end());
  if (out.empty()) return out;
  bool rational = false;
  for (std::size_t i = 0; i < out.size(); ++i) {
    require(out[i].dim() == out[0].dim(), [&] {
      return "make_compatible: spline " + std::to_string(i) + " has control dimension " +
             std::to_string(out[i].dim()) + ", spline 0 has " + std::to_string(out[0].dim());
    });
    rational = rational || out[i].is_rational();
  }
  for (auto& s : out) {
    bool clamped = true;
    for (int k = 0; k < D; ++k) clamped = clamped && s.knots(k).is_clamped();
    if (!clamped) s = sub_patch(s, s.domain());
    if (rational) s = as_rational(s);
  }
  for (int k = 0; k < D; ++k) {
    const double a = out[0].knots(k).start(), b = out[0].knots(k).end();
    int degree = 0;
    for (auto& s : out) {
      if (s.knots(k).start() != a || s.knots(k).end() != b) s = reparametrize(s, k, a, b);
      degree = std::max(degree, s.degree(k));
    }
    // Elevate first: elevation raises every multiplicity, so merging afterwards sees the final ones.
    std::map<double, int> merged;
    for (auto& s : out) {
      if (s.degree(k) < degree) s = elevate_degree(s, k, degree - s.degree(k));
      const auto values = s.knots(k).unique();
      const auto mults = s.knots(k).multiplicities();
      for (std::size_t j = 0; j < values.size(); ++j) merged[values[j]] = std::max(merged[values[j]], mults[j]);
    }
    for (auto& s : out) {
      std::vector<double> missing;
      for (const auto& [value, mult] : merged)
        missing.insert(missing.end(), static_cast<std::size_t>(mult - s.knots(k).multiplicity(value)), value);
      if (!missing.empty()) s = insert_knots(s, k, missing);
    }
  }
  return out;
}

template std::vector<TensorSpline<1>> make_compatible(const std::vector<TensorSpline<1>>&);
template std::vector<TensorSpline<2>> make_compatible(const std::vector<TensorSpline<2>>&);
template std::vector<TensorSpline<3>> make_compatible(const std::vector<TensorSpline<3>>&);

}  // namespace trivar
