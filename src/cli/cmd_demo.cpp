// trivar demo [--out DIR] [--force] [--allow-open]: the library end to end. Part 1 builds an exact NURBS volume of revolution, refines
// it, certifies its Jacobian, verifies its volume and radii against closed forms and writes files for
// ParaView. Part 2 is the additive-manufacturing job: a graded 7-cell ball whose two materials blend from the
// centre to the surface is built, certified, sliced into printer bitmaps and exported as 3MF and STL.
#include <cmath>
#include <limits>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/stl_writer.hpp"
#include "trivar/io/threemf_writer.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/io/vtk_writer.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/block.hpp"
#include "trivar/model/model_tessellation.hpp"
#include "trivar/model/revolve.hpp"
#include "trivar/spline/derivative_index.hpp"
#include "trivar/spline/jacobian.hpp"
#include "trivar/spline/knot_insertion.hpp"
#include "trivar/spline/measure.hpp"

namespace trivar::cli {

namespace {

constexpr double kPi = std::numbers::pi;

// det[S_u, S_v, S_w] from the three first derivatives stored one after the other.
double jacobian_determinant(const double* a) {
  return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) + a[2] * (a[3] * a[7] - a[4] * a[6]);
}

// Largest |distance to the z-axis - (r0 + v (r1 - r0))| on a grid of samples: zero for an exact model.
double max_radius_error(const SplineVolume& s, double r0, double r1, int samples, int threads) {
  std::array<std::vector<double>, 3> grid;
  for (auto& g : grid)
    for (int i = 0; i < samples; ++i) g.push_back(static_cast<double>(i) / (samples - 1));
  std::vector<double> x(static_cast<std::size_t>(samples) * samples * samples * 3);
  s.eval_grid(grid, x, threads);
  double worst = 0;
  for (std::size_t p = 0; p < x.size() / 3; ++p) {
    const double v = grid[1][(p / samples) % samples];
    worst = std::max(worst, std::abs(std::hypot(x[3 * p], x[3 * p + 1]) - (r0 + v * (r1 - r0))));
  }
  return worst;
}

// Part 2: a graded ball of radius 5 mm, material M1 at the centre blending linearly into M2 at the surface.
// `out` stages the files; `dir` is where they end up, as the messages name them.
void graded_ball_demo(OutputFolder& out, const std::filesystem::path& dir, bool allow_open, Context& ctx) {
  const double radius = 5.0;
  VModel ball;
  for (const auto& cell : make_ball({.radius = radius})) ball.add_cell(VCell(cell));
  const Attribute material = Attribute::expression(
      blend_components(2, "min(1, sqrt(x^2 + y^2 + z^2) / " + fmt(radius) + ")"), Attribute::Space::model);
  for (int i = 0; i < ball.num_cells(); ++i) ball.cell(i).set_attribute("material", material);
  ball.set_materials(default_materials(2));
  ball.glue();
  double min_det = std::numeric_limits<double>::infinity();
  bool valid = true;
  for (const VCell& c : ball.cells()) {
    const JacobianReport<3> r = check_jacobian(c.geometry());
    valid = valid && r.valid;
    min_det = std::min(min_det, r.min_lower_bound);
  }
  const double volume = ball.volume(), exact = 4.0 / 3.0 * kPi * radius * radius * radius;

  const std::string model_file = (dir / "ball.json").string(), mf3 = (dir / "ball.3mf").string(),
                    stl = (dir / "ball.stl").string(), slices = (dir / "slices").string();
  io::write_vmodel(out.path("ball.json").string(), ball);
  const ModelTessellation mesh = tessellate_boundary(ball, {.chordal_tolerance = 0.01});
  const bool watertight = is_watertight(mesh.mesh);
  require(watertight || allow_open, "demo: the boundary mesh of the graded ball is not watertight; no files "
                                    "written (--allow-open keeps them)");
  std::vector<double> fractions;
  for (std::size_t v = 0; v < mesh.cell.size(); ++v) {
    double f[2];
    ball.eval_attribute(mesh.cell[v], "material", mesh.param[v], f);
    fractions.insert(fractions.end(), f, f + 2);
  }
  io::write_3mf(out.path("ball.3mf").string(), mesh.mesh, ball.materials(), fractions);
  io::write_stl(out.path("ball.stl").string(), mesh.mesh);
  am::SliceOptions opts;
  opts.layer_thickness = 0.1;
  opts.threads = ctx.threads;
  const am::SliceSummary s =
      slice_to_directory(ball, opts, out.path("slices").string(), false, am::DitherMethod::error_diffusion,
                         model_file, {"demo", {}, false});
  out.commit();
  char middle[32];
  std::snprintf(middle, sizeof middle, "layer_%05d.png", s.layers / 2);

  std::printf("trivar demo: graded ball for a multi-material printer\n");
  std::printf("  model        7 non-singular cells (core cube, 6 shells to exact sphere patches), radius %s mm\n",
              fmt(radius).c_str());
  std::printf("  materials    M1 at the centre blending linearly into M2 at the surface\n");
  std::printf("  Jacobian     %s for every cell: min det J >= %.6g\n", valid ? "valid" : "NOT certified", min_det);
  std::printf("  volume       %.15g, exact %.15g (relative error %.1e)\n", volume, exact, std::abs(volume - exact) / exact);
  std::printf("  boundary     %zu triangles, watertight %s, chordal tolerance 0.01 mm\n", mesh.mesh.triangles.size(),
              watertight ? "yes" : "NO");
  std::printf("  slices       %s\n", am::format_summary(s).c_str());
  std::printf("outputs:\n");
  std::printf("  %s  the V-model (try: trivar info %s)\n", model_file.c_str(), model_file.c_str());
  std::printf("  %s/  %d palette PNGs at 600 dpi, 0.1 mm layers, and manifest.json\n", slices.c_str(), s.layers);
  std::printf("  %s/%s  preview: the middle slice\n", slices.c_str(), middle);
  std::printf("  %s  3MF with graded (composite) materials per vertex\n", mf3.c_str());
  std::printf("  %s  binary STL of the boundary\n", stl.c_str());
  if (!valid && ctx.exit_code == kSuccess) ctx.exit_code = kUndecided;
}

}  // namespace

