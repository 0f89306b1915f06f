#pragma once
// Batch-level parallel loop. Work is split statically so every index is computed by exactly the same code
// whatever the thread count, which keeps results bit-identical for 1 or N threads.
#include <cstddef>
#include <omp.h>

namespace trivar {

// threads <= 0 means "all available" (OpenMP's default).
inline int resolve_threads(int threads) { return threads > 0 ? threads : omp_get_max_threads(); }

template <class F>
void parallel_for(std::ptrdiff_t n, int threads, F&& body) {
  const int t = resolve_threads(threads);
  if (t == 1 || n < 2) {
    for (std::ptrdiff_t i = 0; i < n; ++i) body(i);
    return;
  }
#pragma omp parallel for num_threads(t) schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i) body(i);
}

}  // namespace trivar
