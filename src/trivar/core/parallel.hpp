#pragma once
// Batch-level parallel loop. Work is split statically so every index is computed by exactly the same code
// whatever the thread count, which keeps results bit-identical for 1 or N threads.
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <omp.h>

namespace trivar {

// threads <= 0 means "all available" (OpenMP's default).
inline int resolve_threads(int threads) { return threads > 0 ? threads : omp_get_max_threads(); }

// An exception thrown by `body` (a trivar::Error, std::bad_alloc) is rethrown to the caller once the loop has
// stopped: one escaping an OpenMP region would terminate the program instead.
template <class F>
void parallel_for(std::ptrdiff_t n, int threads, F&& body) {
  const int t = resolve_threads(threads);
  if (t == 1 || n < 2) {
    for (std::ptrdiff_t i = 0; i < n; ++i) body(i);
    return;
  }
  std::exception_ptr failure;
  std::mutex lock;
  std::atomic<bool> failed{false};
#pragma omp parallel for num_threads(t) schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    if (failed.load(std::memory_order_relaxed)) continue;
    try {
      body(i);
    } catch (...) {
      const std::lock_guard<std::mutex> guard(lock);
      if (!failure) failure = std::current_exception();
      failed.store(true, std::memory_order_relaxed);
    }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace trivar
