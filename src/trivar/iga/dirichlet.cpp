#include "trivar/iga/dirichlet.hpp"

#include <map>

#include <Eigen/SparseCholesky>

#include "trivar/core/error.hpp"
#include "trivar/iga/boundary_integral.hpp"

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
  const int N = space.num_basis;
  FixedDofs out;
  out.fixed.assign(static_cast<std::size_t>(N) * components, 0);
  out.values = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N) * components);
  for (int c = 0; c < components; ++c) {
    // Boundary basis functions of the faces that constrain component c, numbered locally.
    std::map<int, int> local;
    std::vector<const DirichletCondition<D>*> acting;
    std::vector<Face> faces;
    bool nonzero = false;
    for (const auto& cond : conditions) {
      bool applies = cond.components.empty();
      for (int k : cond.components) {
        require(k >= 0 && k < components, "iga: Dirichlet condition on component " + std::to_string(k) +
                                              " of a " + std::to_string(components) + "-component field");
        applies = applies || k == c;
      }
      if (!applies) continue;
      for (const Face& f : cond.faces) {
        require(f.dir >= 0 && f.dir < D && (f.side == 0 || f.side == 1) && f.patch >= 0 &&
                    f.patch < space.num_patches(),
                "iga: no such face of the patch");
        const std::vector<int>& g = space.global[static_cast<std::size_t>(f.patch)];
        for (int id : face_basis(space.patches[static_cast<std::size_t>(f.patch)], f))
          local.emplace(g[static_cast<std::size_t>(id)], 0);
        faces.push_back(f);
        acting.push_back(&cond);
      }
      nonzero = nonzero || static_cast<bool>(cond.value);
    }
    int n = 0;
    for (auto& [id, l] : local) {
      l = n++;
      out.fixed[static_cast<std::size_t>(c * N + id)] = 1;
    }
    if (!nonzero || n == 0) continue;
    std::vector<Eigen::Triplet<double>> trip;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    std::vector<double> u(static_cast<std::size_t>(components));
    for (std::size_t fi = 0; fi < faces.size(); ++fi) {
      const DirichletCondition<D>& cond = *acting[fi];
      const TensorSpace<D>& patch = space.patches[static_cast<std::size_t>(faces[fi].patch)];
      const std::vector<int>& g = space.global[static_cast<std::size_t>(faces[fi].patch)];
      integrate_face<D>(patch, faces[fi], patch.geometry.degree(0) + 2, [&](const FacePoint<D>& p) {
        std::fill(u.begin(), u.end(), 0.0);
        if (cond.value) cond.value(p.x.data(), u.data());
        for (std::size_t i = 0; i < p.ids.size(); ++i) {
          const auto it = local.find(g[static_cast<std::size_t>(p.ids[i])]);
          if (it == local.end() || p.values[i] == 0.0) continue;
          rhs[it->second] += p.weight * p.values[i] * u[static_cast<std::size_t>(c)];
          for (std::size_t j = 0; j < p.ids.size(); ++j) {
            const auto jt = local.find(g[static_cast<std::size_t>(p.ids[j])]);
            if (jt != local.end() && p.values[j] != 0.0)
              trip.emplace_back(it->second, jt->second, p.weight * p.values[i] * p.values[j]);
          }
        }
      });
    }
    Eigen::SparseMatrix<double> M(n, n);
    M.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(M);
    require(ldlt.info() == Eigen::Success, "iga: singular boundary mass matrix in the Dirichlet projection");
    const Eigen::VectorXd g = ldlt.solve(rhs);
    for (const auto& [id, l] : local) out.values[c * N + id] = g[l];
  }
  return out;
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
