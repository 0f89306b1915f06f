#include "trivar/iga/trimmed_model_space.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"
#include "trivar/iga/refined_quadrature.hpp"

namespace trivar {

int TrimmedModelSpace::cell_at(const double* x) const {
  const Param<3> u{x[0], x[1], x[2]};
  const int e = space.locate(u);
  if (e < 0) return -1;
  const std::vector<int>& cells = element_cells[static_cast<std::size_t>(e)];
  if (cells.size() == 1) return cells[0];
  for (int c : cells)
    if (model->cell(c).trim()->contains(u)) return c;
  // A point of the element's rule within the chordal tolerance of a face between two cells: the first cell.
  return cells.empty() ? -1 : cells[0];
}

double TrimmedModelSpace::volume() const {
  double v = 0;
  for (const RefinedElement<3>& el : space.elements)
    for_each_element_point<3>(el, space.degree(0) + 1, [&](const Param<3>&, double w) { v += w; });
  return v;
}

TrimmedModelSpace trimmed_model_space(const VModel& model, int degree, int elements, int threads,
                                      const TrimmedSpaceOptions& opts) {
  require(model.num_cells() > 0, "trimmed model space: the model has no cells");
  TrimmedModelSpace m;
  m.model = &model;
  m.box = Box<3>::empty();
  for (int c = 0; c < model.num_cells(); ++c) {
    require(model.cell(c).is_trimmed(), [&] {
      return "trimmed model space: cell " + std::to_string(c) + " is not trimmed (analysis of models mixing trimmed and "
             "untrimmed cells is not supported)";
    });
    const Box<3> b = analysis_box(*model.cell(c).trim());
    m.box.extend(b.lo.data());
    m.box.extend(b.hi.data());
  }
  m.interfaces = trimmed_interfaces(model);
  if (!m.interfaces.non_conforming.empty()) {
    const TrimmedFaceRef f = m.interfaces.non_conforming.front();
    throw Error("trimmed model space: face " + std::to_string(f.face) + " of cell " + std::to_string(f.cell) +
                " is only partly shared with other cells (" + std::to_string(m.interfaces.non_conforming.size()) +
                " such faces; cells must meet on whole faces, as a Boolean's cells do)");
  }
  std::vector<TrimmedPart> parts;
  std::array<bool, 6> side_used{};
  for (int c = 0; c < model.num_cells(); ++c) {
    const TrimmedSolid& solid = *model.cell(c).trim();
    TrimmedPart p{&solid, std::vector<char>(solid.boundary().faces.size(), 0)};
    for (int f : faces_on_box_sides(solid, m.box)) p.skip_faces[static_cast<std::size_t>(f)] = 1;
    for (std::size_t f = 0; f < p.skip_faces.size(); ++f)
      if (m.interfaces.twin[static_cast<std::size_t>(c)][f].cell >= 0) p.skip_faces[f] = 1;
    for (const Face& s : box_sides_with_faces(solid, m.box)) side_used[static_cast<std::size_t>(2 * s.dir + s.side)] = true;
    parts.push_back(std::move(p));
  }
  for (int s = 0; s < 6; ++s)
    if (side_used[static_cast<std::size_t>(s)]) m.sides.push_back({s / 2, s % 2, 0});
  m.space = trimmed_space(parts, m.box, degree, elements, threads, opts, &m.element_cells);
  for (const RefinedElement<3>& el : m.space.elements) {
    m.cut += !el.rule.empty();
    m.outside += el.outside;
  }
  return m;
}

}  // namespace trivar
