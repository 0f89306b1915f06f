#include "trivar/lr/lr_element.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/eval_kernels.hpp"
#include "trivar/spline/knot_refinement.hpp"

namespace trivar {

namespace {

inline void bernstein_any(int p, double t, double h, double* B, double* dB) {
  switch (p) {
    case 1: bernstein_values<1>(1, t, h, B, dB); break;
    case 2: bernstein_values<2>(2, t, h, B, dB); break;
    case 3: bernstein_values<3>(3, t, h, B, dB); break;
    default: bernstein_values<-1>(p, t, h, B, dB); break;
  }
}

// Dot product of the p + 1 Bernstein coefficients of a row with the Bernstein values.
template <int P>
inline double dot_row(int p_runtime, const double* row, const double* B) {
  const int p = P >= 0 ? P : p_runtime;
  double s = 0.0;
  for (int j = 0; j <= p; ++j) s += row[j] * B[j];
  return s;
}

}  // namespace

template <int D>
ElementEvaluator<D>::ElementEvaluator(const Ints<D>& degrees, int dim, bool rational, const Box<D>& domain,
                                      std::span<const LRBSpline<D>> basis, std::span<const Box<D>> elements,
                                      const Incidence& element_basis)
    : degrees_(degrees), dim_(dim), rational_(rational), domain_(domain), elements_(elements.begin(), elements.end()) {
  const int st = dim + (rational ? 1 : 0);
  gc_.resize(basis.size() * static_cast<std::size_t>(st));
  for (std::size_t i = 0; i < basis.size(); ++i)
    for (int c = 0; c < st; ++c)
      gc_[i * static_cast<std::size_t>(st) + static_cast<std::size_t>(c)] =
          basis[i].gamma * basis[i].coef[static_cast<std::size_t>(c)];

  const std::size_t E = elements.size();
  row_start_.resize(E * D);
  row_count_.resize(E * D);
  entry_start_.assign(E + 1, 0);
  std::array<std::vector<const std::vector<double>*>, D> distinct;
  for (std::size_t e = 0; e < E; ++e) {
    const auto& el = elements[e];
    for (auto& v : distinct) v.clear();
    for (int id : element_basis[static_cast<int>(e)]) {
      Entry en{id, {0, 0, 0, 0}};
      for (int k = 0; k < D; ++k) {
        const auto& y = basis[static_cast<std::size_t>(id)].knots[k];
        auto& dk = distinct[static_cast<std::size_t>(k)];
        std::size_t r = 0;
        while (r < dk.size() && *dk[r] != y) ++r;
        if (r == dk.size()) {
          require(r < 255, [&] {
            return "ElementEvaluator: element " + std::to_string(e) + " has more than 255 distinct B-splines in direction " +
                   std::to_string(k);
          });
          dk.push_back(&y);
        }
        en.row[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(r);
      }
      entries_.push_back(en);
    }
    entry_start_[e + 1] = static_cast<int>(entries_.size());
    for (int k = 0; k < D; ++k) {
      const int p = degrees[k];
      const auto& dk = distinct[static_cast<std::size_t>(k)];
      row_start_[e * D + static_cast<std::size_t>(k)] = static_cast<int>(rows_.size());
      row_count_[e * D + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(dk.size());
      for (const auto* y : dk) {
        rows_.resize(rows_.size() + static_cast<std::size_t>(p + 1));
        bernstein_coefficients<double>(*y, el.lo[k], el.hi[k], rows_.data() + rows_.size() - (p + 1));
      }
    }
  }
  std::vector<int> ids(E);
  for (std::size_t e = 0; e < E; ++e) ids[e] = static_cast<int>(e);
  build_tree(ids, domain, 0);
  build_start_grid();
  build_bezier_blocks(st);
}

template <int D>
void ElementEvaluator<D>::build_start_grid() {
  const double per_direction = std::pow(static_cast<double>(std::max<std::size_t>(elements_.size(), 1)), 1.0 / D);
  std::size_t cells = 1;
  for (int k = 0; k < D; ++k) {
    grid_n_[k] = std::clamp(static_cast<int>(std::ceil(per_direction)), 1, 1 << (18 / D));
    grid_scale_[k] = grid_n_[k] / (domain_.hi[k] - domain_.lo[k]);
    cells *= static_cast<std::size_t>(grid_n_[k]);
    auto& bounds = grid_bounds_[static_cast<std::size_t>(k)];
    bounds.resize(static_cast<std::size_t>(grid_n_[k]) + 1);
    for (int i = 0; i < grid_n_[k]; ++i) bounds[static_cast<std::size_t>(i)] = domain_.lo[k] + i / grid_scale_[k];
    bounds.back() = domain_.hi[k];
  }
  grid_start_.resize(cells);
  for (std::size_t c = 0; c < cells; ++c) {
    Box<D> cell;
    std::size_t rest = c;
    for (int k = 0; k < D; ++k) {
      const auto i = static_cast<int>(rest % static_cast<std::size_t>(grid_n_[k]));
      rest /= static_cast<std::size_t>(grid_n_[k]);
      cell.lo[k] = grid_bounds_[static_cast<std::size_t>(k)][static_cast<std::size_t>(i)];
      cell.hi[k] = grid_bounds_[static_cast<std::size_t>(k)][static_cast<std::size_t>(i) + 1];
    }
    int node = 0;
    for (;;) {
      const Node& n = nodes_[static_cast<std::size_t>(node)];
      if (n.dir < 0) break;
      if (cell.hi[n.dir] <= n.value) node = n.child[0];
      else if (cell.lo[n.dir] >= n.value) node = n.child[1];
      else break;
    }
    grid_start_[c] = node;
  }
}

// Where it fits the budget, each element's polynomial is summed once into its Bezier block (the outer products
// of each B-spline's Bernstein rows times gamma * control value): a point then costs the same contraction as a
// tensor spline's, (p + 1)^D rows, instead of one product per B-spline of the element (more than (p + 1)^D on
// refined elements) with gathered rows.
template <int D>
void ElementEvaluator<D>::build_bezier_blocks(int st) {
  const int p = degrees_[0];
  for (int k = 1; k < D; ++k)
    if (degrees_[k] != p) return;
  const BezierKernels<D> kernels = bezier_kernels<D>(p, st, simd_level());
  std::size_t block = static_cast<std::size_t>(st);
  for (int k = 0; k < D; ++k) block *= static_cast<std::size_t>(p + 1);
  if (!kernels.value || elements_.size() * block * sizeof(double) > kBezierBudget) return;
  blocks_.assign(elements_.size() * block, 0.0);
  block_size_ = block;
  const std::size_t P1 = static_cast<std::size_t>(p + 1);
  std::vector<double> outer(block / static_cast<std::size_t>(st));
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    double* out = blocks_.data() + e * block;
    for (int i = entry_start_[e]; i < entry_start_[e + 1]; ++i) {
      const Entry& en = entries_[static_cast<std::size_t>(i)];
      // Outer product of the rows, direction 0 fastest.
      outer[0] = 1.0;
      std::size_t len = 1;
      for (int k = 0; k < D; ++k) {
        const double* row = rows_.data() + row_start_[e * D + static_cast<std::size_t>(k)] +
                            static_cast<std::size_t>(en.row[static_cast<std::size_t>(k)]) * P1;
        for (std::size_t j = P1; j-- > 0;)
          for (std::size_t x = 0; x < len; ++x) outer[j * len + x] = outer[x] * row[j];
        len *= P1;
      }
      const double* c = gc_.data() + static_cast<std::size_t>(en.id) * static_cast<std::size_t>(st);
      for (std::size_t x = 0; x < len; ++x)
        for (int d = 0; d < st; ++d) out[x * static_cast<std::size_t>(st) + static_cast<std::size_t>(d)] += outer[x] * c[d];
    }
  }
  bezier_value_ = kernels.value;
  bezier_first_ = kernels.first;
}

template <int D>
int ElementEvaluator<D>::build_tree(std::vector<int>& ids, const Box<D>& box, int depth) {
  const int node = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  const auto make_leaf = [&] {
    nodes_[static_cast<std::size_t>(node)].first = static_cast<int>(leaf_elements_.size());
    nodes_[static_cast<std::size_t>(node)].count = static_cast<int>(ids.size());
    leaf_elements_.insert(leaf_elements_.end(), ids.begin(), ids.end());
    return node;
  };
  if (ids.size() <= 2 || depth > 60) return make_leaf();
  std::array<int, D> order;
  for (int k = 0; k < D; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return box.extent(a) > box.extent(b); });
  std::vector<double> centers(ids.size());
  for (int k : order) {
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const auto& el = elements_[static_cast<std::size_t>(ids[i])];
      centers[i] = 0.5 * (el.lo[k] + el.hi[k]);
    }
    auto mid = centers.begin() + static_cast<std::ptrdiff_t>(centers.size() / 2);
    std::nth_element(centers.begin(), mid, centers.end());
    // The element boundary strictly inside the node closest to the median centre.
    double best = 0.0, best_dist = -1.0;
    for (int id : ids) {
      for (double v : {elements_[static_cast<std::size_t>(id)].lo[k], elements_[static_cast<std::size_t>(id)].hi[k]}) {
        if (v <= box.lo[k] || v >= box.hi[k]) continue;
        const double dist = std::abs(v - *mid);
        if (best_dist < 0.0 || dist < best_dist) {
          best = v;
          best_dist = dist;
        }
      }
    }
    if (best_dist < 0.0) continue;
    std::vector<int> left, right;
    for (int id : ids) {
      const auto& el = elements_[static_cast<std::size_t>(id)];
      if (el.lo[k] < best) left.push_back(id);
      if (el.hi[k] > best) right.push_back(id);
    }
    if (left.size() == ids.size() || right.size() == ids.size()) continue;
    ids.clear();
    ids.shrink_to_fit();
    Box<D> lb = box, rb = box;
    lb.hi[k] = best;
    rb.lo[k] = best;
    const int l = build_tree(left, lb, depth + 1);
    const int r = build_tree(right, rb, depth + 1);
    auto& n = nodes_[static_cast<std::size_t>(node)];
    n.dir = k;
    n.value = best;
    n.child[0] = l;
    n.child[1] = r;
    return node;
  }
  return make_leaf();
}

