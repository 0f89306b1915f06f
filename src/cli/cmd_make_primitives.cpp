// trivar make ball|cylinder|cone|torus [dimensions] [--materials m] -o model.json: V-model primitives, each a
// complex of non-singular cells, optionally with m material fractions blending smoothly across the part.
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/cone.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/torus.hpp"

namespace trivar::cli {

// m fractions that blend linearly between m equally spaced stations of a normalised coordinate rho in [0, 1]
// (the hat functions of degree-1 B-splines): a partition of unity, each material pure at its station.
std::vector<std::string> blend_components(int m, const std::string& rho) {
  if (m == 1) return {"1"};
  std::vector<std::string> c;
  for (int i = 0; i < m; ++i)
    c.push_back("max(0, 1 - abs((" + rho + ") * " + std::to_string(m - 1) + " - " + std::to_string(i) + "))");
  return c;
}

// Materials "M1".."Mm" in the colours of a CMYK+W printer first, then spread over the hue circle.
MaterialTable default_materials(int m) {
  static constexpr std::array<Rgba, 5> kBase{{{0, 174, 239, 255}, {236, 0, 140, 255}, {255, 242, 0, 255},
                                              {35, 31, 32, 255}, {245, 245, 245, 255}}};
  MaterialTable t;
  for (int i = 0; i < m; ++i) {
    Rgba c = i < static_cast<int>(kBase.size()) ? kBase[static_cast<std::size_t>(i)] : Rgba{};
    if (i >= static_cast<int>(kBase.size())) {
      // Hue steps by the golden angle keep neighbours distinguishable for any count.
      const double h = std::fmod(0.618033988749895 * i, 1.0) * 6.0;
      const double x = 1.0 - std::abs(std::fmod(h, 2.0) - 1.0);
      const double rgb[6][3] = {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}};
      const auto& q = rgb[static_cast<int>(h) % 6];
      c = {static_cast<std::uint8_t>(255 * q[0]), static_cast<std::uint8_t>(255 * q[1]), static_cast<std::uint8_t>(255 * q[2]), 255};
    }
    t.add({"M" + std::to_string(i + 1), c});
  }
  return t;
}

void add_material_options(CLI::App* cmd, MaterialArgs& a, const char* axial_meaning) {
  auto* m = cmd->add_option("--materials", a.materials,
                            "Give every cell an attribute \"material\" with this many fractions that blend smoothly")
                ->check(at_least(1));
  cmd->add_option("--blend", a.blend, std::string("Direction of the blend: radial, or axial (") + axial_meaning + ")")
      ->check(CLI::IsMember({"radial", "axial"}))
      ->capture_default_str();
  auto* f = cmd->add_option("--material-field", a.field,
                            "Material fractions as formulas in x, y, z, one per material (instead of --materials)");
  m->excludes(f);
}

void write_model(const std::vector<TensorSpline<3>>& cells, const MaterialArgs& a, const std::string& radial,
                 const std::string& axial, const std::string& out) {
  write_model(std::vector<VCell>(cells.begin(), cells.end()), a, radial, axial, out);
}

void write_model(std::vector<VCell> cells, const MaterialArgs& a, const std::string& radial, const std::string& axial,
                 const std::string& out) {
  VModel m;
  for (auto& c : cells) m.add_cell(std::move(c));
  std::vector<std::string> components = a.field;
  if (a.materials > 0) {
    // clamp: rounding can put boundary points a hair outside [0, 1].
    components = blend_components(a.materials, "min(1, max(0, " + (a.blend == "radial" ? radial : axial) + "))");
  }
  if (!components.empty()) {
    const Attribute material = Attribute::expression(components, Attribute::Space::model);
    for (int i = 0; i < m.num_cells(); ++i) m.cell(i).set_attribute("material", material);
    m.set_materials(default_materials(static_cast<int>(components.size())));
  }
  m.glue();
  io::write_vmodel(out, m);
}

