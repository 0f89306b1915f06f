#include "trivar/model/curve_matching.hpp"

#include "trivar/core/vec3.hpp"

namespace trivar {

CurveMatch match_curve(std::span<const CurveCandidate> candidates, int p0, int p1,
                       std::span<const std::array<double, 3>> samples, double tol,
                       const std::function<double(std::size_t, const std::array<double, 3>&)>& distance_to) {
  const std::size_t ns = samples.size();
  for (std::size_t id = 0; id < candidates.size(); ++id) {
    const CurveCandidate& cv = candidates[id];
    for (int rev = 0; rev < 2; ++rev) {
      if (rev ? (p0 != cv.points[1] || p1 != cv.points[0]) : (p0 != cv.points[0] || p1 != cv.points[1])) continue;
      const auto& ref = cv.samples;
      bool same = true;
      for (std::size_t k = 0; k < ns && same; ++k) same = distance(samples[k], ref[rev ? ns - 1 - k : k]) <= tol;
      if (!same) {
        same = true;
        for (std::size_t k = 0; k < ns && same; ++k) same = distance_to(id, samples[k]) <= tol;
        if (same && p0 == p1 && rev == 0) same = distance(samples[0], ref[0]) <= distance(samples[0], ref[ns - 1]);
      }
      if (same) return {static_cast<int>(id), rev == 1};
    }
  }
  return {};
}

}  // namespace trivar
