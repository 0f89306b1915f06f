#include "trivar/lr/lr_spline.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

namespace {

template <int D>
std::vector<double> key_of(const LRBSpline<D>& b) {
  std::vector<double> key;
  for (int k = 0; k < D; ++k) key.insert(key.end(), b.knots[k].begin(), b.knots[k].end());
  return key;
}

// Value (and derivative) of the single B-spline of degree p on local knots y[0..p+1] at u, where
// y[0] <= u <= y[p+1]. The local knots are padded by p copies of each end so that the library's triangular
// scheme, which reads p knots either side of the span, applies unchanged.
template <bool kDerivs>
void local_bspline(const double* y, int p, double u, double& value, double& deriv) {
  double t[3 * kMaxDegree + 2];
  for (int i = 0; i < p; ++i) {
    t[i] = y[0];
    t[2 * p + 2 + i] = y[p + 1];
  }
  std::copy(y, y + p + 2, t + p);
  int s = 0;
  if (u >= y[p + 1]) {
    s = p;
    while (y[s] == y[s + 1]) --s;
  } else {
    while (u >= y[s + 1]) ++s;
  }
  const int span = s + p;
  if constexpr (kDerivs) {
    double ders[2 * (kMaxDegree + 1)];
    basis_derivatives(t, p, span, u, 1, ders);
    value = ders[p - s];
    deriv = ders[p + 1 + p - s];
  } else {
    double N[kMaxDegree + 1];
    basis_values(t, p, span, u, N);
    value = N[p - s];
    deriv = 0.0;
  }
}

}  // namespace

template <int D>
LRSpline<D>::LRSpline(const TensorSpline<D>& s) : dim_(s.dim()), rational_(s.is_rational()), domain_(s.domain()) {
  for (int k = 0; k < D; ++k) {
    require(s.knots(k).is_clamped(), "LRSpline: knot vector in direction " + std::to_string(k) + " is not clamped");
    degrees_[k] = s.degree(k);
  }
  const int st = stride();
  for (int i = 0; i < s.num_coefs(); ++i) {
    const auto idx = s.multi_index(i);
    LRBSpline<D> b;
    for (int k = 0; k < D; ++k) {
      const auto& t = s.knots(k).knots();
      b.knots[k].assign(t.begin() + idx[k], t.begin() + idx[k] + degrees_[k] + 2);
    }
    b.coef.assign(s.coef(i), s.coef(i) + st);
    auto key = key_of(b);
    basis_.emplace(std::move(key), std::move(b));
  }
  std::array<std::vector<double>, D> breaks;
  for (int k = 0; k < D; ++k) {
    breaks[k] = s.knots(k).breakpoints();
    for (double v : breaks[k]) {
      mesh_.push_back(MeshRectangle<D>::make(k, v, domain_.lo, domain_.hi, s.knots(k).multiplicity(v)));
    }
  }
  Ints<D> c{};
  for (;;) {
    Box<D> e;
    for (int k = 0; k < D; ++k) {
      e.lo[k] = breaks[k][c[k]];
      e.hi[k] = breaks[k][c[k] + 1];
    }
    elements_.push_back(e);
    int k = 0;
    for (; k < D; ++k) {
      if (++c[k] + 1 < static_cast<int>(breaks[k].size())) break;
      c[k] = 0;
    }
    if (k == D) break;
  }
  rebuild_lookup();
}

template <int D>
void LRSpline<D>::add_to_mesh(const MeshRectangle<D>& r) {
  MeshRectangle<D> n = r;
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::size_t i = 0; i < mesh_.size() && !changed; ++i) {
      const auto& e = mesh_[i];
      if (e.dir != n.dir || e.value != n.value) continue;
      if (e.multiplicity <= n.multiplicity && n.contains_across(e.extent)) {
        changed = true;
      } else if (e.multiplicity == n.multiplicity) {
        // The union is a box when the extents agree in all directions but one and touch or overlap in it.
        int differing = -1, count = 0;
        for (int j = 0; j < D; ++j)
          if (j != n.dir && (e.extent.lo[j] != n.extent.lo[j] || e.extent.hi[j] != n.extent.hi[j])) {
            differing = j;
            ++count;
          }
        if (count == 1 && e.extent.lo[differing] <= n.extent.hi[differing] &&
            n.extent.lo[differing] <= e.extent.hi[differing]) {
          n.extent.lo[differing] = std::min(n.extent.lo[differing], e.extent.lo[differing]);
          n.extent.hi[differing] = std::max(n.extent.hi[differing], e.extent.hi[differing]);
          changed = true;
        }
      }
      if (changed) mesh_.erase(mesh_.begin() + static_cast<std::ptrdiff_t>(i));
    }
  }
  mesh_.push_back(n);
}

