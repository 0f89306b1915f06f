#include "trivar/lr/tensor_expansion.hpp"

#include <algorithm>
#include <map>

#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/spline/knot_refinement.hpp"

namespace trivar {

void raise_knot_multiplicities(const std::vector<double>& t, std::map<double, int>& mult) {
  for (std::size_t i = 0; i < t.size();) {
    std::size_t j = i;
    while (j < t.size() && t[j] == t[i]) ++j;
    int& m = mult[t[i]];
    m = std::max(m, static_cast<int>(j - i));
    i = j;
  }
}

template <int D>
TensorSpline<D> tensor_expansion(const LRSpline<D>& lr) {
  require(!lr.is_rational(), "tensor expansion: rational LR splines are not supported");
  std::array<KnotVector, D> knots;
  std::array<std::size_t, D> n{};
  double count = 1.0;
  for (int k = 0; k < D; ++k) {
    std::map<double, int> mult;
    for (const LRBSpline<D>& b : lr.basis_functions())
      raise_knot_multiplicities(b.knots[static_cast<std::size_t>(k)], mult);
    std::vector<double> t;
    for (const auto& [value, m] : mult) t.insert(t.end(), static_cast<std::size_t>(m), value);
    knots[static_cast<std::size_t>(k)] = KnotVector(lr.degree(k), std::move(t));
    n[static_cast<std::size_t>(k)] = knots[static_cast<std::size_t>(k)].knots().size() - static_cast<std::size_t>(lr.degree(k)) - 1;
    count *= static_cast<double>(n[static_cast<std::size_t>(k)]);
  }
  const auto dim = static_cast<std::size_t>(lr.dim());
  require_memory(8.0 * count * static_cast<double>(dim), "tensor expansion of an LR spline: " +
                                                             std::to_string(static_cast<long long>(count)) + " coefficients");
  std::vector<double> coefs(static_cast<std::size_t>(count) * dim, 0.0);
  std::array<std::vector<double>, D> alpha;
  std::array<int, D> first{};
  for (const LRBSpline<D>& b : lr.basis_functions()) {
    for (int k = 0; k < D; ++k)
      express_in(b.knots[static_cast<std::size_t>(k)], lr.degree(k), knots[static_cast<std::size_t>(k)],
                 first[static_cast<std::size_t>(k)], alpha[static_cast<std::size_t>(k)]);
    // Every tensor index of the support (direction 0 fastest), weighted by the product of the 1-D factors.
    std::array<std::size_t, D> i{};
    for (;;) {
      double w = b.gamma;
      std::size_t index = 0, stride = 1;
      for (int k = 0; k < D; ++k) {
        const auto K = static_cast<std::size_t>(k);
        w *= alpha[K][i[K]];
        index += (static_cast<std::size_t>(first[K]) + i[K]) * stride;
        stride *= n[K];
      }
      if (w != 0.0)
        for (std::size_t c = 0; c < dim; ++c) coefs[index * dim + c] += w * b.coef[c];
      int k = 0;
      while (k < D && ++i[static_cast<std::size_t>(k)] == alpha[static_cast<std::size_t>(k)].size()) i[static_cast<std::size_t>(k++)] = 0;
      if (k == D) break;
    }
  }
  return TensorSpline<D>(std::move(knots), lr.dim(), false, std::move(coefs));
}

template TensorSpline<2> tensor_expansion(const LRSpline<2>&);
template TensorSpline<3> tensor_expansion(const LRSpline<3>&);

}  // namespace trivar
