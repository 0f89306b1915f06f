#pragma once
// Invalid materials met inside a threaded assembly are recorded (an exception must not leave an OpenMP region)
// and reported after it.
#include <atomic>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/iga/elasticity.hpp"

namespace trivar {

class MaterialCheck {
public:
  ElasticMaterial operator()(const ElasticMaterial& m, int patch) {
    if (!m.valid()) {
      int none = -1;
      bad_patch_.compare_exchange_strong(none, patch);
    }
    return m;
  }
  // Throws trivar::Error naming the first patch recorded with an invalid material.
  void report() const {
    const int p = bad_patch_.load();
    require(p < 0, "elasticity: invalid material on patch " + std::to_string(p) +
                       " (Young's modulus and density must be positive, Poisson's ratio in (-1, 0.5))");
  }

private:
  std::atomic<int> bad_patch_{-1};
};

}  // namespace trivar
