#include "trivar/hier/hierarchical_evaluator.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/hier/local_tensor.hpp"
#include "trivar/spline/derivative_index.hpp"

namespace trivar {

namespace {

// Bernstein values of degree p at t in [0, 1] (triangular scheme, p(p+1)/2 multiply-adds) and optionally the
// derivatives p (b^{p-1}_{i-1} - b^{p-1}_i) / h.
template <int P = -1>
inline void bernstein(int p_runtime, double t, double inv_h, double* b, double* db) {
  const int p = P >= 0 ? P : p_runtime;
  const double s = 1.0 - t;
  b[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    if (db && j == p) {
      for (int i = 0; i <= p; ++i) db[i] = p * inv_h * ((i > 0 ? b[i - 1] : 0.0) - (i < p ? b[i] : 0.0));
    }
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double tmp = b[r];
      b[r] = saved + s * tmp;
      saved = t * tmp;
    }
    b[j] = saved;
  }
  if (db && p == 0) db[0] = 0.0;
}

}  // namespace

template <int D>
HierarchicalEvaluator<D>::HierarchicalEvaluator(const HierarchicalSpace<D>& space, int dim, bool rational,
                                                std::span<const double> coefs)
    : degrees_(space.degrees()), dim_(dim), rational_(rational), local_(space.local_size()) {
  const int st = stride();
  require(coefs.size() == static_cast<std::size_t>(space.num_basis()) * st, "hier: coefficient count does not match the space");
  const int E = space.num_elements();
  nets_.resize(static_cast<std::size_t>(E) * local_ * st);
  boxes_ = space.element_boxes();
  same_degree_ = degrees_[0];
  for (int k = 1; k < D; ++k)
    if (degrees_[k] != same_degree_) same_degree_ = -1;
  Ints<D> n;
  std::array<std::vector<double>, D> B;
  std::array<const double*, D> M;
  std::vector<double> tmp;
  typename HierarchicalSpace<D>::ExpansionCache cache;
  for (int e = 0; e < E; ++e) {
    const HierarchicalCell<D> c = space.element(e);
    double* net = nets_.data() + static_cast<std::ptrdiff_t>(e) * local_ * st;
    space.local_expansion(c.level, c.index, coefs, st, net, cache);
    for (int k = 0; k < D; ++k) {
      n[k] = degrees_[k] + 1;
      B[k].resize(static_cast<std::size_t>(n[k] * n[k]));
      space.hierarchy().local_bezier(c.level, k, c.index[k], B[k].data());
      M[k] = B[k].data();
    }
    apply_kronecker<D>(n, M, st, 1, net, tmp);
  }
  Ints<D> lo{}, hi;
  for (int k = 0; k < D; ++k) hi[k] = space.hierarchy().axis(0, k).num_cells();
  build_table(space, 0, lo, hi);
}

template <int D>
int HierarchicalEvaluator<D>::build_table(const HierarchicalSpace<D>& space, int level, const Ints<D>& lo,
                                          const Ints<D>& hi) {
  int size = 1;
  for (int k = 0; k < D; ++k) size *= hi[k] - lo[k];
  const int start = static_cast<int>(codes_.size());
  codes_.resize(codes_.size() + static_cast<std::size_t>(size));
  Ints<D> c = lo;
  for (int q = 0; q < size; ++q) {
    int code;
    if (space.is_split(level, c)) {
      Ints<D> clo, chi;
      for (int k = 0; k < D; ++k) {
        clo[k] = space.hierarchy().first_child(level, k, c[k]);
        chi[k] = space.hierarchy().end_child(level, k, c[k]);
      }
      code = -build_table(space, level + 1, clo, chi) - 1;
    } else {
      code = space.find_leaf(level, c);
    }
    codes_[static_cast<std::size_t>(start + q)] = code;
    for (int k = 0; k < D && ++c[k] == hi[k]; ++k) c[k] = lo[k];
  }
  return start;
}

template <int D>
int HierarchicalEvaluator<D>::find_element(const HierarchicalSpace<D>& space, const Param<D>& x) const {
  const auto& h = space.hierarchy();
  Ints<D> c;
  int q = 0;
  for (int k = D - 1; k >= 0; --k) {
    c[k] = h.axis(0, k).cell_of(x[k]);
    q = q * h.axis(0, k).num_cells() + c[k];
  }
  int code = codes_[static_cast<std::size_t>(q)];
  for (int level = 0; code < 0; ++level) {
    int offset = 0;
    for (int k = D - 1; k >= 0; --k) {
      const HierarchyAxis& a = h.axis(level + 1, k);
      const int lo = h.first_child(level, k, c[k]), hi = h.end_child(level, k, c[k]);
      int e = lo;
      while (e + 1 < hi && x[k] >= a.brk(e + 1)) ++e;
      c[k] = e;
      offset = offset * (hi - lo) + (e - lo);
    }
    code = codes_[static_cast<std::size_t>(-code - 1 + offset)];
  }
  return code;
}

