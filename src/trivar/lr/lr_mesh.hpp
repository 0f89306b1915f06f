#pragma once
// ElementGrid<D>: a uniform bucket grid over a domain holding box ids (an LR mesh's elements), for finding
// the elements a mesh rectangle touches while a refinement adds elements. A box is listed in every cell its
// closed extent meets on the half-open cell partition, so a query with a closed box reports a superset of the
// boxes meeting it (the caller tests the boxes exactly). Boxes that shrink may stay listed in cells they left:
// harmless for a superset.
//
// A locally refined mesh is dense where it was refined: a cell there holds many small boxes, most of which a
// query through the cell misses. query_dense() splits such a cell into kFine parts per direction the first time a query
// reaches it (only where queries go; boxes added later enter both levels), so the cost follows the local
// element size. Sub-cell indices are floor(kFine x position) on the same positions, so a box's or a query's
// sub-cells always lie inside its cells.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "trivar/core/box.hpp"

namespace trivar {

template <int D>
class ElementGrid {
public:
  // About `cells` cells in all, as equal per direction as the domain allows.
  ElementGrid(const Box<D>& domain, std::size_t cells) : domain_(domain) {
    const double n = std::max(1.0, std::round(std::pow(static_cast<double>(std::max<std::size_t>(cells, 1)), 1.0 / D)));
    std::size_t total = 1;
    for (int k = 0; k < D; ++k) {
      n_[k] = static_cast<int>(n);
      scale_[k] = n / domain.extent(k);
      total *= static_cast<std::size_t>(n_[k]);
    }
    cells_.resize(total);
  }

  void add(int id, const Box<D>& b) {
    Ints<D> lo, hi, sub_lo, sub_hi;
    box_cells(b, 1, lo, hi);
    bool sub_known = false;
    for_cells(lo, hi, [&](std::size_t cell, const Ints<D>& c) {
      cells_[cell].push_back(id);
      if (split_.empty() || split_[cell] < 0) return;
      if (!sub_known) box_cells(b, kFine, sub_lo, sub_hi);
      sub_known = true;
      add_to_subcells(id, cell, c, sub_lo, sub_hi);
    });
    if (static_cast<std::size_t>(id) >= stamp_.size()) stamp_.resize(static_cast<std::size_t>(id) + 1, 0);
  }

  // Calls f(id) once for every listed box that may meet the closed box q.
  template <class F>
  void query(const Box<D>& q, F&& f) {
    ++epoch_;
    Ints<D> lo, hi;
    query_cells(q, 1, lo, hi);
    for_cells(lo, hi, [&](std::size_t cell, const Ints<D>&) { visit(cells_[cell], f); });
  }

  // As query(), splitting the cells it reaches that hold more than kDense boxes; box(id) is the current box of
  // id (contained in the box it was added with).
  template <class Boxes, class F>
  void query_dense(const Box<D>& q, Boxes&& box, F&& f) {
    ++epoch_;
    Ints<D> lo, hi, sub_lo, sub_hi;
    query_cells(q, 1, lo, hi);
    query_cells(q, kFine, sub_lo, sub_hi);
    if (split_.empty()) split_.assign(cells_.size(), -1);
    for_cells(lo, hi, [&](std::size_t cell, const Ints<D>& c) {
      if (split_[cell] < 0) {
        if (cells_[cell].size() <= kDense) return visit(cells_[cell], f);
        split_[cell] = static_cast<int>(subcells_.size());
        subcells_.resize(subcells_.size() + kSubcells);
        for (int id : cells_[cell]) {
          Ints<D> blo, bhi;
          box_cells(box(id), kFine, blo, bhi);
          add_to_subcells(id, cell, c, blo, bhi);
        }
      }
      for_subcells(cell, c, sub_lo, sub_hi, [&](std::vector<int>& ids) { visit(ids, f); });
    });
  }

private:
  Box<D> domain_;
  Ints<D> n_{};
  Param<D> scale_{};
  static constexpr std::size_t kDense = 48;
  static constexpr int kFine = 4;  // sub-cells per cell and direction (a power of two: kFine * x is exact)
  static constexpr std::size_t kSubcells = [] {
    std::size_t n = 1;
    for (int k = 0; k < D; ++k) n *= kFine;
    return n;
  }();
  std::vector<std::vector<int>> cells_;
  std::vector<int> split_;                  // per cell: its first sub-cell in subcells_, or -1 (query_dense only)
  std::vector<std::vector<int>> subcells_;  // kSubcells per split cell, the first direction fastest
  std::vector<int> stamp_;
  int epoch_ = 0;

