// trivar demo [--out DIR]: the library end to end on one model. Builds an exact NURBS volume of revolution,
// refines it, certifies its Jacobian, verifies its volume and radii against closed forms, and writes files
// for ParaView.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/vtk_writer.hpp"
#include "trivar/model/block.hpp"
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

}  // namespace

void add_demo_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("demo", "Build, refine, check and export a NURBS volume of revolution");
  auto out = std::make_shared<std::string>("out/demo");
  cmd->add_option("--out", *out, "Output directory")->capture_default_str();
  cmd->callback([out, &ctx] {
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

    const std::filesystem::path dir(*out);
    std::filesystem::create_directories(dir);
    const std::string json = (dir / "ring.json").string(), vtu = (dir / "ring.vtu").string(),
                      bezier = (dir / "ring_bezier.vtu").string(), net = (dir / "ring_net.vtu").string();
    io::write_spline_file(json, {AnySpline(model)});
    const io::VtkPointField det_j{"detJ", 1, [&model](int, std::span<const double> u, std::span<double> v) {
                                    double d[derivative_count(3, 1) * 3];
                                    model.eval_derivs({u[0], u[1], u[2]}, 1, d);
                                    v[0] = jacobian_determinant(d + 3);
                                  }};
    io::write_vtu(vtu, model, io::VtkOptions{4, false, false}, {det_j});
    io::write_vtu(bezier, model, io::VtkOptions{1, true, false});
    io::write_vtu(net, model, io::VtkOptions{1, false, true});

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
  });
}

}  // namespace trivar::cli