template <int D>
void LRSpline<D>::add_basis(LRBSpline<D>&& b, std::vector<std::vector<double>>& queue) {
  auto key = key_of(b);
  auto it = basis_.find(key);
  if (it == basis_.end()) {
    basis_.emplace(key, std::move(b));
  } else {
    // gamma c is what the function sees: keep sum gamma_i c_i for the merged B-spline.
    auto& old = it->second;
    const double g = old.gamma + b.gamma;
    for (std::size_t i = 0; i < old.coef.size(); ++i) old.coef[i] = (old.gamma * old.coef[i] + b.gamma * b.coef[i]) / g;
    old.gamma = g;
  }
  queue.push_back(std::move(key));
}

template <int D>
bool LRSpline<D>::split_once(const std::vector<double>& key, std::vector<std::vector<double>>& queue) {
  auto it = basis_.find(key);
  if (it == basis_.end()) return false;
  const Box<D> supp = it->second.support();
  for (int k = 0; k < D; ++k) {
    const int p = degrees_[k];
    const auto& y = it->second.knots[k];
    for (const auto& r : mesh_) {
      if (r.dir != k || r.value <= supp.lo[k] || r.value >= supp.hi[k]) continue;
      const double z = r.value;
      const int m = static_cast<int>(std::count(y.begin(), y.end(), z));
      if (!mesh_covers(mesh_, k, z, supp, m + 1)) continue;
      // Two-term split B[y] = a1 B[y'_0..y'_{p+1}] + a2 B[y'_1..y'_{p+2}], y' = y with z inserted.
      const double a1 = (y[p] <= z && z < y[p + 1]) ? 1.0 : (z - y[0]) / (y[p] - y[0]);
      const double a2 = (y[0] < z && z <= y[1]) ? 1.0 : (y[p + 1] - z) / (y[p + 1] - y[1]);
      std::vector<double> yz(y);
      yz.insert(std::upper_bound(yz.begin(), yz.end(), z), z);
      LRBSpline<D> b1 = it->second;
      LRBSpline<D> b2 = std::move(it->second);
      basis_.erase(it);
      b1.knots[k].assign(yz.begin(), yz.end() - 1);
      b1.gamma *= a1;
      b2.knots[k].assign(yz.begin() + 1, yz.end());
      b2.gamma *= a2;
      add_basis(std::move(b1), queue);
      add_basis(std::move(b2), queue);
      return true;
    }
  }
  return false;
}

template <int D>
bool LRSpline<D>::insert(const MeshRectangle<D>& r) {
  const int k = r.dir;
  const auto where = [&] {
    return "LRSpline::insert: mesh rectangle in direction " + std::to_string(k) + " at " + std::to_string(r.value);
  };
  require(k >= 0 && k < D, [&] { return where() + ": direction out of range"; });
  require(r.multiplicity >= 1 && r.multiplicity <= degrees_[k] + 1,
          [&] { return where() + ": multiplicity " + std::to_string(r.multiplicity) + " outside 1..p+1"; });
  require(r.value > domain_.lo[k] && r.value < domain_.hi[k],
          [&] { return where() + ": value not inside the domain"; });
  for (int j = 0; j < D; ++j)
    if (j != k)
      require(domain_.lo[j] <= r.extent.lo[j] && r.extent.lo[j] < r.extent.hi[j] && r.extent.hi[j] <= domain_.hi[j],
              [&] { return where() + ": extent in direction " + std::to_string(j) + " empty or outside the domain"; });
  Box<D> across = r.extent;
  if (mesh_covers(mesh_, k, r.value, across, r.multiplicity)) return false;
  // Every element the rectangle cuts or lies on must be cut or bounded across its whole cross-section:
  // otherwise the rectangle ends inside an element or inside an element face.
  for (const auto& e : elements_)
    if (e.lo[k] <= r.value && r.value <= e.hi[k] && r.overlaps_across(e))
      require(r.contains_across(e), [&] { return where() + ": rectangle ends inside an element or face"; });

  const auto old_mesh = mesh_;
  add_to_mesh(r);
  std::vector<std::vector<double>> queue;
  for (const auto& [key, b] : basis_) {
    const Box<D> s = b.support();
    if (s.lo[k] < r.value && r.value < s.hi[k] && r.overlaps_across(s)) queue.push_back(key);
  }
  int splits = 0;
  while (!queue.empty()) {
    const auto key = std::move(queue.back());
    queue.pop_back();
    if (split_once(key, queue)) ++splits;
  }
  if (splits == 0) {
    mesh_ = old_mesh;
    throw Error(where() + ": splits no B-spline support");
  }
  std::vector<Box<D>> refined;
  refined.reserve(elements_.size() + 16);
  for (const auto& e : elements_) {
    if (e.lo[k] < r.value && r.value < e.hi[k] && r.overlaps_across(e)) {
      Box<D> a = e, b = e;
      a.hi[k] = r.value;
      b.lo[k] = r.value;
      refined.push_back(a);
      refined.push_back(b);
    } else {
      refined.push_back(e);
    }
  }
  elements_ = std::move(refined);
  rebuild_lookup();
  return true;
}