template <int D>
std::span<const double> HierarchicalEvaluator<D>::net(int e) const {
  const std::size_t size = static_cast<std::size_t>(local_) * stride();
  return {nets_.data() + static_cast<std::size_t>(e) * size, size};
}


template <int D>
template <int N>
void HierarchicalEvaluator<D>::eval_fixed(const Box<D>& box, const double* net, const Param<D>& x, double* h) const {
  // N = p + 1 in every direction: the loops unroll; rows along u are contracted with the row weight of the
  // other directions.
  double b[D][kMaxDegree + 1];
  for (int k = 0; k < D; ++k)
    bernstein<N - 1>(degrees_[k], (x[k] - box.lo[k]) / box.extent(k), 0.0, b[k], nullptr);
  const int st = stride(), n0 = (N > 0 ? N : degrees_[0] + 1);
  const int rows = local_ / n0;
  auto row_weight = [&](int r) {
    double w = 1.0;
    for (int k = 1, q = r; k < D; ++k) {
      const int nk = N > 0 ? N : degrees_[k] + 1;
      w *= b[k][q % nk];
      q /= nk;
    }
    return w;
  };
  if (st == 3) {
    // Local accumulators: the compiler cannot keep h[] in registers (it may alias the net).
    double h0 = 0, h1 = 0, h2 = 0;
    for (int r = 0; r < rows; ++r) {
      const double* row = net + static_cast<std::ptrdiff_t>(r) * n0 * 3;
      double a0 = 0, a1 = 0, a2 = 0;
      for (int a = 0; a < n0; ++a) {
        a0 += b[0][a] * row[3 * a];
        a1 += b[0][a] * row[3 * a + 1];
        a2 += b[0][a] * row[3 * a + 2];
      }
      const double w = row_weight(r);
      h0 += w * a0;
      h1 += w * a1;
      h2 += w * a2;
    }
    h[0] = h0;
    h[1] = h1;
    h[2] = h2;
    return;
  }
  for (int s = 0; s < st; ++s) h[s] = 0.0;
  for (int r = 0; r < rows; ++r) {
    const double w = row_weight(r);
    const double* row = net + static_cast<std::ptrdiff_t>(r) * n0 * st;
    for (int a = 0; a < n0; ++a) {
      const double f = w * b[0][a];
      for (int s = 0; s < st; ++s) h[s] += f * row[a * st + s];
    }
  }
}

template <int D>
void HierarchicalEvaluator<D>::eval(const HierarchicalSpace<D>& space, const Param<D>& u, double* out) const {
  const Box<D> dom = space.domain();
  Param<D> x;
  for (int k = 0; k < D; ++k) x[k] = std::clamp(u[k], dom.lo[k], dom.hi[k]);
  const int e = find_element(space, x);
  const int st = stride();
  const double* net = nets_.data() + static_cast<std::size_t>(e) * local_ * st;
  double acc[16];
  std::vector<double> big;
  double* h = acc;
  if (st > 16) {
    big.resize(static_cast<std::size_t>(st));
    h = big.data();
  }
  const Box<D>& box = boxes_[static_cast<std::size_t>(e)];
  switch (same_degree_) {
    case 1: eval_fixed<2>(box, net, x, h); break;
    case 2: eval_fixed<3>(box, net, x, h); break;
    case 3: eval_fixed<4>(box, net, x, h); break;
    default: eval_fixed<0>(box, net, x, h);
  }
  if (rational_)
    for (int s = 0; s < dim_; ++s) out[s] = h[s] / h[dim_];
  else
    std::copy(h, h + dim_, out);
}

