#pragma once
// The instruction sets the evaluation kernels are compiled for, chosen at run time: the portable release build
// runs the generic x86-64 code on any CPU and the AVX2 + FMA or AVX-512 code where the CPU has it. Splines pick
// their kernels when constructed, from simd_level().
namespace trivar {

enum class SimdLevel : int { generic = 0, avx2 = 1, avx512 = 2 };
inline constexpr int kSimdLevels = 3;

// The best level this CPU supports (CPUID; generic on other architectures).
SimdLevel supported_simd_level();
// The level kernels are chosen for: the supported one, lowered by limit_simd_level or by the environment
// variable TRIVAR_SIMD=generic|avx2|avx512 read at the first call.
SimdLevel simd_level();
// Caps simd_level() for splines constructed afterwards (tests compare the paths, benchmarks measure them).
// A cap above the supported level has no effect.
void limit_simd_level(SimdLevel cap);
const char* simd_level_name(SimdLevel level);

}  // namespace trivar
