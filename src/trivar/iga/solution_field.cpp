#include "trivar/iga/solution_field.hpp"

#include "trivar/iga/multipatch_space.hpp"

namespace trivar {

template <int D>
TensorSpline<D> solution_field(const TensorSpace<D>& space, const Eigen::VectorXd& coefs, int components) {
  const TensorSpline<D>& g = space.geometry;
  const int N = g.num_coefs(), stride = components + (g.is_rational() ? 1 : 0);
  std::vector<double> c(static_cast<std::size_t>(N) * stride);
  for (int I = 0; I < N; ++I) {
    const double w = g.weight(I);
    for (int k = 0; k < components; ++k)
      c[static_cast<std::size_t>(I * stride + k)] = w * coefs[static_cast<Eigen::Index>(k) * N + I];
    if (g.is_rational()) c[static_cast<std::size_t>(I * stride + components)] = w;
  }
  return TensorSpline<D>(g.knot_vectors(), components, g.is_rational(), std::move(c));
}

template <int D>
std::vector<TensorSpline<D>> solution_fields(const MultipatchSpace<D>& space, const Eigen::VectorXd& coefs,
                                             int components) {
  std::vector<TensorSpline<D>> fields;
  for (int p = 0; p < space.num_patches(); ++p)
    fields.push_back(solution_field(space.patches[static_cast<std::size_t>(p)],
                                    patch_coefs(space, p, coefs, components), components));
  return fields;
}

template TensorSpline<2> solution_field(const TensorSpace<2>&, const Eigen::VectorXd&, int);
template TensorSpline<3> solution_field(const TensorSpace<3>&, const Eigen::VectorXd&, int);
template std::vector<TensorSpline<2>> solution_fields(const MultipatchSpace<2>&, const Eigen::VectorXd&, int);
template std::vector<TensorSpline<3>> solution_fields(const MultipatchSpace<3>&, const Eigen::VectorXd&, int);

}  // namespace trivar