  // Monotone in x, so the cell ranges of two closed intervals that meet always meet. `fine` is 1 for cells,
  // kFine for sub-cells (a multiplication by a power of two is exact, so sub-cell ranges nest in cell ranges).
  double position(int k, double x) const { return (x - domain_.lo[k]) * scale_[k]; }
  // Clamped before the conversion: a coordinate far outside the domain must not overflow int.
  int cell_floor(int k, double x, int fine = 1) const {
    return static_cast<int>(std::clamp(std::floor(fine * position(k, x)), 0.0, static_cast<double>(fine * n_[k] - 1)));
  }
  int cell_ceil(int k, double x, int fine = 1) const {
    return static_cast<int>(std::clamp(std::ceil(fine * position(k, x)), 1.0, static_cast<double>(fine * n_[k])));
  }
  void box_cells(const Box<D>& b, int fine, Ints<D>& lo, Ints<D>& hi) const {
    for (int k = 0; k < D; ++k) {
      lo[k] = cell_floor(k, b.lo[k], fine);
      hi[k] = std::max(lo[k], cell_ceil(k, b.hi[k], fine) - 1);
    }
  }
  void query_cells(const Box<D>& q, int fine, Ints<D>& lo, Ints<D>& hi) const {
    for (int k = 0; k < D; ++k) {
      lo[k] = std::max(0, cell_ceil(k, q.lo[k], fine) - 1);
      hi[k] = cell_floor(k, q.hi[k], fine);
    }
  }
  // g(ids) for the sub-cells of the split cell (index `cell`, position c) inside the sub-cell range lo..hi.
  template <class G>
  void for_subcells(std::size_t cell, const Ints<D>& c, const Ints<D>& lo, const Ints<D>& hi, G&& g) {
    Ints<D> from, to;
    for (int k = 0; k < D; ++k) {
      from[k] = std::max(lo[k] - kFine * c[k], 0);
      to[k] = std::min(hi[k] - kFine * c[k], kFine - 1);
      if (from[k] > to[k]) return;
    }
    Ints<D> j = from;
    for (;;) {
      std::size_t linear = 0;
      for (int k = D - 1; k >= 0; --k) linear = linear * kFine + static_cast<std::size_t>(j[k]);
      g(subcells_[static_cast<std::size_t>(split_[cell]) + linear]);
      int k = 0;
      for (; k < D; ++k) {
        if (++j[k] <= to[k]) break;
        j[k] = from[k];
      }
      if (k == D) return;
    }
  }
  void add_to_subcells(int id, std::size_t cell, const Ints<D>& c, const Ints<D>& lo, const Ints<D>& hi) {
    for_subcells(cell, c, lo, hi, [&](std::vector<int>& ids) { ids.push_back(id); });
  }
  template <class F>
  void visit(const std::vector<int>& ids, F&& f) {
    for (int id : ids) {
      auto& s = stamp_[static_cast<std::size_t>(id)];
      if (s == epoch_) continue;
      s = epoch_;
      f(id);
    }
  }

  template <class F>
  void for_cells(const Ints<D>& lo, const Ints<D>& hi, F&& f) {
    Ints<D> c = lo;
    for (;;) {
      std::size_t linear = 0;
      for (int k = D - 1; k >= 0; --k) linear = linear * static_cast<std::size_t>(n_[k]) + static_cast<std::size_t>(c[k]);
      f(linear, c);
      int k = 0;
      for (; k < D; ++k) {
        if (++c[k] <= hi[k]) break;
        c[k] = lo[k];
      }
      if (k == D) return;
    }
  }
};

}  // namespace trivar