template <int D>
int ElementEvaluator<D>::find_element(const Param<D>& u) const {
  std::size_t cell = 0;
  for (int k = D - 1; k >= 0; --k) {
    int i = std::clamp(static_cast<int>((u[k] - domain_.lo[k]) * grid_scale_[k]), 0, grid_n_[k] - 1);
    // The product can round across a cell bound (u just below a bound); the cell is the one whose stored bounds
    // hold u, or its start node may lie in a subtree without u's element.
    const double* bounds = grid_bounds_[static_cast<std::size_t>(k)].data();
    if (u[k] < bounds[i]) --i;
    else if (i + 1 < grid_n_[k] && u[k] >= bounds[i + 1]) ++i;
    cell = cell * static_cast<std::size_t>(grid_n_[k]) + static_cast<std::size_t>(i);
  }
  const Node* n = nodes_.data() + grid_start_[cell];
  while (n->dir >= 0) n = nodes_.data() + n->child[u[static_cast<std::size_t>(n->dir)] >= n->value ? 1 : 0];
  for (int i = 0; i < n->count; ++i) {
    const int e = leaf_elements_[static_cast<std::size_t>(n->first + i)];
    const auto& el = elements_[static_cast<std::size_t>(e)];
    bool in = true;
    for (int k = 0; k < D && in; ++k)
      in = el.lo[k] <= u[k] && (u[k] < el.hi[k] || (u[k] == el.hi[k] && el.hi[k] == domain_.hi[k]));
    if (in) return e;
  }
  throw Error("ElementEvaluator: no element contains the parameter point (corrupt mesh)");
}

