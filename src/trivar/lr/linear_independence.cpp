#include "trivar/lr/linear_independence.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <string>

#include <gmpxx.h>

#include "trivar/core/error.hpp"
#include "trivar/lr/exact_rank.hpp"
#include "trivar/spline/knot_refinement.hpp"

namespace trivar {

const char* to_string(Independence s) {
  switch (s) {
    case Independence::independent: return "independent";
    case Independence::not_independent: return "not_independent";
    case Independence::not_tested: return "not_tested";
  }
  return "not_tested";
}

PeelingResult peel(int P, const Incidence& element_basis, const Incidence& basis_elements) {
  const int ne = element_basis.size(), nb = basis_elements.size();
  PeelingResult res;
  std::vector<int> left(static_cast<std::size_t>(ne));  // B-splines on the element not yet proven free
  for (int e = 0; e < ne; ++e) {
    const int n = static_cast<int>(element_basis[e].size());
    require(n >= P, [&] {
      return "linear independence: element " + std::to_string(e) + " lies in the support of " + std::to_string(n) +
             " B-splines, fewer than prod(p_k + 1) = " + std::to_string(P) +
             ", so the collection does not span the polynomials there";
    });
    left[static_cast<std::size_t>(e)] = n;
    if (n > P) ++res.overloaded_elements;
  }
  std::vector<char> alive(static_cast<std::size_t>(nb), 1);
  auto drop = [&](int b, std::vector<int>& queue) {
    alive[static_cast<std::size_t>(b)] = 0;
    for (int e : basis_elements[b])
      if (--left[static_cast<std::size_t>(e)] == 1) queue.push_back(e);
  };
  // A B-spline with one element that is not overloaded has coefficient 0 in every relation.
  std::vector<int> free;
  for (int b = 0; b < nb; ++b) {
    const auto els = basis_elements[b];
    const bool overloaded = std::all_of(els.begin(), els.end(), [&](int e) {
      return static_cast<int>(element_basis[e].size()) > P;
    });
    if (overloaded)
      ++res.overloaded_basis;
    else
      free.push_back(b);
  }
  std::vector<int> queue;
  for (int b : free) drop(b, queue);
  // An element with a single B-spline left forces its coefficient to 0.
  while (!queue.empty()) {
    const int e = queue.back();
    queue.pop_back();
    if (left[static_cast<std::size_t>(e)] != 1) continue;
    for (int b : element_basis[e])
      if (alive[static_cast<std::size_t>(b)]) {
        drop(b, queue);
        break;
      }
  }
  for (int b = 0; b < nb; ++b)
    if (alive[static_cast<std::size_t>(b)]) res.unresolved.push_back(b);
  res.status = res.unresolved.empty() ? Independence::independent : Independence::not_tested;
  return res;
}

namespace {

template <int D>
int polynomial_dimension(const Ints<D>& degrees) {
  int P = 1;
  for (int k = 0; k < D; ++k) {
    require(degrees[static_cast<std::size_t>(k)] >= 0, "linear independence: negative degree");
    P *= degrees[static_cast<std::size_t>(k)] + 1;
  }
  return P;
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

// The rows of one block in the field F: per element of the block (in the order met), its prod (p_k + 1)
// Bernstein columns; row r of B-spline rows[r] holds B's Bernstein coefficients there (the scaling factor gamma,
// a rounded product, is left out: it scales a row and does not change the rank). Columns ascend in each row.
template <class F, int D>
std::vector<SparseRow<F>> block_rows(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis,
                                     std::span<const Box<D>> elements, const std::vector<int>& rows,
                                     const Incidence& be, const Incidence& eb, const std::vector<char>& open,
                                     const std::vector<int>& row_of, std::vector<int>& seen, int stamp,
                                     int& cols) {
  const int P = polynomial_dimension<D>(degrees);
  std::vector<SparseRow<F>> out(rows.size());
  const F zero(0);
  F uni[D][kMaxDegree + 1];
  cols = 0;
  for (int b : rows)
    for (int e : be[b]) {
      if (seen[static_cast<std::size_t>(e)] == stamp) continue;
      seen[static_cast<std::size_t>(e)] = stamp;
      const Box<D>& el = elements[static_cast<std::size_t>(e)];
      for (int c : eb[e]) {
        if (!open[static_cast<std::size_t>(c)]) continue;
        const auto& bs = basis[static_cast<std::size_t>(c)];
        for (int k = 0; k < D; ++k)
          bernstein_coefficients<F>(bs.knots[static_cast<std::size_t>(k)], el.lo[k], el.hi[k], uni[k]);
        auto& row = out[static_cast<std::size_t>(row_of[static_cast<std::size_t>(c)])];
        std::array<int, D> j{};
        for (int col = 0; col < P; ++col) {
          F v = uni[0][j[0]];
          for (int k = 1; k < D; ++k) v = v * uni[k][j[static_cast<std::size_t>(k)]];
          if (!(v == zero)) row.emplace_back(cols + col, std::move(v));
          for (int k = 0; k < D; ++k) {
            if (++j[static_cast<std::size_t>(k)] <= degrees[static_cast<std::size_t>(k)]) break;
            j[static_cast<std::size_t>(k)] = 0;
          }
        }
      }
      cols += P;
    }
  return out;
}

}  // namespace

template <int D>
PeelingResult peeling_test(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis,
                           std::span<const Box<D>> elements, int threads) {
  const Incidence be = support_elements<D>(basis, elements, threads);
  return peel(polynomial_dimension<D>(degrees), be.transposed(static_cast<int>(elements.size())), be);
}

namespace {

// The exact test on given incidence lists (be: elements of each support, eb: its transpose).
template <int D>
ExactResult exact_on(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis, std::span<const Box<D>> elements,
                     const Incidence& be, const Incidence& eb) {
  const int P = polynomial_dimension<D>(degrees);
  const PeelingResult peeled = peel(P, eb, be);
  ExactResult res;
  res.tested = static_cast<int>(peeled.unresolved.size());
  if (peeled.unresolved.empty()) {
    res.status = Independence::independent;
    return res;
  }
  // Blocks: unresolved B-splines linked through shared elements (union-find over the B-splines).
  const int nb = static_cast<int>(basis.size());
  std::vector<char> open(static_cast<std::size_t>(nb), 0);
  for (int b : peeled.unresolved) open[static_cast<std::size_t>(b)] = 1;
  std::vector<int> parent(static_cast<std::size_t>(nb));
  std::iota(parent.begin(), parent.end(), 0);
  for (int e = 0; e < eb.size(); ++e) {
    int first = -1;
    for (int b : eb[e]) {
      if (!open[static_cast<std::size_t>(b)]) continue;
      if (first < 0)
        first = find_root(parent, b);
      else
        parent[static_cast<std::size_t>(find_root(parent, b))] = first;
    }
  }
  std::vector<std::vector<int>> blocks;
  std::vector<int> block_of(static_cast<std::size_t>(nb), -1);
  for (int b : peeled.unresolved) {
    const int r = find_root(parent, b);
    if (block_of[static_cast<std::size_t>(r)] < 0) {
      block_of[static_cast<std::size_t>(r)] = static_cast<int>(blocks.size());
      blocks.emplace_back();
    }
    blocks[static_cast<std::size_t>(block_of[static_cast<std::size_t>(r)])].push_back(b);
  }
  res.blocks = static_cast<int>(blocks.size());
  std::vector<int> row_of(static_cast<std::size_t>(nb), -1);
  std::vector<int> seen(elements.size(), -1);  // element stamps: one per block_rows call
  int stamp = 0;
  for (const auto& rows : blocks) {
    for (std::size_t r = 0; r < rows.size(); ++r) row_of[static_cast<std::size_t>(rows[r])] = static_cast<int>(r);
    int cols = 0, rank = -1;
    try {
      auto m = block_rows<ModP, D>(degrees, basis, elements, rows, be, eb, open, row_of, seen, stamp++, cols);
      rank = echelon_rank(std::move(m), cols);
    } catch (const UnluckyPrime&) {
      rank = -1;  // p divides a knot difference: only rational arithmetic can decide this block
    }
    // Full rank modulo p proves full rank; otherwise the rank over Q decides (exact_rank.hpp).
    if (rank < static_cast<int>(rows.size())) {
      auto m = block_rows<mpq_class, D>(degrees, basis, elements, rows, be, eb, open, row_of, seen, stamp++, cols);
      rank = echelon_rank(std::move(m), cols);
      ++res.rational_blocks;
    }
    res.rank += rank;
  }
  res.status = res.rank == res.tested ? Independence::independent : Independence::not_independent;
  return res;
}

// Incidence lists in CSR form from an LR spline's own per-id lists.
template <class Lists>
Incidence incidence_of(int n, Lists&& list) {
  Incidence out;
  out.offsets.reserve(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i < n; ++i) {
    const auto l = list(i);
    out.ids.insert(out.ids.end(), l.begin(), l.end());
    out.offsets.push_back(static_cast<int>(out.ids.size()));
  }
  return out;
}

}  // namespace

template <int D>
ExactResult exact_test(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis, std::span<const Box<D>> elements,
                       int threads) {
  const Incidence be = support_elements<D>(basis, elements, threads);
  return exact_on<D>(degrees, basis, elements, be, be.transposed(static_cast<int>(elements.size())));
}

template <int D>
PeelingResult peeling_test(const LRSpline<D>& lr) {
  return peel(polynomial_dimension<D>(lr.degrees()),
              incidence_of(lr.num_elements(), [&](int e) { return lr.element_support(e); }),
              incidence_of(lr.num_basis(), [&](int b) { return lr.basis_elements(b); }));
}

template <int D>
ExactResult exact_test(const LRSpline<D>& lr) {
  return exact_on<D>(lr.degrees(), lr.basis_functions(), lr.elements(),
                     incidence_of(lr.num_basis(), [&](int b) { return lr.basis_elements(b); }),
                     incidence_of(lr.num_elements(), [&](int e) { return lr.element_support(e); }));
}

#define TRIVAR_INSTANTIATE(D)                                                                                  \
  template PeelingResult peeling_test<D>(const Ints<D>&, std::span<const LRBSpline<D>>, std::span<const Box<D>>, \
                                         int);                                                                 \
  template ExactResult exact_test<D>(const Ints<D>&, std::span<const LRBSpline<D>>, std::span<const Box<D>>,    \
                                     int);
TRIVAR_INSTANTIATE(1)
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

#define TRIVAR_INSTANTIATE(D)                                \
  template PeelingResult peeling_test<D>(const LRSpline<D>&); \
  template ExactResult exact_test<D>(const LRSpline<D>&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
