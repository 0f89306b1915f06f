// trivar make box|revolve ... -o FILE: models built from a few numbers.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cli.hpp"
#include "lr_cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/model/block.hpp"
#include "trivar/model/revolve.hpp"
#include "trivar/spline/knot_insertion.hpp"

namespace trivar::cli {

namespace {

// Per-direction values: one value applies to every direction.
template <class T, int D>
std::array<T, D> per_direction(const std::vector<T>& v, const char* option) {
  require(v.size() == 1 || static_cast<int>(v.size()) == D, std::string("make box: ") + option + " takes 1 or " +
                                                                 std::to_string(D) + " values, got " +
                                                                 std::to_string(v.size()));
  std::array<T, D> r;
  for (int k = 0; k < D; ++k) r[k] = v[v.size() == 1 ? 0 : k];
  return r;
}

template <int D>
AnySpline box(const std::vector<int>& degrees, const std::vector<int>& elements, const std::vector<double>& size) {
  const auto p = per_direction<int, D>(degrees, "--degree");
  const auto n = per_direction<int, D>(elements, "--elements");
  // Control points (D coordinates each) and knots, in double so huge counts cannot overflow; the spline is
  // built once more while it is written, so twice that.
  double points = 1, knots = 0;
  std::string degree_list, counts;
  for (int k = 0; k < D; ++k) {
    points *= static_cast<double>(n[k]) + p[k];
    knots += static_cast<double>(n[k]) + 2.0 * p[k] + 1;
    degree_list += " " + std::to_string(p[k]);
    counts += " " + std::to_string(n[k]);
  }
  const std::string request = "make box: --degree" + degree_list + " --elements" + counts;
  require_memory(2 * (points * D + knots) * sizeof(double),
                 request + " (" + fmt(points) + " control points)");
  return make_block<D>(p, n, per_direction<double, D>(size, "--size"));
}

void add_box(CLI::App& make) {
  auto* cmd = make.add_subcommand("box", "Block [0,X] x [0,Y] x [0,Z] with the identity parametrisation");
  struct Args : MaterialArgs {
    std::vector<int> degrees{1}, elements{1};
    std::vector<double> size{1.0};
    bool model = false, lr = false;
    std::string out;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--degree", a->degrees, "Degree per direction (one value: all directions)")
      ->expected(1, 3)
      ->check(at_least(1))
      ->capture_default_str();
  cmd->add_option("--elements", a->elements, "Elements per direction; the number of values sets the kind: "
                                              "2 a surface (in the plane z = 0), 3 a volume")
      ->expected(1, 3)
      ->check(at_least(1))
      ->capture_default_str();
  cmd->add_option("--size", a->size, "Edge lengths (one value: all directions)")
      ->expected(1, 3)
      ->check(positive())
      ->capture_default_str();
  cmd->add_flag("--model", a->model, "Write a one-cell V-model (.json) instead of a spline file");
  cmd->add_flag("--lr", a->lr, "Write the box as an LR spline (.lr, .json, .g2, .vtu), converted exactly");
  add_material_options(cmd, *a, "along z");
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2), or V-model with --model")->required();
  cmd->callback([a] {
    require(!(a->lr && (a->model || a->materials > 0 || !a->field.empty())),
            "make box: --lr does not combine with --model, --materials or --material-field");
    if (a->model || a->materials > 0 || !a->field.empty()) {
      require(a->model, "make box: --materials and --material-field need --model");
      require(std::max({a->degrees.size(), a->elements.size(), a->size.size()}) != 2,
              "make box: a V-model is a volume; give 1 or 3 values per option");
      const auto size = per_direction<double, 3>(a->size, "--size");
      // Normalised radial coordinate: distance from the box centre over the half diagonal.
      const std::string half = "(" + fmt(std::sqrt(size[0] * size[0] + size[1] * size[1] + size[2] * size[2]) / 2) + ")";
      const std::string radial = "sqrt((x - " + fmt(size[0] / 2) + ")^2 + (y - " + fmt(size[1] / 2) + ")^2 + (z - " +
                                 fmt(size[2] / 2) + ")^2) / " + half;
      const SplineVolume cell = std::get<TensorSpline<3>>(box<3>(a->degrees, a->elements, a->size));
      write_model({cell}, *a, radial, "z / (" + fmt(size[2]) + ")", a->out);
      return;
    }
    // The direction count is the longest of the per-direction lists; a single list of one value is a volume.
    std::size_t n = std::max({a->degrees.size(), a->elements.size(), a->size.size()});
    if (n == 1) n = 3;
    const AnySpline s = n == 2 ? box<2>(a->degrees, a->elements, a->size) : box<3>(a->degrees, a->elements, a->size);
    if (a->lr) {
      write_lr_file(a->out, {n == 2 ? AnyLRSpline(LRSpline<2>(std::get<TensorSpline<2>>(s)))
                                    : AnyLRSpline(LRSpline<3>(std::get<TensorSpline<3>>(s)))},
                    "make box");
      return;
    }
    io::write_spline_file(a->out, {s});
  });
}

void add_revolve(CLI::App& make) {
  auto* cmd = make.add_subcommand("revolve", "Exact NURBS volume of revolution of a rectangle about the z-axis "
                                             "(u along the axis, v radial, w angular, det J > 0), or of a "
                                             "--profile curve or surface about any axis");
  struct Args {
    std::vector<double> radii{1.0, 2.0};
    double height = 1.0, angle = 360.0;
    std::vector<int> degrees{2}, elements{1};
    std::string profile, out;
    std::vector<double> axis_point{0, 0, 0}, axis_dir{0, 0, 1};
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--profile", a->profile, "File with a curve or surface to revolve instead of the rectangle "
                                           "(then --radii, --height, --degree and --elements do not apply)");
  cmd->add_option("--axis-point", a->axis_point, "A point of the axis (with --profile)")->expected(3);
  cmd->add_option("--axis-dir", a->axis_dir, "Direction of the axis (with --profile)")->expected(3);
  cmd->add_option("--radii", a->radii, "Inner and outer radius r0 < r1 (r0 = 0 touches the axis: singular volume)")
      ->expected(2)
      ->capture_default_str();
  cmd->add_option("--height", a->height, "Height along z")->check(positive())->capture_default_str();
  cmd->add_option("--angle", a->angle, "Sweep angle in degrees, in (0, 360]")->capture_default_str();
  cmd->add_option("--degree", a->degrees, "Degree of u (axial) and v (radial); one value: both. Angular: always 2")
      ->expected(1, 2)
      ->check(at_least(1))
      ->capture_default_str();
  cmd->add_option("--elements", a->elements,
                  "Elements of u (axial), v (radial) and w (angular, per segment); one value applies to u and v. "
                  "The angle is split into one rational segment per started 90 degrees")
      ->expected(1, 3)
      ->check(at_least(1))
      ->capture_default_str();
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2)")->required();
  cmd->callback([a] {
    require(a->angle > 0 && a->angle <= 360, "make revolve: --angle must be in (0, 360] degrees, got " + fmt(a->angle));
    // angle / 180 * pi keeps 360 degrees exactly 2 pi.
    const double radians = a->angle / 180.0 * std::numbers::pi;
    if (!a->profile.empty()) {
      const AnySpline p = read_single(a->profile, "make revolve");
      const Eigen::Vector3d point(a->axis_point[0], a->axis_point[1], a->axis_point[2]);
      const Eigen::Vector3d dir(a->axis_dir[0], a->axis_dir[1], a->axis_dir[2]);
      require(parametric_dimension(p) <= 2, "make revolve: --profile " + a->profile + " must hold a curve or surface");
      io::write_spline_file(a->out, {parametric_dimension(p) == 1
                                         ? AnySpline(revolve<2>(std::get<TensorSpline<1>>(p), point, dir, radians))
                                         : AnySpline(revolve<3>(std::get<TensorSpline<2>>(p), point, dir, radians))});
      return;
    }
    require(a->radii[0] < a->radii[1],
            "make revolve: --radii must satisfy r0 < r1, got " + fmt(a->radii[0]) + " " + fmt(a->radii[1]));
    const Ints<2> degrees{a->degrees[0], a->degrees.back()};
    const Ints<2> elements{a->elements[0], a->elements[a->elements.size() > 1 ? 1 : 0]};
    const int angular = a->elements.size() > 2 ? a->elements[2] : 1;
    const TensorSpline<2> profile = make_rectangle_profile({0.0, a->height}, {a->radii[0], a->radii[1]}, degrees, elements);
    TensorSpline<3> vol = revolve<3>(profile, {0, 0, 0}, {0, 0, 1}, radians);
    if (angular > 1) vol = refine_uniform(vol, Ints<3>{1, 1, angular});
    io::write_spline_file(a->out, {AnySpline(std::move(vol))});
  });
}

}  // namespace

void add_make_command(CLI::App& app, Context&) {
  auto* make = app.add_subcommand("make", "Build a model: make box|revolve|extrude|ruled|loft|coons|sweep|morph|ball|cylinder|cone|torus|vmodel ...");
  make->require_subcommand(1);
  add_box(*make);
  add_revolve(*make);
  add_make_constructors(*make);
  add_make_primitives(*make);
  add_make_vmodel(*make);
}

}  // namespace trivar::cli
