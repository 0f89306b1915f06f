#include "trivar/iga/refined_field.hpp"

namespace trivar {

template <int D>
void refined_field_value(const RefinedSpace<D>& space, const Eigen::VectorXd& coefs, int components,
                         const Param<D>& u, double* out) {
  refined_field_value(space, space.locate(u), coefs, components, u, out);
}

template <int D>
void refined_field_value(const RefinedSpace<D>& space, int element, const Eigen::VectorXd& coefs, int components,
                         const Param<D>& u, double* out) {
  const RefinedElement<D>& el = space.elements[static_cast<std::size_t>(element)];
  RefinedPoint<D> p;
  refined_point(space, el, u, p);
  for (int c = 0; c < components; ++c) {
    out[c] = 0;
    for (std::size_t l = 0; l < el.ids.size(); ++l) out[c] += coefs[c * space.num_basis + el.ids[l]] * p.R[l];
  }
}

template void refined_field_value(const RefinedSpace<2>&, const Eigen::VectorXd&, int, const Param<2>&, double*);
template void refined_field_value(const RefinedSpace<3>&, const Eigen::VectorXd&, int, const Param<3>&, double*);
template void refined_field_value(const RefinedSpace<2>&, int, const Eigen::VectorXd&, int, const Param<2>&, double*);
template void refined_field_value(const RefinedSpace<3>&, int, const Eigen::VectorXd&, int, const Param<3>&, double*);

}  // namespace trivar
