#include "trivar/spline/eval_kernels.hpp"

#include <algorithm>

#include "trivar/spline/basis.hpp"

namespace trivar {

namespace {

// The bodies are forced inline into the per-instruction-set entry points below, so each is compiled for that
// entry's target (GCC inlines default-target code into functions with a wider target).
#define TRIVAR_KERNEL_INLINE [[gnu::always_inline]] inline

// Degrees: P in directions 0..D-2 and Q in the last (P == Q for curves), which covers equal degrees and the
// mixed cells of exact models (sphere and torus shells of degree 4 x 4 x 1). kWidth: the basis arrays' length,
// p + 1 rounded up to a vector width (the basis of a direction is computed as one vector).
template <int P, int Q>
inline constexpr int kWidth = (P > Q ? P : Q) < 2 ? 2 : (P > Q ? P : Q) < 4 ? 4 : 8;

template <int P, int Q, int D>
constexpr int degree_of(int k) {
  return D > 1 && k == D - 1 ? Q : P;
}

// W doubles as one value (GCC vector extension): the row contraction is written in these so it is vector code
// in every build: W = 2 for generic x86-64 (SSE2), 4 for AVX2 and AVX-512 (see the kernel sets below).
// (GCC drops vector_size in an alias template with a dependent size, hence one explicit type per width.)
template <int W>
struct VecOf;
template <>
struct VecOf<1> {
  typedef double type __attribute__((vector_size(8)));
};
template <>
struct VecOf<2> {
  typedef double type __attribute__((vector_size(16)));
};
template <>
struct VecOf<4> {
  typedef double type __attribute__((vector_size(32)));
};
template <>
struct VecOf<8> {
  typedef double type __attribute__((vector_size(64)));
};
template <int W>
using Vec = typename VecOf<W>::type;
// Vec never crosses a call boundary (everything is inlined into the entry points), so the ABI note about
// passing wide vectors without AVX does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

template <int W>
TRIVAR_KERNEL_INLINE Vec<W> load(const double* p) {
  Vec<W> v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}

// N[a] = sum_{m <= M} c[m * L + a] x^m for a < L, in pieces no wider than the instruction set's vectors (VW;
// wider GCC vectors than the target's registers go through memory): L rounded up to 2 or VW values are written.
template <int M, int L, int VW>
TRIVAR_KERNEL_INLINE void horner(const double* c, double x, double* N) {
  constexpr int V = L <= 2 ? 2 : VW;
#pragma GCC unroll 4
  for (int j = 0; j < L; j += V) {
    Vec<V> n = load<V>(c + M * L + j);
#pragma GCC unroll 4
    for (int m = M - 1; m >= 0; --m) n = n * x + load<V>(c + m * L + j);
    __builtin_memcpy(N + j, &n, sizeof n);
  }
}

// The span of u (clamped to the domain) and its basis functions of degree PK, with kD1 also their derivatives:
// Horner's rule on the span's power form (KnotVector::span_power_form), vectors over the p + 1 functions. On
// uniform knots the span comes from one multiplication, without the search's corrections: a local coordinate a
// rounding outside [0, 1] evaluates the neighbouring span's polynomial, equal there to rounding.
template <int PK, int VW, bool kD1>
TRIVAR_KERNEL_INLINE int power_basis(const KnotVector& kv, double u, double* N, double* dN) {
  constexpr int L = PK + 1, kBlock = KnotVector::power_form_block(PK);
  const double uk = std::clamp(u, kv.start(), kv.end());
  const int first = kv.first_span();
  int s;
  if (const double inv_h = kv.uniform_inverse_spacing(); inv_h > 0.0)
    s = first +
        static_cast<int>(std::clamp((uk - kv[first]) * inv_h, 0.0, static_cast<double>(kv.last_span() - first)));
  else
    s = kv.find_span(uk);
  const double* b = kv.power_forms() + static_cast<std::size_t>(s - first) * kBlock;
  const double x = (uk - b[0]) * b[1];
  const double* C = b + 2;
  horner<PK, L, VW>(C, x, N);
  if constexpr (kD1) horner<PK - 1, L, VW>(C + L * L, x, dN);
  return s;
}

// Span, basis functions (or with kD1 also their derivatives) in every direction and the offset of the active
// control block; step[k] is the distance between neighbouring control values in direction k.
template <int VW, int P, int Q, int ST, int D, bool kD1>
TRIVAR_KERNEL_INLINE std::size_t locate(const std::array<KnotVector, D>& knots, const Param<D>& u,
                                        double (*N)[kWidth<P, Q>], double (*dN)[kWidth<P, Q>], std::size_t* step) {
  std::size_t offset = 0, stride_k = ST;
#pragma GCC unroll 4
  for (int k = 0; k < D; ++k) {
    const KnotVector& kv = knots[k];
    const int s = degree_of<P, Q, D>(k) != P ? power_basis<Q, VW, kD1>(kv, u[k], N[k], kD1 ? dN[k] : nullptr)
                                             : power_basis<P, VW, kD1>(kv, u[k], N[k], kD1 ? dN[k] : nullptr);
    step[k] = stride_k;
    offset += static_cast<std::size_t>(s - degree_of<P, Q, D>(k)) * stride_k;
    stride_k *= static_cast<std::size_t>(kv.size());
  }
  return offset;
}

// The active block is prod_{k >= 1} (p_k + 1) rows of L = (P + 1) * ST contiguous control values (direction 0
// and the stride). Row r has weight W[r], the product of the basis functions of directions 1..D-1 for its
// indices, and starts off[r] values after the block's first. Built by outer products, last direction outermost.
template <int P, int Q, int D>
constexpr int rows_count() {
  int n = 1;
  for (int k = 1; k < D; ++k) n *= degree_of<P, Q, D>(k) + 1;
  return n;
}
template <int P, int Q, int D>
inline constexpr int kRows = rows_count<P, Q, D>();

template <int P, int Q, int D>
TRIVAR_KERNEL_INLINE void row_offsets(const std::size_t* step, std::size_t* off) {
  off[0] = 0;
  int n = 1;
#pragma GCC unroll 4
  for (int k = 1; k < D; ++k) {
    const int pk = degree_of<P, Q, D>(k);
#pragma GCC unroll 8
    for (int j = n - 1; j >= 0; --j) {
      const std::size_t o = off[j];
      for (int a = pk; a >= 0; --a) off[j * (pk + 1) + a] = o + static_cast<std::size_t>(a) * step[k];
    }
    n *= pk + 1;
  }
}

// W[r] = prod_{k >= 1} (k == deriv ? dN : N)[k][a_k] in the order of row_offsets.
template <int P, int Q, int D>
TRIVAR_KERNEL_INLINE void row_weights(const double (*N)[kWidth<P, Q>], const double (*dN)[kWidth<P, Q>], int deriv,
                                      double* W) {
  W[0] = 1.0;
  int n = 1;
#pragma GCC unroll 4
  for (int k = 1; k < D; ++k) {
    const int pk = degree_of<P, Q, D>(k);
    const double* B = k == deriv ? dN[k] : N[k];
#pragma GCC unroll 8
    for (int j = n - 1; j >= 0; --j) {
      const double w = W[j];
      for (int a = pk; a >= 0; --a) W[j * (pk + 1) + a] = w * B[a];
    }
    n *= pk + 1;
  }
}

// sums[t][X0..L) = sum_r W[t][r] * row_r[X0..L) for T weight sets at once (the value and, for first
// derivatives, one set per direction k >= 1): as many W-wide pieces as fit, the rest with W / 2, down to
// scalars. Two accumulators per set alternate between rows where registers allow, halving the chain of dependent
// multiply-adds that bounds a single point.
template <int VW, int X0, int L, int R, int T>
TRIVAR_KERNEL_INLINE void contract_rows(const double* base, const std::size_t* off, const double (*Wt)[R],
                                        double (*sums)[L]) {
  constexpr int NV = (L - X0) / VW;
  // Two accumulators only while they fit the 16 vector registers beside the loaded values.
  constexpr int NA = 2 * T * NV <= 12 ? 2 : 1;
  if constexpr (NV > 0) {
    Vec<VW> acc[T][NA][NV] = {};
#pragma GCC unroll 32
    for (int r = 0; r < R; ++r) {
      const double* row = base + off[r] + X0;
      for (int t = 0; t < T; ++t)
        for (int v = 0; v < NV; ++v) acc[t][r % NA][v] += Wt[t][r] * load<VW>(row + VW * v);
    }
    for (int t = 0; t < T; ++t)
      for (int v = 0; v < NV; ++v) {
        const Vec<VW> sum = NA == 2 ? acc[t][0][v] + acc[t][NA - 1][v] : acc[t][0][v];
        __builtin_memcpy(sums[t] + X0 + VW * v, &sum, sizeof sum);
      }
  }
  if constexpr (X0 + NV * VW < L) contract_rows<VW / 2, X0 + NV * VW, L, R, T>(base, off, Wt, sums);
}

// Homogeneous value: locate (basis functions of every direction, steps, offset of the active block), contract
// the rows, then reduce along direction 0. `locate` is the B-spline span and basis, or a Bezier element's
// Bernstein basis.
template <int VW, int P, int Q, int ST, int D, class Locate>
TRIVAR_KERNEL_INLINE void value_from(const double* coefs, Locate&& locate, double* h) {
  static_assert(D > 1 || P == Q);
  constexpr int R = kRows<P, Q, D>;
  double N[D][kWidth<P, Q>];
  std::size_t step[D], off[R];
  const double* base = coefs + locate(N, static_cast<double(*)[kWidth<P, Q>]>(nullptr), step);
  double W[1][R], sums[1][(P + 1) * ST] = {};
  row_offsets<P, Q, D>(step, off);
  row_weights<P, Q, D>(N, nullptr, -1, W[0]);
  contract_rows<VW, 0, (P + 1) * ST, R, 1>(base, off, W, sums);
  for (int d = 0; d < ST; ++d) h[d] = 0.0;
  for (int a = 0; a <= P; ++a)
    for (int d = 0; d < ST; ++d) h[d] += N[0][a] * sums[0][a * ST + d];
}

// Value and first derivatives in one pass over the rows: weight set 0 gives the value row sum, set k >= 1 the
// row sum with N_k replaced by its derivative; direction 0 is differentiated in the final reduction.
template <int VW, int P, int Q, int ST, int D, class Locate>
TRIVAR_KERNEL_INLINE void first_from(const double* coefs, Locate&& locate, double* h) {
  static_assert(D > 1 || P == Q);
  constexpr int R = kRows<P, Q, D>;
  double N[D][kWidth<P, Q>], dN[D][kWidth<P, Q>];
  std::size_t step[D], off[R];
  const double* base = coefs + locate(N, dN, step);
  double W[D][R], sums[D][(P + 1) * ST] = {};
  row_offsets<P, Q, D>(step, off);
  for (int t = 0; t < D; ++t) row_weights<P, Q, D>(N, dN, t == 0 ? -1 : t, W[t]);
  contract_rows<VW, 0, (P + 1) * ST, R, D>(base, off, W, sums);
  for (int x = 0; x < (D + 1) * ST; ++x) h[x] = 0.0;
  for (int a = 0; a <= P; ++a)
    for (int d = 0; d < ST; ++d) {
      h[d] += N[0][a] * sums[0][a * ST + d];
      h[ST + d] += dN[0][a] * sums[0][a * ST + d];
      for (int t = 1; t < D; ++t) h[(t + 1) * ST + d] += N[0][a] * sums[t][a * ST + d];
    }
}

template <int VW, int P, int Q, int ST, int D>
TRIVAR_KERNEL_INLINE void value_body(const std::array<KnotVector, D>& knots, const double* coefs, const Param<D>& u,
                                     double* h) {
  value_from<VW, P, Q, ST, D>(
      coefs,
      [&](auto N, auto dN, std::size_t* step) { return locate<VW, P, Q, ST, D, false>(knots, u, N, dN, step); }, h);
}

template <int VW, int P, int Q, int ST, int D>
TRIVAR_KERNEL_INLINE void first_body(const std::array<KnotVector, D>& knots, const double* coefs, const Param<D>& u,
                                     double* h) {
  first_from<VW, P, Q, ST, D>(
      coefs,
      [&](auto N, auto dN, std::size_t* step) { return locate<VW, P, Q, ST, D, true>(knots, u, N, dN, step); }, h);
}

// The Bernstein basis of a Bezier element block: steps of a dense (P + 1)^D block, offset 0.
template <int P, int ST, int D, bool kD1>
TRIVAR_KERNEL_INLINE std::size_t locate_bezier(const Param<D>& t, const Param<D>& scale, double (*N)[kWidth<P, P>],
                                               double (*dN)[kWidth<P, P>], std::size_t* step) {
  std::size_t stride_k = ST;
#pragma GCC unroll 4
  for (int k = 0; k < D; ++k) {
    bernstein_values<P>(P, t[k], scale[k], N[k], kD1 ? dN[k] : nullptr);
    step[k] = stride_k;
    stride_k *= P + 1;
  }
  return 0;
}

template <int VW, int P, int ST, int D>
TRIVAR_KERNEL_INLINE void bezier_value_body(const double* block, const Param<D>& t, const Param<D>& scale, double* h) {
  value_from<VW, P, P, ST, D>(
      block, [&](auto N, auto dN, std::size_t* step) { return locate_bezier<P, ST, D, false>(t, scale, N, dN, step); },
      h);
}

template <int VW, int P, int ST, int D>
TRIVAR_KERNEL_INLINE void bezier_first_body(const double* block, const Param<D>& t, const Param<D>& scale, double* h) {
  first_from<VW, P, P, ST, D>(
      block, [&](auto N, auto dN, std::size_t* step) { return locate_bezier<P, ST, D, true>(t, scale, N, dN, step); },
      h);
}

// Many points in one call: no indirect call and no thread-pool step per point. It calls the same compiled
// point kernel as eval() (a wider-target function is never inlined into this one), so batch and pointwise
// results are bit-identical.
template <int ST, int D, PointKernel<D> kValue>
void batch_of(const std::array<KnotVector, D>& knots, const double* coefs, bool rational, const Param<D>* u,
              std::size_t n, double* out) {
  if (!rational) {
    for (std::size_t i = 0; i < n; ++i) kValue(knots, coefs, u[i], out + i * ST);
    return;
  }
  for (std::size_t i = 0; i < n; ++i) {
    double h[ST];
    kValue(knots, coefs, u[i], h);
    const double inv = 1.0 / h[ST - 1];
    for (int d = 0; d < ST - 1; ++d) out[i * (ST - 1) + d] = h[d] * inv;
  }
}

// One entry point of each kind per instruction set.
// flatten: everything the bodies call (span search, basis functions) is compiled into the entry point too.
#define TRIVAR_KERNEL_SET(NAME, VW, ...)                                                                         \
  template <int P, int Q, int ST, int D>                                                                       \
  __VA_ARGS__ void NAME##_value(const std::array<KnotVector, D>& k, const double* c, const Param<D>& u,       \
                                double* h) {                                                                   \
    value_body<VW, P, Q, ST, D>(k, c, u, h);                                                                   \
  }                                                                                                            \
  template <int P, int Q, int ST, int D>                                                                       \
  __VA_ARGS__ void NAME##_first(const std::array<KnotVector, D>& k, const double* c, const Param<D>& u,       \
                                double* h) {                                                                   \
    first_body<VW, P, Q, ST, D>(k, c, u, h);                                                                   \
  }                                                                                                            \
  template <int P, int ST, int D>                                                                              \
  __VA_ARGS__ void NAME##_bezier_value(const double* b, const Param<D>& t, const Param<D>& sc, double* h) {    \
    bezier_value_body<VW, P, ST, D>(b, t, sc, h);                                                              \
  }                                                                                                            \
  template <int P, int ST, int D>                                                                              \
  __VA_ARGS__ void NAME##_bezier_first(const double* b, const Param<D>& t, const Param<D>& sc, double* h) {    \
    bezier_first_body<VW, P, ST, D>(b, t, sc, h);                                                              \
  }                                                                                                            \
  template <int P, int ST, int D>                                                                              \
  BezierKernels<D> NAME##_bezier_kernels() {                                                                   \
    return {&NAME##_bezier_value<P, ST, D>, &NAME##_bezier_first<P, ST, D>};                                   \
  }                                                                                                            \
  template <int P, int Q, int ST, int D>                                                                       \
  FixedKernels<D> NAME##_kernels() {                                                                           \
    return {&NAME##_value<P, Q, ST, D>, &NAME##_first<P, Q, ST, D>,                                            \
            &batch_of<ST, D, &NAME##_value<P, Q, ST, D>>};                                                     \
  }