namespace {

std::string num(double x) { return "(" + fmt(x) + ")"; }

struct ModelArgs : MaterialArgs {
  std::string out;
};

void add_primitive_options(CLI::App* cmd, ModelArgs& a, const char* axial_meaning) {
  add_material_options(cmd, a, axial_meaning);
  cmd->add_option("-o,--output", a.out, "Output V-model file (.json)")->required();
}

void add_ball(CLI::App& make) {
  auto* cmd = make.add_subcommand("ball", "Ball of 7 non-singular cells (a core cube and 6 shells out to exact "
                                          "sphere patches)");
  struct Args : ModelArgs {
    BallSpec spec;
    std::vector<double> center{0, 0, 0};
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--radius", a->spec.radius, "Radius")->check(positive())->capture_default_str();
  cmd->add_option("--center", a->center, "Centre x y z")->expected(3);
  cmd->add_option("--core", a->spec.core, "Core cube size as a fraction of the largest that fits, in (0, 1)")
      ->capture_default_str();
  add_primitive_options(cmd, *a, "along z");
  cmd->callback([a] {
    a->spec.center = {a->center[0], a->center[1], a->center[2]};
    const std::string x = "(x - " + num(a->center[0]) + ")", y = "(y - " + num(a->center[1]) + ")",
                      z = "(z - " + num(a->center[2]) + ")";
    const double r = a->spec.radius;
    write_model(make_ball(a->spec), *a, "sqrt(" + x + "^2 + " + y + "^2 + " + z + "^2) / " + num(r),
                "(" + z + " + " + num(r) + ") / " + num(2 * r), a->out);
  });
}

void add_cylinder(CLI::App& make) {
  auto* cmd = make.add_subcommand("cylinder", "Solid cylinder about the z-axis, 5 cells: a core box and 4 ruled "
                                              "cells out to exact arcs");
  struct Args : ModelArgs {
    CylinderSpec spec;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--radius", a->spec.radius, "Radius")->check(positive())->capture_default_str();
  cmd->add_option("--height", a->spec.height, "Height along z")->check(positive())->capture_default_str();
  cmd->add_option("--core", a->spec.core, "Core square size as a fraction of the largest that fits, in (0, 1)")
      ->capture_default_str();
  add_primitive_options(cmd, *a, "along z");
  cmd->callback([a] {
    write_model(make_cylinder(a->spec), *a, "sqrt(x^2 + y^2) / " + num(a->spec.radius), "z / " + num(a->spec.height),
                a->out);
  });
}

void add_cone(CLI::App& make) {
  auto* cmd = make.add_subcommand("cone", "Frustum about the z-axis (top radius > 0: a full apex is singular), "
                                          "5 cells");
  struct Args : ModelArgs {
    ConeSpec spec;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--radii", a->spec.bottom_radius, "Bottom radius")->check(positive())->capture_default_str();
  cmd->add_option("--top-radius", a->spec.top_radius, "Top radius (> 0)")->check(positive())->capture_default_str();
  cmd->add_option("--height", a->spec.height, "Height along z")->check(positive())->capture_default_str();
  cmd->add_option("--core", a->spec.core, "Core square size as a fraction of the largest that fits, in (0, 1)")
      ->capture_default_str();
  add_primitive_options(cmd, *a, "along z");
  cmd->callback([a] {
    const ConeSpec& c = a->spec;
    // Radius at height z: r0 + (r1 - r0) z / h.
    const std::string radius = "(" + num(c.bottom_radius) + " + " + num(c.top_radius - c.bottom_radius) + " * z / " +
                               num(c.height) + ")";
    write_model(make_cone(c), *a, "sqrt(x^2 + y^2) / " + radius, "z / " + num(c.height), a->out);
  });
}

void add_torus(CLI::App& make) {
  auto* cmd = make.add_subcommand("torus", "Ring torus about the z-axis, 5 cells of revolution");
  struct Args : ModelArgs {
    TorusSpec spec;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--major", a->spec.major_radius, "Major radius (tube centre circle)")->check(positive())->capture_default_str();
  cmd->add_option("--minor", a->spec.minor_radius, "Minor radius (tube), less than the major radius")
      ->check(positive())
      ->capture_default_str();
  cmd->add_option("--core", a->spec.core, "Core square size as a fraction of the largest that fits, in (0, 1)")
      ->capture_default_str();
  add_primitive_options(cmd, *a, "around the ring");
  cmd->callback([a] {
    const TorusSpec& t = a->spec;
    const std::string tube = "sqrt((sqrt(x^2 + y^2) - " + num(t.major_radius) + ")^2 + z^2) / " + num(t.minor_radius);
    write_model(make_torus(t), *a, tube, "(atan2(y, x) + pi) / (2 * pi)", a->out);
  });
}

}  // namespace

void add_make_primitives(CLI::App& make) {
  add_ball(make);
  add_cylinder(make);
  add_cone(make);
  add_torus(make);
}

}  // namespace trivar::cli
