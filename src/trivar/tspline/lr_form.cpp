#include "trivar/tspline/lr_form.hpp"

#include "trivar/core/error.hpp"
#include "trivar/lr/knot_line_mesh.hpp"

namespace trivar {

std::optional<LRSpline<2>> lr_form(const TSplineSurface& surface, std::string& why) {
  bool rational = false;
  for (const auto& b : surface.basis()) rational = rational || b.coef[3] != 1.0;
  std::vector<LRBSpline<2>> basis(surface.basis().begin(), surface.basis().end());
  if (!rational)
    for (auto& b : basis) b.coef.resize(3);
  auto mesh = knot_line_mesh<2>(basis);
  try {
    return LRSpline<2>(surface.degrees(), 3, rational, std::move(basis), std::move(mesh));
  } catch (const Error& e) {
    why = e.what();
    return std::nullopt;
  }
}

}  // namespace trivar
