#pragma once
// The L2 projection behind every project_dirichlet (tensor, multipatch and LR spaces differ only in which
// functions live on a face and how a face is integrated): per component, the functions on the faces that
// constrain it are fixed, and their values solve one boundary mass system.
#include <algorithm>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCholesky>

#include "trivar/core/error.hpp"
#include "trivar/iga/dirichlet.hpp"

namespace trivar {

// face_ids(face): the global functions non-zero on a face (throws for a face the space does not have).
// integrate(face, body): calls body(x, weight, ids, values) at the quadrature points of the face, with the
// global ids and values of the functions that may be non-zero there.
template <int D, class FaceIds, class Integrate>
FixedDofs project_per_component(int num_basis, int components, const std::vector<DirichletCondition<D>>& conditions,
                                FaceIds&& face_ids, Integrate&& integrate) {
  const int N = num_basis;
  FixedDofs out;
  out.fixed.assign(static_cast<std::size_t>(N) * components, 0);
  out.values = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N) * components);
  for (int c = 0; c < components; ++c) {
    // Functions on the faces that constrain component c, numbered locally.
    std::map<int, int> local;
    std::vector<std::pair<const DirichletCondition<D>*, Face>> acting;
    bool nonzero = false;
    for (const auto& cond : conditions) {
      bool applies = cond.components.empty();
      for (int k : cond.components) {
        require(k >= 0 && k < components, "iga: Dirichlet condition on component " + std::to_string(k) + " of a " +
                                              std::to_string(components) + "-component field");
        applies = applies || k == c;
      }
      if (!applies) continue;
      for (const Face& f : cond.faces) {
        for (int id : face_ids(f)) local.emplace(id, 0);
        acting.emplace_back(&cond, f);
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
    for (const auto& [cond, face] : acting)
      integrate(face, [&](const double* x, double w, std::span<const int> ids, std::span<const double> values) {
        std::fill(u.begin(), u.end(), 0.0);
        if (cond->value) cond->value(x, u.data());
        for (std::size_t i = 0; i < ids.size(); ++i) {
          const auto it = local.find(ids[i]);
          if (it == local.end() || values[i] == 0.0) continue;
          rhs[it->second] += w * values[i] * u[static_cast<std::size_t>(c)];
          for (std::size_t j = 0; j < ids.size(); ++j) {
            const auto jt = local.find(ids[j]);
            if (jt != local.end() && values[j] != 0.0)
              trip.emplace_back(it->second, jt->second, w * values[i] * values[j]);
          }
        }
      });
    Eigen::SparseMatrix<double> M(n, n);
    M.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(M);
    require(ldlt.info() == Eigen::Success, "iga: singular boundary mass matrix in the Dirichlet projection");
    const Eigen::VectorXd g = ldlt.solve(rhs);
    for (const auto& [id, l] : local) out.values[c * N + id] = g[l];
  }
  return out;
}

}  // namespace trivar
