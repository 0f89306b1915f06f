#include "trivar/iga/dirichlet.hpp"

#include "trivar/core/error.hpp"
#include "trivar/iga/boundary_integral.hpp"
#include "trivar/iga/dirichlet_projection.hpp"

namespace trivar {

int FixedDofs::num_free() const {
  int n = 0;
  for (char f : fixed) n += f ? 0 : 1;
  return n;
}

std::vector<int> FixedDofs::free_dofs() const {
  std::vector<int> ids;
  for (std::size_t i = 0; i < fixed.size(); ++i)
    if (!fixed[i]) ids.push_back(static_cast<int>(i));
  return ids;
}

template <int D>
FixedDofs project_dirichlet(const MultipatchSpace<D>& space, int components,
                            const std::vector<DirichletCondition<D>>& conditions) {
  std::vector<int> ids;
  return project_per_component<D>(
      space.num_basis, components, conditions,
      [&](const Face& f) {
        require(f.dir >= 0 && f.dir < D && (f.side == 0 || f.side == 1) && f.patch >= 0 &&
                    f.patch < space.num_patches(),
                "iga: no such face of the patch");
        const std::vector<int>& g = space.global[static_cast<std::size_t>(f.patch)];
        std::vector<int> on_face;
        for (int id : face_basis(space.patches[static_cast<std::size_t>(f.patch)], f))
          on_face.push_back(g[static_cast<std::size_t>(id)]);
        return on_face;
      },
      [&](const Face& f, auto&& body) {
        const TensorSpace<D>& patch = space.patches[static_cast<std::size_t>(f.patch)];
        const std::vector<int>& g = space.global[static_cast<std::size_t>(f.patch)];
        integrate_face<D>(patch, f, patch.geometry.degree(0) + 2, [&](const FacePoint<D>& p) {
          ids.clear();
          for (int id : p.ids) ids.push_back(g[static_cast<std::size_t>(id)]);
          body(p.x.data(), p.weight, std::span<const int>(ids), p.values);
        });
      });
}

void apply_dirichlet(SparseMatrix& A, Eigen::VectorXd& b, const FixedDofs& fixed) {
  b -= A * fixed.values;
  for (Eigen::Index r = 0; r < A.outerSize(); ++r) {
    const bool row_fixed = fixed.fixed[static_cast<std::size_t>(r)];
    for (SparseMatrix::InnerIterator it(A, r); it; ++it) {
      if (row_fixed || fixed.fixed[static_cast<std::size_t>(it.col())]) it.valueRef() = it.col() == r && row_fixed ? 1.0 : 0.0;
    }
    if (row_fixed) b[r] = fixed.values[r];
  }
}

SparseMatrix free_block(const SparseMatrix& A, const FixedDofs& fixed) {
  std::vector<int> index(fixed.fixed.size(), -1);
  int n = 0;
  for (std::size_t i = 0; i < fixed.fixed.size(); ++i)
    if (!fixed.fixed[i]) index[i] = n++;
  std::vector<Eigen::Triplet<double>> trip;
  for (Eigen::Index r = 0; r < A.outerSize(); ++r) {
    if (index[static_cast<std::size_t>(r)] < 0) continue;
    for (SparseMatrix::InnerIterator it(A, r); it; ++it)
      if (index[static_cast<std::size_t>(it.col())] >= 0)
        trip.emplace_back(index[static_cast<std::size_t>(r)], index[static_cast<std::size_t>(it.col())], it.value());
  }
  SparseMatrix B(n, n);
  B.setFromTriplets(trip.begin(), trip.end());
  return B;
}

template <int D>
FixedDofs project_dirichlet(const TensorSpace<D>& space, int components,
                            const std::vector<DirichletCondition<D>>& conditions) {
  return project_dirichlet(single_patch_space(space), components, conditions);
}

#define TRIVAR_INSTANTIATE(D)                                                                                \
  template FixedDofs project_dirichlet(const MultipatchSpace<D>&, int, const std::vector<DirichletCondition<D>>&); \
  template FixedDofs project_dirichlet(const TensorSpace<D>&, int, const std::vector<DirichletCondition<D>>&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