void add_demo_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("demo", "Build, refine, check and export a NURBS volume of revolution; build, slice and export a graded ball");
  struct Args {
    std::string out = "out/demo";
    bool force = false, allow_open = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--out", a->out, "Output folder: new, empty, or written by trivar before (see --force)")
      ->capture_default_str();
  cmd->add_flag("--force", a->force, "Write into a non-empty folder trivar did not write (only trivar's file names are replaced)");
  cmd->add_flag("--allow-open", a->allow_open, "Keep the outputs when the boundary mesh is not watertight");
  cmd->callback([a, &ctx] {
    const double r0 = 1.0, r1 = 2.0, height = 1.0, degrees = 270.0;
    const int parts = 2;
    const double angle = degrees / 180.0 * kPi;

    const SplineSurface profile = make_rectangle_profile({0.0, height}, {r0, r1}, {2, 2}, {1, 1});
    const SplineVolume coarse = revolve<3>(profile, {0, 0, 0}, {0, 0, 1}, angle);
    const SplineVolume model = refine_uniform(coarse, Ints<3>{parts, parts, parts});
    const JacobianReport<3> jac = check_jacobian(model);
    const double volume = signed_measure(model, 8, ctx.threads);
    const double exact = angle / 2 * (r1 * r1 - r0 * r0) * height;
    const double radius_error = max_radius_error(model, r0, r1, 21, ctx.threads);

    const std::filesystem::path dir(a->out);
    OutputFolder out(a->out, {"demo", {}, a->force});
    const std::string json = (dir / "ring.json").string(), vtu = (dir / "ring.vtu").string(),
                      bezier = (dir / "ring_bezier.vtu").string(), net = (dir / "ring_net.vtu").string();
    io::write_spline_file(out.path("ring.json").string(), {AnySpline(model)});
    const io::VtkPointField det_j{"detJ", 1, [&model](int, std::span<const double> u, std::span<double> v) {
                                    double d[derivative_count(3, 1) * 3];
                                    model.eval_derivs({u[0], u[1], u[2]}, 1, d);
                                    v[0] = jacobian_determinant(d + 3);
                                  }};
    io::write_vtu(out.path("ring.vtu").string(), model, io::VtkOptions{io::VtkCells::sampled, 4}, {det_j});
    io::write_vtu(out.path("ring_bezier.vtu").string(), model, io::VtkOptions{io::VtkCells::bezier});
    io::write_vtu(out.path("ring_net.vtu").string(), model, io::VtkOptions{io::VtkCells::control_net});

    std::printf("trivar demo: exact NURBS volume of revolution\n");
    std::printf("  profile      rectangle r in [%s, %s], z in [0, %s], degree 2 x 2, swept %s degrees about z\n",
                fmt(r0).c_str(), fmt(r1).c_str(), fmt(height).c_str(), fmt(degrees).c_str());
    std::printf("  coarse       %d x %d x %d control points, %d angular segments, rational degree 2 x 2 x 2\n",
                coarse.count(0), coarse.count(1), coarse.count(2), coarse.knots(2).num_elements());
    std::printf("  refined      every element split in %d per direction: %d x %d x %d = %d control points, %d elements\n",
                parts, model.count(0), model.count(1), model.count(2), model.num_coefs(),
                model.knots(0).num_elements() * model.knots(1).num_elements() * model.knots(2).num_elements());
    std::printf("  Jacobian     %s: min det J >= %.6g, smallest value found %.6g at (%s)\n",
                jac.valid ? "valid" : jac.invalid ? "INVALID" : "undecided", jac.min_lower_bound, jac.min_value,
                fmt(jac.where.data(), 3, ", ").c_str());
    std::printf("  volume       %.15g by Gauss quadrature of det J, exact %.15g (relative error %.1e)\n", volume,
                exact, std::abs(volume - exact) / exact);
    std::printf("  radius error %.1e on 21^3 samples (the rational model is exact)\n", radius_error);
    std::printf("outputs:\n");
    std::printf("  %s  the model (trivar JSON; try: trivar info %s)\n", json.c_str(), json.c_str());
    std::printf("  %s  sampled geometry with point data detJ, for ParaView\n", vtu.c_str());
    std::printf("  %s  exact rational Bezier cells, for ParaView\n", bezier.c_str());
    std::printf("  %s  control net, for ParaView\n", net.c_str());
    if (!jac.valid) ctx.exit_code = jac.invalid ? kInvalid : kUndecided;
    graded_ball_demo(out, dir, a->allow_open, ctx);
  });
}

}  // namespace trivar::cli
