#include "trivar/hier/tensor_hierarchy.hpp"

#include <algorithm>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/spline/knot_refinement.hpp"

namespace trivar {

int HierarchyAxis::cell_of(double x) const {
  const auto it = std::upper_bound(breaks.begin(), breaks.end(), x);
  const int e = static_cast<int>(it - breaks.begin()) - 1;
  return std::clamp(e, 0, num_cells() - 1);
}

namespace {

HierarchyAxis make_axis(const KnotVector& kv) {
  HierarchyAxis a;
  a.knots = kv;
  a.breaks = kv.breakpoints();
  const int p = kv.degree(), n = kv.size();
  const auto& t = kv.knots();
  a.span.resize(a.breaks.size() - 1);
  for (int s = p, e = 0; s < n; ++s)
    if (t[static_cast<std::size_t>(s)] < t[static_cast<std::size_t>(s) + 1]) a.span[static_cast<std::size_t>(e++)] = s;
  a.first_cell.resize(static_cast<std::size_t>(n));
  a.end_cell.resize(static_cast<std::size_t>(n));
  auto index = [&](double x) {
    return static_cast<int>(std::lower_bound(a.breaks.begin(), a.breaks.end(), x) - a.breaks.begin());
  };
  for (int i = 0; i < n; ++i) {
    a.first_cell[static_cast<std::size_t>(i)] = index(t[static_cast<std::size_t>(i)]);
    a.end_cell[static_cast<std::size_t>(i)] = index(t[static_cast<std::size_t>(i + p + 1)]);
  }
  return a;
}

}  // namespace

template <int D>
TensorHierarchy<D>::TensorHierarchy(const std::array<KnotVector, D>& level0) {
  add_level(level0);
  dyadic_from_ = 1;
}

template <int D>
TensorHierarchy<D>::TensorHierarchy(const std::vector<std::array<KnotVector, D>>& levels) {
  require(!levels.empty(), "hierarchy: no levels");
  for (const auto& kv : levels) add_level(kv);
  dyadic_from_ = num_levels();
}

template <int D>
void TensorHierarchy<D>::add_level(const std::array<KnotVector, D>& kv) {
  const int l = num_levels();
  std::array<HierarchyAxis, D> axes;
  // The level below gets its children table: copied first, as other hierarchies may share it.
  if (l > 0) levels_.back() = std::make_shared<std::array<HierarchyAxis, D>>(*levels_.back());
  for (int k = 0; k < D; ++k) {
    auto where = [&] { return "hierarchy: level " + std::to_string(l) + ", direction " + std::to_string(k); };
    require(kv[k].is_clamped(), [&] { return where() + ": the knot vector must be clamped (p + 1 equal end knots)"; });
    if (l == 0) {
      degrees_[k] = kv[k].degree();
    } else {
      const KnotVector& below = knots(l - 1, k);
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
    axes[k] = make_axis(kv[k]);
    if (l > 0) {
      HierarchyAxis& lo = (*levels_.back())[k];
      HierarchyAxis& hi = axes[k];
      hi.parent.resize(static_cast<std::size_t>(hi.num_cells()));
      lo.first_child.assign(static_cast<std::size_t>(lo.num_cells()) + 1, 0);
      for (int c = 0; c < hi.num_cells(); ++c) {
        const int e = lo.cell_of(0.5 * (hi.breaks[static_cast<std::size_t>(c)] + hi.breaks[static_cast<std::size_t>(c) + 1]));
        hi.parent[static_cast<std::size_t>(c)] = e;
        ++lo.first_child[static_cast<std::size_t>(e) + 1];
      }
      for (int e = 0; e < lo.num_cells(); ++e)
        lo.first_child[static_cast<std::size_t>(e) + 1] += lo.first_child[static_cast<std::size_t>(e)];
    } else {
      axes[k].parent.assign(static_cast<std::size_t>(axes[k].num_cells()), -1);
    }
  }
  levels_.push_back(std::make_shared<std::array<HierarchyAxis, D>>(std::move(axes)));
}

template <int D>
void TensorHierarchy<D>::ensure_levels(int n) {
  while (num_levels() < n) {
    std::array<KnotVector, D> next;
    double bytes = 0;
    for (int k = 0; k < D; ++k) {
      const HierarchyAxis& a = (*levels_.back())[k];
      // The knots with the middle of every non-empty span inserted after its left end's copies.
      const auto& t = a.knots.knots();
      std::vector<double> finer;
      finer.reserve(t.size() + a.breaks.size());
      for (std::size_t i = 0; i < t.size(); ++i) {
        finer.push_back(t[i]);
        if (i + 1 < t.size() && t[i] < t[i + 1]) finer.push_back(0.5 * (t[i] + t[i + 1]));
      }
      require(a.num_cells() * 2 <= kMaxIndex, [&] {
        return "hierarchy: level " + std::to_string(num_levels()) + " would have " + std::to_string(2 * static_cast<long long>(a.num_cells())) +
               " cells in direction " + std::to_string(k) + ", more than " + std::to_string(kMaxIndex);
      });
      bytes += 8.0 * 8.0 * static_cast<double>(finer.size());
      next[k] = KnotVector(a.knots.degree(), std::move(finer));
    }
    require_memory(bytes, "hierarchy level " + std::to_string(num_levels()));
    add_level(next);
  }
}

template <int D>
Box<D> TensorHierarchy<D>::domain() const {
  Box<D> b;
  for (int k = 0; k < D; ++k) {
    b.lo[k] = knots(0, k).start();
    b.hi[k] = knots(0, k).end();
  }
  return b;
}

template <int D>
Box<D> TensorHierarchy<D>::cell_box(int level, const Ints<D>& cell) const {
  Box<D> b;
  for (int k = 0; k < D; ++k) {
    const auto& br = axis(level, k).breaks;
    b.lo[k] = br[static_cast<std::size_t>(cell[k])];
    b.hi[k] = br[static_cast<std::size_t>(cell[k]) + 1];
  }
  return b;
}

template <int D>
void TensorHierarchy<D>::local_refinement(int level, int k, int cell, double* R) const {
  const int p = degrees_[k];
  const HierarchyAxis& fine = axis(level, k);
  const HierarchyAxis& coarse = axis(level - 1, k);
  const int sf = fine.span[static_cast<std::size_t>(cell)];
  const int sc = coarse.span[static_cast<std::size_t>(fine.parent[static_cast<std::size_t>(cell)])];
  // The fine B-splines on the cell are those of the window t^l[sf-p .. sf+p+1]; express_in is exact on its
  // middle span, the cell.
  const std::span<const double> window(fine.knots.data() + (sf - p), static_cast<std::size_t>(2 * p + 2));
  for (int a = 0; a <= p; ++a)
    express_in<double>(std::span<const double>(coarse.knots.data() + (sc - p + a), static_cast<std::size_t>(p + 2)),
                       window, R + a * (p + 1));
}

template <int D>
void TensorHierarchy<D>::local_bezier(int level, int k, int cell, double* C) const {
  const int p = degrees_[k];
  const HierarchyAxis& a = axis(level, k);
  const int s = a.span[static_cast<std::size_t>(cell)];
  const double lo = a.breaks[static_cast<std::size_t>(cell)], hi = a.breaks[static_cast<std::size_t>(cell) + 1];
  for (int r = 0; r <= p; ++r)
    bernstein_coefficients<double>(std::span<const double>(a.knots.data() + (s - p + r), static_cast<std::size_t>(p + 2)),
                                   lo, hi, C + r * (p + 1));
}

template class TensorHierarchy<2>;
template class TensorHierarchy<3>;

}  // namespace trivar
