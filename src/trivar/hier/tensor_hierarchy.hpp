#pragma once
// TensorHierarchy<D>: the nested tensor-product spline spaces V^0 ⊂ V^1 ⊂ ... of a hierarchical B-spline
// space (Kraft 1997; Giannelli, Juttler, Speleers 2012). Level l has one knot vector per direction, all of the
// same degree and domain, and level l + 1 contains every knot of level l at least as often (nestedness).
// Levels beyond those given are made on demand by dyadic refinement: one knot in the middle of every non-empty
// span.
//
// Cells and functions of a level are addressed per direction by small integers: cell e is the e-th non-empty
// knot span (element) of the level's knot vector, function i its i-th B-spline. The 1-D tables kept per level
// and direction (the cell of each span, the cells of each B-spline's support, parents and children of cells)
// make every query O(1); the local refinement and Bezier matrices are computed on demand from the knots (a few
// p^3 operations), so deep hierarchies cost memory linear in their knots only.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/spline/knot_vector.hpp"

namespace trivar {

// Per level and direction: the knot vector and its cell tables.
struct HierarchyAxis {
  KnotVector knots;
  std::vector<double> breaks;     // distinct knot values: cell e is [breaks[e], breaks[e + 1])
  std::vector<int> span;          // per cell: the knot span index s (t_s = breaks[e] < t_{s+1}); B-splines s-p..s live on it
  std::vector<int> first_cell;    // per B-spline i: first cell of its support
  std::vector<int> end_cell;      // per B-spline i: one past the last cell of its support
  std::vector<int> parent;        // per cell: the cell of the level below containing it (level 0: -1)
  std::vector<int> first_child;   // per cell + 1: cells of the level above inside it are [first_child[e], first_child[e+1])

  int num_cells() const { return static_cast<int>(breaks.size()) - 1; }
  int num_functions() const { return knots.size(); }
  // The cell containing x (half-open cells, the right end closed); x inside the domain.
  int cell_of(double x) const;
};

template <int D>
class TensorHierarchy {
  static_assert(D == 2 || D == 3, "hierarchical splines are surfaces or volumes");

public:
  // Largest number of cells per direction on any level: cell and function indices are packed into 64-bit keys
  // (hier/cell_key.hpp), 32 bits per direction for surfaces, 21 for volumes.
  static constexpr int kMaxIndex = D == 2 ? (1 << 30) : (1 << 20);

  TensorHierarchy() = default;
  // Level 0 only; the others are dyadic.
  explicit TensorHierarchy(const std::array<KnotVector, D>& level0);
  // Explicit levels (at least one). Throws trivar::Error naming level and direction when degrees or domains
  // differ or a level does not contain the knots of the one below.
  explicit TensorHierarchy(const std::vector<std::array<KnotVector, D>>& levels);

  int num_levels() const { return static_cast<int>(levels_.size()); }
  // Adds dyadic levels until there are n. Throws trivar::Error when a level would exceed kMaxIndex cells in a
  // direction or would not fit into memory.
  void ensure_levels(int n);

  const Ints<D>& degrees() const { return degrees_; }
  int degree(int k) const { return degrees_[k]; }
  const HierarchyAxis& axis(int level, int k) const { return (*levels_[static_cast<std::size_t>(level)])[k]; }
  const KnotVector& knots(int level, int k) const { return axis(level, k).knots; }
  Box<D> domain() const;
  Box<D> cell_box(int level, const Ints<D>& cell) const;
  bool dyadic() const { return dyadic_from_ <= 1; }
  // The first level that was made by dyadic refinement (num_levels() when all were given).
  int dyadic_from() const { return dyadic_from_; }

  // Local refinement along direction k: for a cell c of level l >= 1 with parent cell e of level l - 1, the
  // (p+1) x (p+1) row-major matrix R with B^{l-1}_{s-p+a} = sum_b R[a (p+1) + b] B^l_{s'-p+b} on c (s, s' the
  // spans of e and c).
  void local_refinement(int level, int k, int cell, double* R) const;
  // Bezier extraction along direction k of cell c of level l: (p+1) x (p+1) row-major, row a the B-spline
  // s-p+a in the Bernstein basis of the cell.
  void local_bezier(int level, int k, int cell, double* C) const;

private:
  Ints<D> degrees_{};
  // Copies of a hierarchy share its levels (refinement copies the space it refines); a level is never changed
  // once shared: adding a level replaces the one below by a copy with its children table.
  std::vector<std::shared_ptr<std::array<HierarchyAxis, D>>> levels_;
  int dyadic_from_ = 1;

  void add_level(const std::array<KnotVector, D>& kv);
};

extern template class TensorHierarchy<2>;
extern template class TensorHierarchy<3>;

}  // namespace trivar