template <int D>
template <bool kDerivs, int kStride>
void ElementEvaluator<D>::evaluate(const Param<D>& u_in, double* out) const {
  Param<D> u;
  for (int k = 0; k < D; ++k) u[k] = std::clamp(u_in[k], domain_.lo[k], domain_.hi[k]);
  const int e = find_element(u);
  const auto& el = elements_[static_cast<std::size_t>(e)];
  constexpr int kParts = kDerivs ? D + 1 : 1;
  if (bezier_value_) {
    Param<D> t, scale;
    for (int k = 0; k < D; ++k) {
      scale[k] = 1.0 / (el.hi[k] - el.lo[k]);
      t[k] = (u[k] - el.lo[k]) * scale[k];
    }
    const double* block = blocks_.data() + block_size_ * static_cast<std::size_t>(e);
    double h[kParts * 4];
    (kDerivs ? bezier_first_ : bezier_value_)(block, t, scale, h);
    finish<kParts>(h, dim_ + (rational_ ? 1 : 0), out);
    return;
  }
  // Per direction, the element's distinct univariate B-splines (and derivatives) at u.
  double val[D][256];
  double der[kDerivs ? D : 1][256];
  for (int k = 0; k < D; ++k) {
    const int p = degrees_[k];
    const double h = 1.0 / (el.hi[k] - el.lo[k]);
    const double t = (u[k] - el.lo[k]) * h;
    double B[kMaxDegree + 1], dB[kMaxDegree + 1];
    bernstein_any(p, t, h, B, kDerivs ? dB : nullptr);
    const std::size_t slot = static_cast<std::size_t>(e) * D + static_cast<std::size_t>(k);
    const double* row = rows_.data() + row_start_[slot];
    const int n = row_count_[slot];
    for (int r = 0; r < n; ++r, row += p + 1) {
      if (p == 3) {
        val[k][r] = dot_row<3>(3, row, B);
        if constexpr (kDerivs) der[k][r] = dot_row<3>(3, row, dB);
      } else {
        val[k][r] = dot_row<-1>(p, row, B);
        if constexpr (kDerivs) der[k][r] = dot_row<-1>(p, row, dB);
      }
    }
  }
  const int st = kStride > 0 ? kStride : dim_ + (rational_ ? 1 : 0);
  double acc[kParts * (kMaxDegree + 1)] = {};
  const Entry* it = entries_.data() + entry_start_[static_cast<std::size_t>(e)];
  const Entry* end = entries_.data() + entry_start_[static_cast<std::size_t>(e) + 1];
  for (; it != end; ++it) {
    const double* c = gc_.data() + static_cast<std::ptrdiff_t>(it->id) * st;
    double v[D];
    for (int k = 0; k < D; ++k) v[k] = val[k][it->row[static_cast<std::size_t>(k)]];
    double w0 = v[0];
    for (int k = 1; k < D; ++k) w0 *= v[k];
    for (int i = 0; i < st; ++i) acc[i] += w0 * c[i];
    if constexpr (kDerivs) {
      for (int q = 0; q < D; ++q) {
        double w = der[q][it->row[static_cast<std::size_t>(q)]];
        for (int k = 0; k < D; ++k)
          if (k != q) w *= v[k];
        for (int i = 0; i < st; ++i) acc[(q + 1) * st + i] += w * c[i];
      }
    }
  }
  finish<kParts>(acc, st, out);
}