TRIVAR_KERNEL_SET(generic, 2, [[gnu::flatten]])
// The AVX-512 set keeps 256-bit vectors: the rows are 12 to 20 doubles, Zen 4 splits 512-bit operations in two
// anyway (measured: no faster than AVX2 with 8-wide vectors), and several Xeons lower their clock for 512-bit
// arithmetic; the set still gains the AVX-512 scalar and mask instructions and 32 vector registers.
#if defined(__x86_64__)
TRIVAR_KERNEL_SET(avx2, 4, [[gnu::flatten, gnu::target("avx2,fma")]])
TRIVAR_KERNEL_SET(avx512, 4, [[gnu::flatten, gnu::target("avx512f,avx512vl,avx512dq,avx2,fma")]])
#endif

template <int P, int Q, int ST, int D>
FixedKernels<D> kernels_at(SimdLevel level) {
#if defined(__x86_64__)
  if (level == SimdLevel::avx512) return avx512_kernels<P, Q, ST, D>();
  if (level == SimdLevel::avx2) return avx2_kernels<P, Q, ST, D>();
#endif
  (void)level;
  return generic_kernels<P, Q, ST, D>();
}

template <int P, int ST, int D>
BezierKernels<D> bezier_kernels_at(SimdLevel level) {
#if defined(__x86_64__)
  if (level == SimdLevel::avx512) return avx512_bezier_kernels<P, ST, D>();
  if (level == SimdLevel::avx2) return avx2_bezier_kernels<P, ST, D>();
#endif
  (void)level;
  return generic_bezier_kernels<P, ST, D>();
}

