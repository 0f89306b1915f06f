#include "trivar/lr/linear_independence.hpp"

#include <algorithm>
#include <numeric>
#include <string>

#include <Eigen/OrderingMethods>
#include <Eigen/QR>
#include <Eigen/SparseCore>
#include <Eigen/SparseQR>

#include "trivar/core/error.hpp"

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

// Blocks with at most this many matrix entries are factorised densely.
constexpr long long kDenseEntries = 4'000'000;

// Rank of the rows (B-splines) of a block given as triplets (row, column, value) of a rows x cols matrix whose
// rows are normalised to max-norm 1; factorises the transpose so that column pivoting ranks the B-splines.
int block_rank(int rows, int cols, const std::vector<Eigen::Triplet<double>>& entries, double tol) {
  if (static_cast<long long>(rows) * cols <= kDenseEntries) {
    Eigen::MatrixXd At = Eigen::MatrixXd::Zero(cols, rows);
    for (const auto& t : entries) At(t.col(), t.row()) = t.value();
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(At);
    qr.setThreshold(tol);
    return static_cast<int>(qr.rank());
  }
  std::vector<Eigen::Triplet<double>> tr;
  tr.reserve(entries.size());
  for (const auto& t : entries) tr.emplace_back(t.col(), t.row(), t.value());
  Eigen::SparseMatrix<double> At(cols, rows);
  At.setFromTriplets(tr.begin(), tr.end());
  At.makeCompressed();
  double max_norm = 0.0;
  for (int c = 0; c < rows; ++c) max_norm = std::max(max_norm, At.col(c).norm());
  Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> qr;
  qr.setPivotThreshold(tol * max_norm);
  qr.compute(At);
  require(qr.info() == Eigen::Success, "exact linear independence test: sparse QR failed");
  return static_cast<int>(qr.rank());
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
                     const Incidence& be, const Incidence& eb, double rank_tolerance) {
  require(rank_tolerance > 0.0 && rank_tolerance < 1.0, "exact linear independence test: tolerance outside (0, 1)");
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
  std::vector<int> seen(elements.size(), -1);
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const auto& rows = blocks[k];
    for (std::size_t r = 0; r < rows.size(); ++r) row_of[static_cast<std::size_t>(rows[r])] = static_cast<int>(r);
    std::vector<Eigen::Triplet<double>> entries;
    std::vector<double> row_max(rows.size(), 0.0);
    int cols = 0;
    std::vector<int> ids;
    for (int b : rows)
      for (int e : be[b]) {
        if (seen[static_cast<std::size_t>(e)] == static_cast<int>(k)) continue;
        seen[static_cast<std::size_t>(e)] = static_cast<int>(k);
        ids.clear();
        for (int c : eb[e])
          if (open[static_cast<std::size_t>(c)]) ids.push_back(c);
        const Eigen::MatrixXd C = extraction_operator<D>(degrees, basis, ids, elements[static_cast<std::size_t>(e)]);
        for (std::size_t i = 0; i < ids.size(); ++i) {
          const int r = row_of[static_cast<std::size_t>(ids[i])];
          for (Eigen::Index j = 0; j < C.cols(); ++j) {
            const double v = C(static_cast<Eigen::Index>(i), j);
            if (v == 0.0) continue;
            entries.emplace_back(r, cols + static_cast<int>(j), v);
            row_max[static_cast<std::size_t>(r)] = std::max(row_max[static_cast<std::size_t>(r)], std::abs(v));
          }
        }
        cols += P;
      }
    // Rows scaled to max-norm 1, so the rank tolerance is relative per B-spline.
    std::vector<Eigen::Triplet<double>> scaled;
    scaled.reserve(entries.size());
    for (const auto& t : entries) scaled.emplace_back(t.row(), t.col(), t.value() / row_max[static_cast<std::size_t>(t.row())]);
    res.rank += block_rank(static_cast<int>(rows.size()), cols, scaled, rank_tolerance);
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
                       double rank_tolerance, int threads) {
  const Incidence be = support_elements<D>(basis, elements, threads);
  return exact_on<D>(degrees, basis, elements, be, be.transposed(static_cast<int>(elements.size())), rank_tolerance);
}

template <int D>
PeelingResult peeling_test(const LRSpline<D>& lr) {
  return peel(polynomial_dimension<D>(lr.degrees()),
              incidence_of(lr.num_elements(), [&](int e) { return lr.element_support(e); }),
              incidence_of(lr.num_basis(), [&](int b) { return lr.basis_elements(b); }));
}

template <int D>
ExactResult exact_test(const LRSpline<D>& lr, double rank_tolerance) {
  return exact_on<D>(lr.degrees(), lr.basis_functions(), lr.elements(),
                     incidence_of(lr.num_basis(), [&](int b) { return lr.basis_elements(b); }),
                     incidence_of(lr.num_elements(), [&](int e) { return lr.element_support(e); }), rank_tolerance);
}

#define TRIVAR_INSTANTIATE(D)                                                                                  \
  template PeelingResult peeling_test<D>(const Ints<D>&, std::span<const LRBSpline<D>>, std::span<const Box<D>>, \
                                         int);                                                                 \
  template ExactResult exact_test<D>(const Ints<D>&, std::span<const LRBSpline<D>>, std::span<const Box<D>>,    \
                                     double, int);
TRIVAR_INSTANTIATE(1)
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

#define TRIVAR_INSTANTIATE(D)                                \
  template PeelingResult peeling_test<D>(const LRSpline<D>&); \
  template ExactResult exact_test<D>(const LRSpline<D>&, double);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
