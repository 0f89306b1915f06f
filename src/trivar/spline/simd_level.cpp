#include "trivar/spline/simd_level.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>

namespace trivar {

namespace {

SimdLevel detect() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq"))
    return SimdLevel::avx512;
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return SimdLevel::avx2;
#endif
  return SimdLevel::generic;
}

SimdLevel from_environment(SimdLevel supported) {
  const char* v = std::getenv("TRIVAR_SIMD");
  if (!v) return supported;
  for (int l = 0; l < kSimdLevels; ++l)
    if (std::strcmp(v, simd_level_name(static_cast<SimdLevel>(l))) == 0)
      return std::min(supported, static_cast<SimdLevel>(l));
  return supported;
}

std::atomic<int>& current() {
  static std::atomic<int> level{static_cast<int>(from_environment(supported_simd_level()))};
  return level;
}

}  // namespace

SimdLevel supported_simd_level() {
  static const SimdLevel level = detect();
  return level;
}

SimdLevel simd_level() { return static_cast<SimdLevel>(current().load(std::memory_order_relaxed)); }

void limit_simd_level(SimdLevel cap) {
  current().store(static_cast<int>(std::min(cap, supported_simd_level())), std::memory_order_relaxed);
}

const char* simd_level_name(SimdLevel level) {
  switch (level) {
    case SimdLevel::avx2: return "avx2";
    case SimdLevel::avx512: return "avx512";
    default: return "generic";
  }
}

}  // namespace trivar