// The kernel set of `Set` (fixed or Bezier) for the run-time degree and stride.
template <template <int, int, int> class Set, int D>
auto select(int p, int stride, SimdLevel level) -> decltype(Set<1, 1, D>::get(level)) {
  auto for_stride = [&]<int P>() -> decltype(Set<1, 1, D>::get(level)) {
    switch (stride) {
      case 1: return Set<P, 1, D>::get(level);
      case 3: return Set<P, 3, D>::get(level);
      case 4: return Set<P, 4, D>::get(level);
      default: return {};
    }
  };
  switch (p) {
    case 1: return for_stride.template operator()<1>();
    case 2: return for_stride.template operator()<2>();
    case 3: return for_stride.template operator()<3>();
    case 4: return for_stride.template operator()<4>();  // exact spheres and tori (Cobb's patches, revolutions)
    default: return {};
  }
}

template <int P, int ST, int D>
struct FixedSet {
  static FixedKernels<D> get(SimdLevel level) { return kernels_at<P, P, ST, D>(level); }
};
template <int P, int ST, int D>
struct BezierSet {
  static BezierKernels<D> get(SimdLevel level) { return bezier_kernels_at<P, ST, D>(level); }
};

// Degree P in directions 0..D-2 and a lower degree Q in the last, for strides 3 and 4 (geometry): the shells of
// exact spheres and tori (4 x 4 x 1 after the cube's degree elevation, 2 x 2 x 1 from revolutions).
template <int D>
FixedKernels<D> mixed_kernels(int p, int q, int stride, SimdLevel level) {
  auto for_stride = [&]<int P, int Q>() -> FixedKernels<D> {
    switch (stride) {
      case 3: return kernels_at<P, Q, 3, D>(level);
      case 4: return kernels_at<P, Q, 4, D>(level);
      default: return {};
    }
  };
  switch (p * 10 + q) {
    case 21: return for_stride.template operator()<2, 1>();
    case 31: return for_stride.template operator()<3, 1>();
    case 32: return for_stride.template operator()<3, 2>();
    case 41: return for_stride.template operator()<4, 1>();
    case 42: return for_stride.template operator()<4, 2>();
    default: return {};
  }
}

}  // namespace

template <int D>
FixedKernels<D> fixed_kernels(const std::array<KnotVector, D>& knots, int stride, SimdLevel level) {
  const int p = knots[0].degree(), q = knots[D - 1].degree();
  for (int k = 1; k + 1 < D; ++k)
    if (knots[k].degree() != p) return {};
  if (q == p) return select<FixedSet, D>(p, stride, level);
  if constexpr (D > 1)
    return mixed_kernels<D>(p, q, stride, level);
  return {};
}

template <int D>
BezierKernels<D> bezier_kernels(int degree, int stride, SimdLevel level) {
  return select<BezierSet, D>(degree, stride, level);
}

template FixedKernels<1> fixed_kernels<1>(const std::array<KnotVector, 1>&, int, SimdLevel);
template FixedKernels<2> fixed_kernels<2>(const std::array<KnotVector, 2>&, int, SimdLevel);
template FixedKernels<3> fixed_kernels<3>(const std::array<KnotVector, 3>&, int, SimdLevel);
template BezierKernels<2> bezier_kernels<2>(int, int, SimdLevel);
template BezierKernels<3> bezier_kernels<3>(int, int, SimdLevel);

}  // namespace trivar
