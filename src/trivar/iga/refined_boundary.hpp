#pragma once
// Boundary data on locally refined spaces (refined_space.hpp), shared by the scalar and vector problems: loads on the element sides along
// Neumann / traction faces, and strong Dirichlet conditions by L2 projection onto the functions clamped at the
// Dirichlet sides (the locally refined counterpart of project_dirichlet in dirichlet.hpp). Dofs are component-major.
#include <vector>

#include <Eigen/Core>

#include "trivar/iga/dirichlet.hpp"
#include "trivar/iga/refined_quadrature.hpp"

namespace trivar {

// Adds the integral of sum_c load_c(x, n) v_c over the element's sides on `faces` to the element vector b
// (b[c * m + l] for the m active functions); load(x, n, out) writes `components` values. p + 2 points per
// direction, as add_face_load.
template <int D, class Load>
void add_side_loads(const RefinedSpace<D>& geometry, const RefinedElement<D>& element, const std::vector<Face>& faces,
                    int components, Load&& load, Eigen::VectorXd& b) {
  const Eigen::Index m = static_cast<Eigen::Index>(element.ids.size());
  std::vector<double> t(static_cast<std::size_t>(components));
  for (const Face& f : faces) {
    if (!on_boundary_face(geometry, element, f)) continue;
    for_each_side_point<D>(geometry, element, f.dir, f.side, geometry.degrees[0] + 2,
                           [&](const Param<D>&, const RefinedPoint<D>& q, double w, const std::array<double, D>& n) {
                             load(q.x.data(), n.data(), t.data());
                             const Eigen::Map<const Eigen::VectorXd> R(q.R.data(), m);
                             for (int c = 0; c < components; ++c)
                               b.segment(c * m, m) += (w * t[static_cast<std::size_t>(c)]) * R;
                           });
  }
}

// Adds the integral of sum_c load_c(x, n) v_c over the trimming boundary inside the element (trimmed spaces;
// nothing otherwise) to the element vector b.
template <int D, class Load>
void add_trimmed_side_loads(const RefinedSpace<D>& geometry, const RefinedElement<D>& element, int components,
                            Load&& load, Eigen::VectorXd& b) {
  if (element.trim_sides.empty()) return;
  const Eigen::Index m = static_cast<Eigen::Index>(element.ids.size());
  std::vector<double> t(static_cast<std::size_t>(components));
  RefinedPoint<D> q;
  for (const TrimmedSidePoint<D>& s : element.trim_sides) {
    refined_point(geometry, element, s.u, q);
    load(q.x.data(), s.normal.data(), t.data());
    const Eigen::Map<const Eigen::VectorXd> R(q.R.data(), m);
    for (int c = 0; c < components; ++c) b.segment(c * m, m) += (s.weight * t[static_cast<std::size_t>(c)]) * R;
  }
}

// Fixes at zero the dofs of functions that are non-zero only on elements outside a trimmed domain (their rows
// would be empty); those already fixed keep their values.
template <int D>
void fix_inactive(const RefinedSpace<D>& geometry, int components, FixedDofs& fixed);

// Same conventions as the tensor-patch project_dirichlet; throws trivar::Error for a face or component out of
// range or a singular boundary mass matrix.
template <int D>
FixedDofs project_dirichlet(const RefinedSpace<D>& geometry, int components, const std::vector<DirichletCondition<D>>& conditions);

}  // namespace trivar