namespace {

template <int D>
int cell_of(const Box<D>& domain, const Ints<D>& grid, int k, double x) {
  const double f = (x - domain.lo[k]) / domain.extent(k) * grid[k];
  return std::clamp(static_cast<int>(std::floor(f)), 0, grid[k] - 1);
}

}  // namespace

template <int D>
void LRSpline<D>::rebuild_lookup() {
  const double n = std::max(1.0, std::round(std::pow(static_cast<double>(elements_.size()), 1.0 / D)));
  int total = 1;
  for (int k = 0; k < D; ++k) {
    grid_[k] = static_cast<int>(n);
    total *= grid_[k];
  }
  buckets_.assign(static_cast<std::size_t>(total), {});
  const auto for_cells = [&](const Box<D>& b, auto&& f) {
    Ints<D> lo{}, hi{}, c{};
    for (int k = 0; k < D; ++k) {
      lo[k] = cell_of<D>(domain_, grid_, k, b.lo[k]);
      hi[k] = cell_of<D>(domain_, grid_, k, b.hi[k]);
    }
    c = lo;
    for (;;) {
      int linear = 0;
      for (int k = D - 1; k >= 0; --k) linear = linear * grid_[k] + c[k];
      f(buckets_[static_cast<std::size_t>(linear)]);
      int k = 0;
      for (; k < D; ++k) {
        if (++c[k] <= hi[k]) break;
        c[k] = lo[k];
      }
      if (k == D) return;
    }
  };
  for (int e = 0; e < static_cast<int>(elements_.size()); ++e)
    for_cells(elements_[static_cast<std::size_t>(e)], [&](std::vector<int>& bucket) { bucket.push_back(e); });
  element_basis_.assign(elements_.size(), {});
  std::vector<int> stamp(elements_.size(), -1);
  int id = 0;
  for (const auto& [key, b] : basis_) {
    const Box<D> s = b.support();
    for_cells(s, [&](std::vector<int>& bucket) {
      for (int e : bucket) {
        if (stamp[static_cast<std::size_t>(e)] == id) continue;
        stamp[static_cast<std::size_t>(e)] = id;
        const auto& el = elements_[static_cast<std::size_t>(e)];
        bool inside = true;
        for (int k = 0; k < D && inside; ++k) inside = s.lo[k] <= el.lo[k] && el.hi[k] <= s.hi[k];
        if (inside) element_basis_[static_cast<std::size_t>(e)].push_back(&b);
      }
    });
    ++id;
  }
}

template <int D>
int LRSpline<D>::find_element(const Param<D>& u) const {
  int linear = 0;
  for (int k = D - 1; k >= 0; --k) linear = linear * grid_[k] + cell_of<D>(domain_, grid_, k, u[k]);
  for (int e : buckets_[static_cast<std::size_t>(linear)]) {
    const auto& el = elements_[static_cast<std::size_t>(e)];
    bool in = true;
    for (int k = 0; k < D && in; ++k)
      in = el.lo[k] <= u[k] && (u[k] < el.hi[k] || (u[k] == el.hi[k] && el.hi[k] == domain_.hi[k]));
    if (in) return e;
  }
  throw Error("LRSpline: no element contains the parameter point (corrupt mesh)");
}

template <int D>
template <bool kDerivs>
void LRSpline<D>::evaluate(const Param<D>& u_in, double* out) const {
  Param<D> u;
  for (int k = 0; k < D; ++k) u[k] = std::clamp(u_in[k], domain_.lo[k], domain_.hi[k]);
  const int st = stride();
  constexpr int kParts = kDerivs ? D + 1 : 1;
  // Homogeneous accumulators: value, then one block per partial derivative.
  double acc[kParts * (kMaxDegree + 1)] = {};
  require(st <= kMaxDegree + 1, "LRSpline: control dimension too large for evaluation");
  for (const auto* b : element_basis_[static_cast<std::size_t>(find_element(u))]) {
    double v[D], d[D];
    for (int k = 0; k < D; ++k) local_bspline<kDerivs>(b->knots[k].data(), degrees_[k], u[k], v[k], d[k]);
    double w[kParts];
    w[0] = b->gamma;
    for (int k = 0; k < D; ++k) w[0] *= v[k];
    if constexpr (kDerivs) {
      for (int q = 0; q < D; ++q) {
        double x = b->gamma;
        for (int k = 0; k < D; ++k) x *= (k == q ? d[k] : v[k]);
        w[q + 1] = x;
      }
    }
    for (int q = 0; q < kParts; ++q)
      for (int i = 0; i < st; ++i) acc[q * st + i] += w[q] * b->coef[static_cast<std::size_t>(i)];
  }
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
void LRSpline<D>::eval(const Param<D>& u, double* out) const {
  evaluate<false>(u, out);
}

template <int D>
void LRSpline<D>::eval_first_derivatives(const Param<D>& u, double* out) const {
  evaluate<true>(u, out);
}

template class LRSpline<2>;
template class LRSpline<3>;

}  // namespace trivar
