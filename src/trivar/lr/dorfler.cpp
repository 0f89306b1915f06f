#include "trivar/lr/dorfler.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "trivar/core/error.hpp"

namespace trivar {

std::vector<int> dorfler_mark(std::span<const double> indicators, double beta) {
  require(beta > 0.0 && beta <= 1.0, "dorfler_mark: beta " + std::to_string(beta) + " outside (0, 1]");
  const int n = static_cast<int>(indicators.size());
  for (int i = 0; i < n; ++i)
    require(std::isfinite(indicators[static_cast<std::size_t>(i)]) && indicators[static_cast<std::size_t>(i)] >= 0.0,
            [&] { return "dorfler_mark: indicator " + std::to_string(i) + " is negative or not finite"; });
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return indicators[static_cast<std::size_t>(a)] > indicators[static_cast<std::size_t>(b)];
  });
  double total = 0.0;
  for (int i : order) total += indicators[static_cast<std::size_t>(i)] * indicators[static_cast<std::size_t>(i)];
  std::vector<int> marked;
  if (total == 0.0) return marked;
  double sum = 0.0;
  for (int i : order) {
    const double eta = indicators[static_cast<std::size_t>(i)];
    if (eta == 0.0) break;
    marked.push_back(i);
    sum += eta * eta;
    if (sum >= beta * total) break;
  }
  std::sort(marked.begin(), marked.end());
  return marked;
}

template <int D>
int refine_dorfler(LRSpline<D>& lr, std::span<const double> indicators, double beta, const RefineOptions& opts) {
  require(static_cast<int>(indicators.size()) == lr.num_elements(),
          "refine_dorfler: " + std::to_string(indicators.size()) + " indicators for " + std::to_string(lr.num_elements()) +
              " elements");
  const auto marked = dorfler_mark(indicators, beta);
  return refine_elements(lr, std::span<const int>(marked), opts);
}

template int refine_dorfler(LRSpline<2>&, std::span<const double>, double, const RefineOptions&);
template int refine_dorfler(LRSpline<3>&, std::span<const double>, double, const RefineOptions&);

}  // namespace trivar
