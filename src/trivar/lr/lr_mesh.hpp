#pragma once
// ElementGrid<D>: a uniform bucket grid over a domain holding box ids (an LR mesh's elements), for finding
// the elements a mesh rectangle touches while a refinement adds elements. A box is listed in every cell its
// closed extent meets on the half-open cell partition, so a query with a closed box reports a superset of the
// boxes meeting it (the caller tests the boxes exactly). Boxes that shrink may stay listed in cells they left:
// harmless for a superset.
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
    Ints<D> lo, hi;
    for (int k = 0; k < D; ++k) {
      lo[k] = cell_floor(k, b.lo[k]);
      hi[k] = std::max(lo[k], cell_ceil(k, b.hi[k]) - 1);
    }
    for_cells(lo, hi, [&](std::vector<int>& c) { c.push_back(id); });
    if (static_cast<std::size_t>(id) >= stamp_.size()) stamp_.resize(static_cast<std::size_t>(id) + 1, 0);
  }

  // Calls f(id) once for every listed box that may meet the closed box q.
  template <class F>
  void query(const Box<D>& q, F&& f) {
    ++epoch_;
    Ints<D> lo, hi;
    for (int k = 0; k < D; ++k) {
      lo[k] = std::max(0, cell_ceil(k, q.lo[k]) - 1);
      hi[k] = cell_floor(k, q.hi[k]);
    }
    for_cells(lo, hi, [&](std::vector<int>& c) {
      for (int id : c) {
        auto& s = stamp_[static_cast<std::size_t>(id)];
        if (s == epoch_) continue;
        s = epoch_;
        f(id);
      }
    });
  }

private:
  Box<D> domain_;
  Ints<D> n_{};
  Param<D> scale_{};
  std::vector<std::vector<int>> cells_;
  std::vector<int> stamp_;
  int epoch_ = 0;

  // Monotone in x, so the cell ranges of two closed intervals that meet always meet.
  double position(int k, double x) const { return (x - domain_.lo[k]) * scale_[k]; }
  // Clamped before the conversion: a coordinate far outside the domain must not overflow int.
  int cell_floor(int k, double x) const {
    return static_cast<int>(std::clamp(std::floor(position(k, x)), 0.0, static_cast<double>(n_[k] - 1)));
  }
  int cell_ceil(int k, double x) const {
    return static_cast<int>(std::clamp(std::ceil(position(k, x)), 1.0, static_cast<double>(n_[k])));
  }

  template <class F>
  void for_cells(const Ints<D>& lo, const Ints<D>& hi, F&& f) {
    Ints<D> c = lo;
    for (;;) {
      std::size_t linear = 0;
      for (int k = D - 1; k >= 0; --k) linear = linear * static_cast<std::size_t>(n_[k]) + static_cast<std::size_t>(c[k]);
      f(cells_[linear]);
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