template <int D>
template <int kParts>
void ElementEvaluator<D>::finish(const double* acc, int st, double* out) const {
  if (!rational_) {
    std::copy(acc, acc + kParts * st, out);
    return;
  }
  // Quotient rule on homogeneous values: x = X / W, dx = (dX - x dW) / W.
  const double W = acc[dim_];
  for (int i = 0; i < dim_; ++i) out[i] = acc[i] / W;
  for (int q = 1; q < kParts; ++q)
    for (int i = 0; i < dim_; ++i) out[q * dim_ + i] = (acc[q * st + i] - out[i] * acc[q * st + dim_]) / W;
}

template <int D>
template <bool kDerivs>
void ElementEvaluator<D>::dispatch(const Param<D>& u, double* out) const {
  switch (dim_ + (rational_ ? 1 : 0)) {
    case 1: evaluate<kDerivs, 1>(u, out); break;
    case 2: evaluate<kDerivs, 2>(u, out); break;
    case 3: evaluate<kDerivs, 3>(u, out); break;
    case 4: evaluate<kDerivs, 4>(u, out); break;
    default:
      require(dim_ + (rational_ ? 1 : 0) <= kMaxDegree + 1, "ElementEvaluator: control dimension too large");
      evaluate<kDerivs, 0>(u, out);
  }
}

template <int D>
void ElementEvaluator<D>::eval(const Param<D>& u, double* out) const {
  dispatch<false>(u, out);
}

template <int D>
void ElementEvaluator<D>::eval_first_derivatives(const Param<D>& u, double* out) const {
  dispatch<true>(u, out);
}

template class ElementEvaluator<2>;
template class ElementEvaluator<3>;

}  // namespace trivar
