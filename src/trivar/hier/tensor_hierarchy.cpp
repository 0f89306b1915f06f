#include "trivar/hier/tensor_hierarchy.hpp"

#include <algorithm>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/spline/knot_refinement.hpp"

namespace trivar {

double HierarchyAxis::brk(int e) const {
  const int r = 1 << shift_;
  const int b = e >> shift_, j = e & (r - 1);
  const auto& br = base_->breaks;
  if (j == 0) return br[static_cast<std::size_t>(b)];
  // j / r is exact, so a breakpoint of a level is the same double on every finer level.
  return br[static_cast<std::size_t>(b)] +
         (br[static_cast<std::size_t>(b) + 1] - br[static_cast<std::size_t>(b)]) * (static_cast<double>(j) / r);
}

int HierarchyAxis::first_index(int e) const {
  const int r = 1 << shift_;
  const int b = e >> shift_, j = e & (r - 1);
  return base_->first_knot[static_cast<std::size_t>(b)] + b * (r - 1) + (j > 0 ? base_->mult[static_cast<std::size_t>(b)] + j - 1 : 0);
}

int HierarchyAxis::break_of_knot(int i) const {
  // The base breakpoint b with first_index(b << shift) <= i, then the offset inside its copies and new knots.
  const int r = 1 << shift_;
  const auto& fk = base_->first_knot;
  int lo = 0, hi = static_cast<int>(base_->breaks.size()) - 1;
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (fk[static_cast<std::size_t>(mid)] + mid * (r - 1) <= i) lo = mid;
    else hi = mid - 1;
  }
  const int o = i - (fk[static_cast<std::size_t>(lo)] + lo * (r - 1));
  const int m = base_->mult[static_cast<std::size_t>(lo)];
  return (lo << shift_) + (o < m ? 0 : o - m + 1);
}

void HierarchyAxis::knots(int i, int count, double* out) const {
  int e = break_of_knot(i);
  int left = first_index(e) + multiplicity(e) - i;  // copies of brk(e) from index i on
  double v = brk(e);
  for (int n = 0; n < count; ++n) {
    if (left == 0) {
      ++e;
      v = brk(e);
      left = multiplicity(e);
    }
    out[n] = v;
    --left;
  }
}

int HierarchyAxis::cell_of(double x) const {
  const auto& br = base_->breaks;
  const int nb = static_cast<int>(br.size()) - 1;
  const int b = std::clamp(static_cast<int>(std::upper_bound(br.begin(), br.end(), x) - br.begin()) - 1, 0, nb - 1);
  if (shift_ == 0) return b;
  const int r = 1 << shift_;
  const double lo = br[static_cast<std::size_t>(b)], hi = br[static_cast<std::size_t>(b) + 1];
  int j = static_cast<int>(std::clamp((x - lo) / (hi - lo) * r, 0.0, static_cast<double>(r - 1)));
  int e = (b << shift_) + j;
  // Correct the rounding of the guess against the breakpoints themselves.
  while (e > (b << shift_) && x < brk(e)) --e;
  while (e + 1 < ((b + 1) << shift_) && x >= brk(e + 1)) ++e;
  return e;
}

namespace {

std::shared_ptr<const HierarchyBase> make_base(const KnotVector& kv) {
  auto b = std::make_shared<HierarchyBase>();
  b->knots = kv;
  b->breaks = kv.unique();
  b->mult = kv.multiplicities();
  b->first_knot.assign(1, 0);
  for (int m : b->mult) b->first_knot.push_back(b->first_knot.back() + m);
  return b;
}

}  // namespace

template <int D>
TensorHierarchy<D>::TensorHierarchy(const std::array<KnotVector, D>& level0) {
  add_given(level0);
}

template <int D>
TensorHierarchy<D>::TensorHierarchy(const std::vector<std::array<KnotVector, D>>& levels) {
  require(!levels.empty(), "hierarchy: no levels");
  for (const auto& kv : levels) add_given(kv);
}

