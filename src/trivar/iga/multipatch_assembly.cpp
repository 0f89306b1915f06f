#include "trivar/iga/multipatch_assembly.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"

namespace trivar {

namespace {

// The global compressed rows: the scalar pattern of global function G is the union over the patches of the
// renumbered columns of its rows (sorted), repeated for every component block, so an entry is found by a
// binary search in one short list instead of sorting triplets of every entry.
struct GlobalPattern {
  std::vector<std::vector<int>> columns;  // per global function, ascending
};

GlobalPattern global_pattern(const std::vector<SparseMatrix>& local, const std::vector<std::vector<int>>& global,
                             int num_basis, int threads) {
  GlobalPattern pat;
  pat.columns.resize(static_cast<std::size_t>(num_basis));
  for (std::size_t p = 0; p < local.size(); ++p) {
    const std::vector<int>& g = global[p];
    const int n = static_cast<int>(g.size());
    for (int I = 0; I < n; ++I) {
      std::vector<int>& cols = pat.columns[static_cast<std::size_t>(g[static_cast<std::size_t>(I)])];
      for (SparseMatrix::InnerIterator it(local[p], I); it && it.col() < n; ++it)
        cols.push_back(g[static_cast<std::size_t>(it.col())]);
    }
  }
  parallel_for(num_basis, threads, [&](std::ptrdiff_t G) {
    std::vector<int>& cols = pat.columns[static_cast<std::size_t>(G)];
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
  });
  return pat;
}

bool injective(const std::vector<int>& g, int num_basis) {
  std::vector<char> seen(static_cast<std::size_t>(num_basis), 0);
  for (int G : g) {
    if (seen[static_cast<std::size_t>(G)]) return false;
    seen[static_cast<std::size_t>(G)] = 1;
  }
  return true;
}

}  // namespace

template <int D>
SparseMatrix assemble_matrix(const MultipatchSpace<D>& space, const std::function<BilinearForm<D>(int patch)>& form,
                             int threads, const ElementPartition& part) {
  if (space.num_patches() == 1) return assemble_matrix(space.patches[0], form(0), threads, part);
  const int N = space.num_basis;
  std::vector<SparseMatrix> local;
  int m = 0;
  for (int p = 0; p < space.num_patches(); ++p) {
    const BilinearForm<D> f = form(p);
    require(p == 0 || f.components == m, "iga: the forms of a multipatch problem differ in components");
    m = f.components;
    local.push_back(assemble_matrix(space.patches[static_cast<std::size_t>(p)], f, threads, part));
  }
  const GlobalPattern pat = global_pattern(local, space.global, N, threads);
  const auto width = [&](int G) { return static_cast<long>(pat.columns[static_cast<std::size_t>(G)].size()); };
  std::vector<long> outer(static_cast<std::size_t>(N) * m + 1, 0);
  for (int r = 0; r < N * m; ++r) outer[static_cast<std::size_t>(r) + 1] = outer[static_cast<std::size_t>(r)] + m * width(r % N);
  require(outer.back() <= std::numeric_limits<int>::max(),
          "iga: the system has too many non-zeros (" + std::to_string(outer.back()) + ") for 32-bit indices");
  SparseMatrix A(static_cast<Eigen::Index>(N) * m, static_cast<Eigen::Index>(N) * m);
  A.resizeNonZeros(static_cast<Eigen::Index>(outer.back()));
  for (std::size_t r = 0; r < outer.size(); ++r) A.outerIndexPtr()[r] = static_cast<int>(outer[r]);
  parallel_for(N * m, threads, [&](std::ptrdiff_t r) {
    const std::vector<int>& cols = pat.columns[static_cast<std::size_t>(r % N)];
    int* out = A.innerIndexPtr() + outer[static_cast<std::size_t>(r)];
    for (int d = 0; d < m; ++d)
      for (int c : cols) *out++ = d * N + c;
  });
  std::fill(A.valuePtr(), A.valuePtr() + outer.back(), 0.0);
  for (int p = 0; p < space.num_patches(); ++p) {
    const std::vector<int>& g = space.global[static_cast<std::size_t>(p)];
    const int n = static_cast<int>(g.size());
    const SparseMatrix& L = local[static_cast<std::size_t>(p)];
    // Rows of one patch are distinct global rows unless the patch meets itself (a closed ring, a collapsed face).
    parallel_for(L.rows(), injective(g, N) ? threads : 1, [&](std::ptrdiff_t r) {
      const int G = g[static_cast<std::size_t>(r % n)];
      const std::vector<int>& cols = pat.columns[static_cast<std::size_t>(G)];
      double* row = A.valuePtr() + outer[static_cast<std::size_t>((r / n) * N + G)];
      for (SparseMatrix::InnerIterator it(L, r); it; ++it) {
        const int d = static_cast<int>(it.col()) / n, J = g[static_cast<std::size_t>(it.col() % n)];
        row[d * static_cast<long>(cols.size()) + (std::lower_bound(cols.begin(), cols.end(), J) - cols.begin())] +=
            it.value();
      }
    });
    local[static_cast<std::size_t>(p)] = SparseMatrix();
  }
  return A;
}

template <int D>
void add_patch_vector(const MultipatchSpace<D>& space, int patch, const Eigen::VectorXd& b_patch, int components,
                      Eigen::VectorXd& b) {
  const std::vector<int>& g = space.global[static_cast<std::size_t>(patch)];
  const int n = static_cast<int>(g.size());
  for (int c = 0; c < components; ++c)
    for (int i = 0; i < n; ++i)
      b[static_cast<Eigen::Index>(c) * space.num_basis + g[static_cast<std::size_t>(i)]] +=
          b_patch[static_cast<Eigen::Index>(c) * n + i];
}

template <int D>
Eigen::VectorXd assemble_load(const MultipatchSpace<D>& space, int components,
                              const std::function<void(const double* x, double* f)>& f, int threads,
                              const ElementPartition& part) {
  if (space.num_patches() == 1) return assemble_load(space.patches[0], components, f, threads, part);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(space.num_basis) * components);
  for (int p = 0; p < space.num_patches(); ++p)
    add_patch_vector(space, p, assemble_load(space.patches[static_cast<std::size_t>(p)], components, f, threads, part),
                     components, b);
  return b;
}

#define TRIVAR_INSTANTIATE(D)                                                                                      \
  template SparseMatrix assemble_matrix(const MultipatchSpace<D>&, const std::function<BilinearForm<D>(int)>&, int, \
                                        const ElementPartition&);                                                 \
  template Eigen::VectorXd assemble_load(const MultipatchSpace<D>&, int,                                          \
                                         const std::function<void(const double*, double*)>&, int,                  \
                                         const ElementPartition&);                                                 \
  template void add_patch_vector(const MultipatchSpace<D>&, int, const Eigen::VectorXd&, int, Eigen::VectorXd&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
