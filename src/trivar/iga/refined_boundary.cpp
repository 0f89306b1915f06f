#include "trivar/iga/refined_boundary.hpp"

#include "trivar/core/error.hpp"
#include "trivar/iga/dirichlet_projection.hpp"

namespace trivar {

template <int D>
FixedDofs project_dirichlet(const RefinedSpace<D>& g, int components,
                            const std::vector<DirichletCondition<D>>& conditions) {
  return project_per_component<D>(
      g.num_basis, components, conditions,
      [&](const Face& f) {
        require(f.dir >= 0 && f.dir < D && (f.side == 0 || f.side == 1) && f.patch == 0,
                "iga: no such face of the locally refined domain");
        return g.face_basis[static_cast<std::size_t>(2 * f.dir + f.side)];
      },
      [&](const Face& f, auto&& body) {
        for (const auto& el : g.elements) {
          if (!on_domain_face(g.domain, el.box, f)) continue;
          for_each_side_point<D>(g, el, f.dir, f.side, g.degrees[0] + 2,
                                 [&](const Param<D>&, const RefinedPoint<D>& p, double w, const std::array<double, D>&) {
                                   body(p.x.data(), w, std::span<const int>(el.ids), std::span<const double>(p.R));
                                 });
        }
      });
}

#define TRIVAR_INSTANTIATE(D)                                                                   \
  template FixedDofs project_dirichlet(const RefinedSpace<D>&, int, \
                                       const std::vector<DirichletCondition<D>>&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
