#include "trivar/io/vmodel_vtk.hpp"

#include <algorithm>
#include <limits>
#include <map>

#include "trivar/core/error.hpp"

namespace trivar::io {

void write_vmodel_vtu(const std::string& path, const VModel& model, const VtkOptions& opts) {
  require(model.num_cells() > 0, path + ": nothing to write (the model has no cells)");
  std::vector<AnySpline> pieces;
  for (const VCell& c : model.cells()) pieces.emplace_back(c.geometry());

  std::map<std::string, int> components;
  for (const VCell& c : model.cells())
    for (const auto& [name, a] : c.attributes()) components[name] = std::max(components[name], a.components());

  std::vector<VtkPointField> fields;
  fields.push_back({"vcell", 1, [](int piece, std::span<const double>, std::span<double> out) {
                      out[0] = piece;
                    }});
  for (const auto& [name, n] : components)
    fields.push_back({name, n, [&model, name](int piece, std::span<const double> u, std::span<double> out) {
                        std::fill(out.begin(), out.end(), std::numeric_limits<double>::quiet_NaN());
                        const VCell& c = model.cell(piece);
                        if (c.has_attribute(name)) c.eval_attribute(name, {u[0], u[1], u[2]}, out.data());
                      }});
  write_vtu(path, pieces, opts, fields);
}

}  // namespace trivar::io