template <int D>
void TensorHierarchy<D>::add_given(const std::array<KnotVector, D>& kv) {
  const int l = num_levels();
  Level level;
  for (int k = 0; k < D; ++k) {
    auto where = [&] { return "hierarchy: level " + std::to_string(l) + ", direction " + std::to_string(k); };
    require(kv[k].is_clamped(), [&] { return where() + ": the knot vector must be clamped (p + 1 equal end knots)"; });
    if (l == 0) {
      degrees_[k] = kv[k].degree();
    } else {
      const KnotVector& below = levels_.back().axes[k].base().knots;
      require(kv[k].degree() == degrees_[k], [&] {
        return where() + ": degree " + std::to_string(kv[k].degree()) + " differs from " + std::to_string(degrees_[k]) +
               " of level 0";
      });
      require(kv[k].start() == below.start() && kv[k].end() == below.end(),
              [&] { return where() + ": the domain differs from level " + std::to_string(l - 1) + "'s"; });
      // Nestedness: every knot of the level below, at least as often.
      const auto& a = below.knots();
      const auto& b = kv[k].knots();
      std::size_t j = 0;
      for (double x : a) {
        while (j < b.size() && b[j] < x) ++j;
        require(j < b.size() && b[j] == x, [&] {
          return where() + ": knot " + std::to_string(x) + " of level " + std::to_string(l - 1) +
                 " is missing (the levels must be nested)";
        });
        ++j;
      }
    }
    require(kv[k].num_elements() <= kMaxIndex, [&] { return where() + ": more than " + std::to_string(kMaxIndex) + " cells"; });
    level.axes[k] = HierarchyAxis(make_base(kv[k]), 0);
    if (l > 0) {
      const HierarchyAxis& lo = levels_.back().axes[k];
      const HierarchyAxis& hi = level.axes[k];
      auto& parent = level.parent[k];
      auto& first = levels_.back().first_child[k];
      parent.resize(static_cast<std::size_t>(hi.num_cells()));
      first.assign(static_cast<std::size_t>(lo.num_cells()) + 1, 0);
      for (int c = 0; c < hi.num_cells(); ++c) {
        const int e = lo.cell_of(0.5 * (hi.brk(c) + hi.brk(c + 1)));
        parent[static_cast<std::size_t>(c)] = e;
        ++first[static_cast<std::size_t>(e) + 1];
      }
      for (int e = 0; e < lo.num_cells(); ++e) first[static_cast<std::size_t>(e) + 1] += first[static_cast<std::size_t>(e)];
    }
  }
  levels_.push_back(std::move(level));
  given_ = num_levels();
}

template <int D>
void TensorHierarchy<D>::ensure_levels(int n) {
  while (num_levels() < n) {
    Level next;
    for (int k = 0; k < D; ++k) {
      const HierarchyAxis& a = levels_.back().axes[k];
      require(a.num_cells() <= kMaxIndex / 2, [&] {
        return "hierarchy: level " + std::to_string(num_levels()) + " would have " +
               std::to_string(2 * static_cast<long long>(a.num_cells())) + " cells in direction " + std::to_string(k) +
               ", more than " + std::to_string(kMaxIndex);
      });
      next.axes[k] = HierarchyAxis(a.base_ptr(), a.shift() + 1);
    }
    levels_.push_back(std::move(next));
  }
}

template <int D>
KnotVector TensorHierarchy<D>::knots(int level, int k) const {
  const HierarchyAxis& a = axis(level, k);
  if (a.shift() == 0) return a.base().knots;
  std::vector<double> t(static_cast<std::size_t>(a.num_knots()));
  a.knots(0, a.num_knots(), t.data());
  return KnotVector(degrees_[k], std::move(t));
}

template <int D>
Box<D> TensorHierarchy<D>::domain() const {
  Box<D> b;
  for (int k = 0; k < D; ++k) {
    b.lo[k] = axis(0, k).base().knots.start();
    b.hi[k] = axis(0, k).base().knots.end();
  }
  return b;
}

