#include "trivar/model/metamorphosis.hpp"

#include <algorithm>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/model/ruled.hpp"
#include "trivar/spline/compatibility.hpp"

namespace trivar {

SplineVolume metamorphosis(const SplineSurface& s0, const SplineSurface& s1, int smoothness) {
  require(smoothness >= 0, "metamorphosis: smoothness must be non-negative, got " + std::to_string(smoothness));
  if (smoothness == 0) return ruled<3>(s0, s1);
  const auto c = make_compatible<2>({s0, s1});
  const int layers = smoothness + 1;
  std::vector<double> t(static_cast<std::size_t>(4 * layers), 0.0);  // Bezier knots of degree 2 layers - 1
  std::fill(t.begin() + 2 * layers, t.end(), 1.0);
  // Bezier in time: the first `layers` control nets are S0 and the last `layers` are S1.
  std::vector<double> h;
  for (int k = 0; k < 2 * layers; ++k) {
    const auto& src = c[k < layers ? 0 : 1].coefs();
    h.insert(h.end(), src.begin(), src.end());
  }
  return SplineVolume({c[0].knots(0), c[0].knots(1), KnotVector(2 * layers - 1, std::move(t))}, c[0].dim(),
                      c[0].is_rational(), std::move(h));
}

}  // namespace trivar
