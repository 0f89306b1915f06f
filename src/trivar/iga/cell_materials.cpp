#include "trivar/iga/cell_materials.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar {

namespace {

// One property of one cell: a constant or a model-space expression (a copy: expressions are small values).
struct Property {
  double value = 0;
  std::optional<Expression> expression;
  double at(const double* x) const { return expression ? expression->eval(std::span<const double>(x, 3)) : value; }
};

Property property(const VModel& model, int cell, const std::string& name, double fallback) {
  const VCell& c = model.cell(cell);
  if (!c.has_attribute(name)) return {fallback, std::nullopt};
  const Attribute& a = c.attribute(name);
  const std::string where = "cell " + std::to_string(cell) + " attribute '" + name + "'";
  require(a.components() == 1, "elasticity: " + where + " must be a scalar, it has " +
                                   std::to_string(a.components()) + " components");
  if (a.kind() == Attribute::Kind::constant) return {a.values().front(), std::nullopt};
  require(a.kind() == Attribute::Kind::expression && a.space() == Attribute::Space::model,
          "elasticity: " + where + " must be a constant or an expression in x, y, z");
  return {0, a.expressions().front()};
}

}  // namespace

std::function<ElasticMaterial(int patch, const double* x)> cell_materials(const VModel& model,
                                                                          const ElasticMaterial& defaults) {
  std::vector<std::array<Property, 3>> cells;
  for (int c = 0; c < model.num_cells(); ++c) {
    std::array<Property, 3>& p = cells.emplace_back();
    p[0] = property(model, c, "youngs_modulus", defaults.youngs_modulus);
    p[1] = property(model, c, "poisson_ratio", defaults.poisson_ratio);
    p[2] = property(model, c, "density", defaults.density);
    if (!p[0].expression && !p[1].expression && !p[2].expression)
      require(ElasticMaterial{p[0].value, p[1].value, p[2].value}.valid(),
              "elasticity: cell " + std::to_string(c) +
                  " has an invalid material (Young's modulus and density must be positive, Poisson's ratio in "
                  "(-1, 0.5))");
  }
  return [cells = std::move(cells)](int patch, const double* x) {
    const std::array<Property, 3>& p = cells[static_cast<std::size_t>(patch)];
    return ElasticMaterial{p[0].at(x), p[1].at(x), p[2].at(x)};
  };
}

}  // namespace trivar
