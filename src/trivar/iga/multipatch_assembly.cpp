#include "trivar/iga/multipatch_assembly.hpp"

#include <vector>

#include "trivar/core/error.hpp"

namespace trivar {

template <int D>
SparseMatrix assemble_matrix(const MultipatchSpace<D>& space, const std::function<BilinearForm<D>(int patch)>& form,
                             int threads) {
  if (space.num_patches() == 1) return assemble_matrix(space.patches[0], form(0), threads);
  const int N = space.num_basis;
  std::vector<Eigen::Triplet<double, int>> entries;
  int components = 0;
  for (int p = 0; p < space.num_patches(); ++p) {
    const BilinearForm<D> f = form(p);
    require(p == 0 || f.components == components, "iga: the forms of a multipatch problem differ in components");
    components = f.components;
    const SparseMatrix A = assemble_matrix(space.patches[static_cast<std::size_t>(p)], f, threads);
    const std::vector<int>& g = space.global[static_cast<std::size_t>(p)];
    const int n = static_cast<int>(g.size());
    auto global = [&](int local) { return (local / n) * N + g[static_cast<std::size_t>(local % n)]; };
    entries.reserve(entries.size() + static_cast<std::size_t>(A.nonZeros()));
    for (int r = 0; r < A.outerSize(); ++r)
      for (SparseMatrix::InnerIterator it(A, r); it; ++it)
        entries.emplace_back(global(r), global(static_cast<int>(it.col())), it.value());
  }
  SparseMatrix A(static_cast<Eigen::Index>(N) * components, static_cast<Eigen::Index>(N) * components);
  A.setFromTriplets(entries.begin(), entries.end());
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
                              const std::function<void(const double* x, double* f)>& f, int threads) {
  if (space.num_patches() == 1) return assemble_load(space.patches[0], components, f, threads);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(space.num_basis) * components);
  for (int p = 0; p < space.num_patches(); ++p)
    add_patch_vector(space, p, assemble_load(space.patches[static_cast<std::size_t>(p)], components, f, threads),
                     components, b);
  return b;
}

#define TRIVAR_INSTANTIATE(D)                                                                                      \
  template SparseMatrix assemble_matrix(const MultipatchSpace<D>&, const std::function<BilinearForm<D>(int)>&, int); \
  template Eigen::VectorXd assemble_load(const MultipatchSpace<D>&, int,                                          \
                                         const std::function<void(const double*, double*)>&, int);                 \
  template void add_patch_vector(const MultipatchSpace<D>&, int, const Eigen::VectorXd&, int, Eigen::VectorXd&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
