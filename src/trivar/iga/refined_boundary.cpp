#include "trivar/iga/refined_boundary.hpp"

#include "trivar/core/error.hpp"
#include "trivar/iga/dirichlet_projection.hpp"

namespace trivar {

template <int D>
FixedDofs project_dirichlet(const RefinedSpace<D>& g, int components,
                            const std::vector<DirichletCondition<D>>& conditions) {
  return project_per_component<D>(
      g.num_basis, components, conditions,
      [&](const Face& f) { return boundary_face_basis(g, f); },
      [&](const Face& f, auto&& body) {
        for (const auto& el : g.elements) {
          if (!on_boundary_face(g, el, f)) continue;
          for_each_side_point<D>(g, el, f.dir, f.side, g.degrees[0] + 2,
                                 [&](const Param<D>&, const RefinedPoint<D>& p, double w, const std::array<double, D>&) {
                                   body(p.x.data(), w, std::span<const int>(el.ids), std::span<const double>(p.R));
                                 });
        }
      });
}

template <int D>
void fix_inactive(const RefinedSpace<D>& g, int components, FixedDofs& fixed) {
  std::vector<char> active(static_cast<std::size_t>(g.num_basis), 0);
  for (const RefinedElement<D>& el : g.elements)
    if (!el.outside)
      for (int i : el.ids) active[static_cast<std::size_t>(i)] = 1;
  for (int c = 0; c < components; ++c)
    for (int i = 0; i < g.num_basis; ++i)
      if (!active[static_cast<std::size_t>(i)]) fixed.fixed[static_cast<std::size_t>(c) * g.num_basis + i] = 1;
}

#define TRIVAR_INSTANTIATE(D)                                                                   \
  template FixedDofs project_dirichlet(const RefinedSpace<D>&, int, \
                                       const std::vector<DirichletCondition<D>>&); \
  template void fix_inactive(const RefinedSpace<D>&, int, FixedDofs&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
