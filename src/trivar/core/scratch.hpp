#pragma once
// Per-thread scratch memory for hot paths whose temporary size depends on run-time data (control dimension,
// derivative order). It grows to the largest request once per thread, so steady-state evaluation never
// allocates, and it is thread_local, so const evaluation stays thread-safe.
#include <cstddef>
#include <vector>

namespace trivar {

// Returns at least n doubles, valid until the next call with the same slot on this thread.
template <int Slot = 0>
inline double* scratch(std::size_t n) {
  thread_local std::vector<double> buffer;
  if (buffer.size() < n) buffer.resize(n);
  return buffer.data();
}

}  // namespace trivar
