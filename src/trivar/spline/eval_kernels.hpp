#pragma once
// Evaluation kernels of tensor splines with the degree (equal in every direction) and the stride fixed at
// compile time, each compiled three times: for generic x86-64, for AVX2 + FMA and for AVX-512, and chosen at run
// time by simd_level(). All loops have compile-time bounds, so the compiler unrolls them and vectorises the
// contraction over the rows of the active control block; the wider instruction sets do each row in fewer
// instructions and fuse the multiply-adds. The paths agree to rounding (about 1e-16 relative; tested).
#include <array>
#include <cstddef>

#include "trivar/core/box.hpp"
#include "trivar/spline/knot_vector.hpp"
#include "trivar/spline/simd_level.hpp"

namespace trivar {

// Homogeneous value (stride values) at u; u is clamped to the domain.
template <int D>
using PointKernel = void (*)(const std::array<KnotVector, D>& knots, const double* coefs, const Param<D>& u,
                             double* h);
// Cartesian values of n points (dim = stride - rational values each, divided by the weight when rational).
template <int D>
using BatchKernel = void (*)(const std::array<KnotVector, D>& knots, const double* coefs, bool rational,
                             const Param<D>* u, std::size_t n, double* out);

template <int D>
struct FixedKernels {
  PointKernel<D> value = nullptr;
  // Value and first partials, (D + 1) * stride homogeneous values: f, f_u, f_v, (f_w).
  PointKernel<D> first = nullptr;
  BatchKernel<D> batch = nullptr;
};

// The kernels for these knot vectors and stride at the given level: equal degrees 1 to 4 with strides 1, 3, 4,
// and degree p in all directions but a lower degree q in the last ((p, q) in (2,1), (3,1), (3,2), (4,1), (4,2))
// with strides 3, 4; all null otherwise.
template <int D>
FixedKernels<D> fixed_kernels(const std::array<KnotVector, D>& knots, int stride, SimdLevel level);

// A tensor polynomial of degree P in every direction on one element, in Bernstein form: (P + 1)^D control
// blocks of `stride` values, direction 0 fastest. t is the local parameter in [0, 1]^D and scale[k] = 1 / (element
// width in direction k) (the chain rule of first derivatives). Same homogeneous outputs as PointKernel.
template <int D>
using BezierKernel = void (*)(const double* block, const Param<D>& t, const Param<D>& scale, double* h);

template <int D>
struct BezierKernels {
  BezierKernel<D> value = nullptr;
  BezierKernel<D> first = nullptr;
};

// Kernels for degree 1 to 4 and strides 1, 3, 4 (all null otherwise).
template <int D>
BezierKernels<D> bezier_kernels(int degree, int stride, SimdLevel level);

extern template FixedKernels<1> fixed_kernels<1>(const std::array<KnotVector, 1>&, int, SimdLevel);
extern template FixedKernels<2> fixed_kernels<2>(const std::array<KnotVector, 2>&, int, SimdLevel);
extern template FixedKernels<3> fixed_kernels<3>(const std::array<KnotVector, 3>&, int, SimdLevel);
extern template BezierKernels<2> bezier_kernels<2>(int, int, SimdLevel);
extern template BezierKernels<3> bezier_kernels<3>(int, int, SimdLevel);

}  // namespace trivar