template <int D>
Box<D> TensorHierarchy<D>::cell_box(int level, const Ints<D>& cell) const {
  Box<D> b;
  for (int k = 0; k < D; ++k) {
    b.lo[k] = axis(level, k).brk(cell[k]);
    b.hi[k] = axis(level, k).brk(cell[k] + 1);
  }
  return b;
}

template <int D>
int TensorHierarchy<D>::parent(int level, int k, int c) const {
  if (level >= given_) return c >> 1;
  return levels_[static_cast<std::size_t>(level)].parent[k][static_cast<std::size_t>(c)];
}

template <int D>
int TensorHierarchy<D>::first_child(int level, int k, int c) const {
  if (level + 1 >= given_) return c << 1;
  return levels_[static_cast<std::size_t>(level)].first_child[k][static_cast<std::size_t>(c)];
}

template <int D>
void TensorHierarchy<D>::local_refinement(int level, int k, int cell, double* R) const {
  const int p = degrees_[k];
  const HierarchyAxis& fine = axis(level, k);
  const HierarchyAxis& coarse = axis(level - 1, k);
  const int sf = fine.span(cell);
  const int sc = coarse.span(parent(level, k, cell));
  // The fine B-splines on the cell are those of the window t^l[sf-p .. sf+p+1]; express_in is exact on its
  // middle span, the cell.
  double window[2 * kMaxDegree + 2], local[2 * kMaxDegree + 2];
  fine.knots(sf - p, 2 * p + 2, window);
  coarse.knots(sc - p, 2 * p + 2, local);
  for (int a = 0; a <= p; ++a)
    express_in<double>(std::span<const double>(local + a, static_cast<std::size_t>(p + 2)),
                       std::span<const double>(window, static_cast<std::size_t>(2 * p + 2)), R + a * (p + 1));
}

template <int D>
void TensorHierarchy<D>::local_bezier(int level, int k, int cell, double* C) const {
  const int p = degrees_[k];
  const HierarchyAxis& a = axis(level, k);
  const int s = a.span(cell);
  const double lo = a.brk(cell), hi = a.brk(cell + 1);
  double t[2 * kMaxDegree + 2];
  a.knots(s - p, 2 * p + 2, t);
  for (int r = 0; r <= p; ++r)
    bernstein_coefficients<double>(std::span<const double>(t + r, static_cast<std::size_t>(p + 2)), lo, hi, C + r * (p + 1));
}

template <int D>
void TensorHierarchy<D>::two_scale(int level, int k, int i, int& first, std::vector<double>& w) const {
  const int p = degrees_[k];
  const HierarchyAxis& coarse = axis(level, k);
  const HierarchyAxis& fine = axis(level + 1, k);
  double local[kMaxDegree + 2];
  coarse.knots(i, p + 2, local);
  const int m_start = static_cast<int>(std::count(local, local + p + 2, local[0]));
  const int m_end = static_cast<int>(std::count(local, local + p + 2, local[p + 1]));
  // The fine knots from local's first value (with local's multiplicity there) to its last.
  const int c0 = first_child(level, k, coarse.first_cell(i));
  const int c1 = first_child(level, k, coarse.end_cell(i));  // fine breakpoint of the last value
  first = fine.span(c0) - m_start + 1;
  const int last = fine.span(c1 - 1) + m_end;  // first copy of the last value, then m_end - 1 more
  std::vector<double> t(static_cast<std::size_t>(last - first + 1));
  fine.knots(first, static_cast<int>(t.size()), t.data());
  w.resize(t.size() - static_cast<std::size_t>(p) - 1);
  express_in<double>(std::span<const double>(local, static_cast<std::size_t>(p + 2)), t, w.data());
}

template class TensorHierarchy<2>;
template class TensorHierarchy<3>;

}  // namespace trivar