template <int D>
void HierarchicalEvaluator<D>::eval_first_derivatives(const HierarchicalSpace<D>& space, const Param<D>& u,
                                                      double* out) const {
  const Box<D> dom = space.domain();
  Param<D> x;
  for (int k = 0; k < D; ++k) x[k] = std::clamp(u[k], dom.lo[k], dom.hi[k]);
  const int e = find_element(space, x);
  const Box<D>& box = boxes_[static_cast<std::size_t>(e)];
  double b[D][kMaxDegree + 1], db[D][kMaxDegree + 1];
  for (int k = 0; k < D; ++k)
    bernstein(degrees_[k], (x[k] - box.lo[k]) / box.extent(k), 1.0 / box.extent(k), b[k], db[k]);
  const int st = stride();
  const double* net = nets_.data() + static_cast<std::size_t>(e) * local_ * st;
  double small[(D + 1) * 8] = {};
  std::vector<double> big;
  double* hv = small;
  if (st > 8) {
    big.assign(static_cast<std::size_t>((D + 1) * st), 0.0);
    hv = big.data();
  }
  Ints<D> a{};
  for (int q = 0; q < local_; ++q) {
    double w[D + 1];
    w[0] = 1.0;
    for (int k = 0; k < D; ++k) w[0] *= b[k][a[k]];
    for (int d = 0; d < D; ++d) {
      w[d + 1] = 1.0;
      for (int k = 0; k < D; ++k) w[d + 1] *= k == d ? db[k][a[k]] : b[k][a[k]];
    }
    const double* c = net + static_cast<std::size_t>(q) * st;
    for (int d = 0; d <= D; ++d)
      for (int s = 0; s < st; ++s) hv[static_cast<std::size_t>(d * st + s)] += w[d] * c[s];
    for (int k = 0; k < D && ++a[k] == degrees_[k] + 1; ++k) a[k] = 0;
  }
  for (int d = 0; d <= D; ++d)
    for (int s = 0; s < dim_; ++s) {
      double v = hv[static_cast<std::size_t>(d * st + s)];
      if (rational_) {
        const double w0 = hv[static_cast<std::size_t>(dim_)];
        v = d == 0 ? v / w0 : (v - hv[static_cast<std::size_t>(d * st + dim_)] * (hv[static_cast<std::size_t>(s)] / w0)) / w0;
      }
      out[d * dim_ + s] = v;
    }
}

template <int D>
void HierarchicalEvaluator<D>::eval_derivs(const HierarchicalSpace<D>& space, const Param<D>& u, int order,
                                           double* out) const {
  require(order >= 0 && order <= kMaxDerivativeOrder, "hier: derivative order " + std::to_string(order) + " out of range");
  const Box<D> dom = space.domain();
  Param<D> x;
  for (int k = 0; k < D; ++k) x[k] = std::clamp(u[k], dom.lo[k], dom.hi[k]);
  const int e = find_element(space, x);
  const Box<D>& box = boxes_[static_cast<std::size_t>(e)];
  std::array<std::vector<double>, D> B;
  for (int k = 0; k < D; ++k) {
    B[k].resize(static_cast<std::size_t>((order + 1) * (degrees_[k] + 1)));
    bernstein_derivatives(degrees_[k], box.lo[k], box.hi[k], x[k], order, B[k].data());
  }
  const auto table = derivative_multi_indices<D>(order);
  const int nd = static_cast<int>(table.size()), st = stride();
  const double* net = nets_.data() + static_cast<std::size_t>(e) * local_ * st;
  std::vector<double> h(static_cast<std::size_t>(nd * st), 0.0);
  for (int d = 0; d < nd; ++d) {
    Ints<D> a{};
    for (int q = 0; q < local_; ++q) {
      double w = 1.0;
      for (int k = 0; k < D; ++k) w *= B[k][static_cast<std::size_t>(table[static_cast<std::size_t>(d)][k] * (degrees_[k] + 1) + a[k])];
      for (int s = 0; s < st; ++s) h[static_cast<std::size_t>(d * st + s)] += w * net[static_cast<std::size_t>(q * st + s)];
      for (int k = 0; k < D && ++a[k] == degrees_[k] + 1; ++k) a[k] = 0;
    }
  }
  // Generalised quotient rule, as TensorSpline::eval_derivs: S^(a) = (A^(a) - sum_{0 < b <= a} C(a,b) w^(b) S^(a-b)) / w.
  for (int d = 0; d < nd; ++d) {
    double* s = out + static_cast<std::size_t>(d) * dim_;
    for (int c = 0; c < dim_; ++c) s[c] = h[static_cast<std::size_t>(d * st + c)];
    if (!rational_) continue;
    const auto& alpha = table[static_cast<std::size_t>(d)];
    for (int bi = 1; bi <= d; ++bi) {
      const auto& beta = table[static_cast<std::size_t>(bi)];
      bool le = true;
      double f = 1.0;
      std::array<int, D> diff;
      for (int k = 0; k < D; ++k) {
        le = le && beta[k] <= alpha[k];
        diff[k] = alpha[k] - beta[k];
        f *= static_cast<double>(binomial(alpha[k], beta[k]));
      }
      if (!le) continue;
      f *= h[static_cast<std::size_t>(bi * st + dim_)];
      const double* prev = out + static_cast<std::size_t>(derivative_position<D>(diff)) * dim_;
      for (int c = 0; c < dim_; ++c) s[c] -= f * prev[c];
    }
    for (int c = 0; c < dim_; ++c) s[c] /= h[static_cast<std::size_t>(dim_)];
  }
}

template class HierarchicalEvaluator<2>;
template class HierarchicalEvaluator<3>;

}  // namespace trivar
