// trivar fit POINTS -o OUT --tolerance T: an LR spline approximating scattered data (terrain x y z, or with
// --volume a field over x y z), refined where the points are not yet within the tolerance.
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "lr_cli.hpp"
#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/fit/cell_field.hpp"
#include "trivar/fit/graph_surface.hpp"
#include "trivar/fit/height_image.hpp"
#include "trivar/fit/lr_approximation.hpp"
#include "trivar/fit/point_file.hpp"
#include "trivar/io/png_writer.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/io/step/step_file.hpp"

namespace trivar::cli {
namespace {

struct FitArgs {
  std::string in;
  std::vector<std::string> out;
  double tolerance = 0.0, relative = 0.0;
  bool volume = false, height_field = false, report = false, no_check = false;
  std::string report_json, image, error_image, strategy = "fullspan", method = "ls";
  std::string into, attribute = "material";  // --into: the model whose cell receives the fitted field
  int cell = 0;
  int image_width = 1024;
  ApproximationOptions opts;
};

nlohmann::json to_json(const IterationReport& r) {
  return {{"level", r.level},         {"coefficients", r.coefficients}, {"elements", r.elements},
          {"max_error", r.max_error}, {"mean_error", r.mean_error},     {"rms_error", r.rms_error},
          {"outside", r.outside},     {"seconds", r.seconds},           {"independence", r.independence}};
}

void print_row(const IterationReport& r) {
  std::printf("%5d %8d %8d %12.5g %12.5g %12.5g %9zu %8.3f  %s\n", r.level, r.coefficients, r.elements, r.max_error,
              r.mean_error, r.rms_error, r.outside, r.seconds, r.independence.c_str());
  std::fflush(stdout);
}

template <int D>
void run(const FitArgs& a, const PointTable& table) {
  const ScatteredData<D> data = scattered_data<D>(table, a.in);
  ApproximationOptions o = a.opts;
  o.strategy = parse_strategy(a.strategy);
  o.method = parse_fit_method(a.method);
  o.check_independence = !a.no_check;
  double lo = data.values.front(), hi = lo;
  for (double v : data.values) lo = std::min(lo, v), hi = std::max(hi, v);
  o.tolerance = a.tolerance > 0.0 ? a.tolerance : a.relative * (hi - lo);
  require(o.tolerance > 0.0, "fit: " + a.in + ": the values are constant, so a relative tolerance is 0; give --tolerance");
  if (a.report) {
    std::printf("fit %s: %zu points, %d value%s, tolerance %s\n", a.in.c_str(), data.size(), data.dim,
                data.dim == 1 ? "" : "s", fmt(o.tolerance).c_str());
    std::printf("level   coefs elements    max error   mean error    rms error   outside  seconds  basis\n");
  }
  const Approximation<D> fit = approximate(data, o, a.report ? std::function<void(const IterationReport&)>(print_row)
                                                             : std::function<void(const IterationReport&)>());
  const LRSpline<D>& s = fit.spline;
  AnyLRSpline result = s;
  if constexpr (D == 2)
    if (data.dim == 1 && !a.height_field) result = graph_surface(s, fit.parameters);
  for (const std::string& out : a.out) {
    if (is_step_file(out)) {
      io::step::GeometryFileOptions options;
      options.description = "trivar fit of " + a.in;
      io::step::write_step(out, {}, {result}, options);
    } else {
      write_lr_file(out, {result}, "fit");
    }
  }
  if constexpr (D == 2) {
    if (!a.image.empty()) io::write_png(a.image, height_image(s, a.image_width));
    if (!a.error_image.empty()) io::write_png(a.error_image, error_image(data, fit.errors, o.tolerance, a.image_width));
  }
  if (!a.report_json.empty()) {
    nlohmann::json doc = {{"input", a.in},
                          {"points", data.size()},
                          {"tolerance", o.tolerance},
                          {"strategy", a.strategy},
                          {"method", a.method},
                          {"converged", fit.converged},
                          {"stop_reason", fit.stop_reason},
                          {"iterations", nlohmann::json::array()}};
    for (const IterationReport& r : fit.iterations) doc["iterations"].push_back(to_json(r));
    write_file_atomically(a.report_json, [&](std::ostream& os) { os << doc.dump(2) << '\n'; });
  }
  const IterationReport& last = fit.iterations.back();
  std::printf("%s: LR %s, %d coefficients, %d elements, max error %s (tolerance %s), %zu point%s outside: %s\n",
              a.out.front().c_str(), kind_name(D), s.num_basis(), s.num_elements(), fmt(last.max_error).c_str(),
              fmt(o.tolerance).c_str(), last.outside, last.outside == 1 ? "" : "s", fit.stop_reason.c_str());
}

// --into: the samples (x y z values) fitted over one cell of a V-model and attached to it as a field attribute.
void run_into(const FitArgs& a, const PointTable& table, ApproximationOptions o) {
  const ScatteredData<3> samples = scattered_data<3>(table, a.in);
  VModel model = read_model(a.into, "fit");
  require(a.cell >= 0 && a.cell < model.num_cells(), "fit: " + a.into + " has " + std::to_string(model.num_cells()) +
                                                         " cells, no cell " + std::to_string(a.cell));
  double lo = samples.values.front(), hi = lo;
  for (double v : samples.values) lo = std::min(lo, v), hi = std::max(hi, v);
  o.tolerance = a.tolerance > 0.0 ? a.tolerance : a.relative * (hi - lo);
  require(o.tolerance > 0.0, "fit: " + a.in + ": the values are constant, so a relative tolerance is 0; give --tolerance");
  CellFieldOptions co;
  co.fit = o;
  co.fractions = a.attribute == "material";
  if (co.fractions && !model.materials().empty())
    require(samples.dim == model.materials().size(), "fit: " + a.in + " has " + std::to_string(samples.dim) +
                                                         " fractions per sample but " + a.into + " lists " +
                                                         std::to_string(model.materials().size()) + " materials");
  const CellField f = fit_cell_field(model.cell(a.cell), samples, co);
  if (a.report)
    for (const IterationReport& r : f.fit.iterations) print_row(r);
  model.cell(a.cell).set_attribute(a.attribute, f.attribute);
  io::write_vmodel(a.out.front(), model);
  const TensorSpline<3>& field = *f.attribute.spline();
  std::printf("%s: cell %d attribute '%s' (%d value%s): %zu samples in the cell, %zu outside; LR fit %d coefficients, "
              "%s; field %d tensor coefficients, max error at the samples %s (tolerance %s)%s\n",
              a.out.front().c_str(), a.cell, a.attribute.c_str(), samples.dim, samples.dim == 1 ? "" : "s", f.used,
              f.outside, f.fit.spline.num_basis(), f.fit.stop_reason.c_str(), field.num_coefs(), fmt(f.max_error).c_str(),
              fmt(o.tolerance).c_str(),
              f.clamped > 0 ? (", negative fractions up to " + fmt(f.clamped) + " raised to 0").c_str() : "");
}

}  // namespace

void add_fit_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("fit", "Approximate scattered points by an LR spline (terrain, volumetric fields)");
  auto a = std::make_shared<FitArgs>();
  cmd->add_option("POINTS", a->in,
                  "Point file: text/CSV rows 'x y z' (or 'x y z v...' with --volume), or the binary .tvp format")
      ->required();
  cmd->add_option("-o,--output", a->out, "Output files by extension: .lr, .g2, .json, .vtu, .stp/.step (repeatable)")
      ->required();
  auto* tol = cmd->add_option("--tolerance", a->tolerance, "Largest error allowed at any point (absolute)")
                  ->check(positive());
  cmd->add_option("--relative-tolerance", a->relative, "Tolerance as a fraction of the value range, e.g. 0.005")
      ->check(positive())
      ->excludes(tol);
  cmd->add_option("--levels", a->opts.max_levels, "Refinement rounds at most")->check(CLI::Range(0, 30))->capture_default_str();
  cmd->add_option("--degree", a->opts.degree, "Polynomial degree in every direction")->check(CLI::Range(1, 5))->capture_default_str();
  cmd->add_option("--initial-elements", a->opts.initial_elements, "Elements of the start spline along the longest side")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--strategy", a->strategy, "Refinement: fullspan, minspan or structured")
      ->check(CLI::IsMember({"fullspan", "minspan", "structured"}))
      ->capture_default_str();
  cmd->add_option("--method", a->method,
                  "Fit of each round: ls (penalised least squares) or mba (multilevel B-spline approximation, "
                  "no linear system: for millions of points)")
      ->check(CLI::IsMember({"ls", "mba"}))
      ->capture_default_str();
  cmd->add_option("--mba-passes", a->opts.mba_passes, "MBA passes per refinement round")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("--smoothing", a->opts.smoothing, "Weight of the thin-plate smoothing term (dimensionless)")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_option("--max-coefs", a->opts.max_coefficients, "Stop before exceeding this many coefficients (0: no limit)")
      ->check(at_least(0));
  cmd->add_flag("--uniform", a->opts.uniform,
                "Refine every element (a uniform tensor spline), to compare with the local refinement");
  cmd->add_option("--into", a->into,
                  "V-model (.json) whose cell receives the fitted field as an attribute (with --volume; samples are model "
                  "points x y z with values; -o names the model written)");
  cmd->add_option("--cell", a->cell, "With --into: the cell's index")->check(at_least(0))->capture_default_str();
  cmd->add_option("--attribute", a->attribute,
                  "With --into: the attribute's name; 'material' fits material fractions (kept >= 0 everywhere)")
      ->capture_default_str();
  cmd->add_flag("--volume", a->volume, "The first three columns are x y z (an LR volume), the rest values");
  cmd->add_flag("--height-field", a->height_field, "Terrain: write the height z(x, y) instead of the surface (x, y, z)");
  cmd->add_flag("--no-independence-check", a->no_check, "Skip the linear-independence test after each refinement");
  cmd->add_flag("--report", a->report, "Print one line per iteration: coefficients, elements, errors, seconds");
  cmd->add_option("--report-json", a->report_json, "Write the per-iteration report as JSON");
  cmd->add_option("--image", a->image, "Terrain: height-coloured, hill-shaded PNG of the fitted surface");
  cmd->add_option("--error-image", a->error_image, "Terrain: PNG of the error at the points (red at the tolerance)");
  cmd->add_option("--image-width", a->image_width, "Width of the pictures in pixels")->check(CLI::Range(1, 16384))->capture_default_str();
  cmd->callback([a, &ctx] {
    require(a->tolerance > 0.0 || a->relative > 0.0, "fit: give --tolerance or --relative-tolerance");
    if (!a->into.empty()) {
      require(a->volume, "fit: --into fits a field over a cell: give --volume (samples x y z values)");
      require(a->out.size() == 1 && io::file_extension(a->out.front()) == ".json",
              "fit: with --into, -o names the one V-model .json file written");
      require(a->image.empty() && a->error_image.empty(), "fit: --image and --error-image picture terrain, not cells");
      a->opts.threads = ctx.threads;
      ApproximationOptions o = a->opts;
      o.strategy = parse_strategy(a->strategy);
      o.method = parse_fit_method(a->method);
      o.check_independence = !a->no_check;
      run_into(*a, read_point_file(a->in), o);
      return;
    }
    for (const std::string& out : a->out)
      require(is_step_file(out) || lr_output_extension(out),
              "fit: cannot write '" + out + "' (use .lr, .g2, .json, .vtu, .stp or .step)");
    for (const std::string* png : {&a->image, &a->error_image}) {
      if (png->empty()) continue;
      require(!a->volume, "fit: --image and --error-image picture terrain, not volumes");
      require(io::file_extension(*png) == ".png", "fit: '" + *png + "' is not a .png file");
    }
    a->opts.threads = ctx.threads;
    const PointTable table = read_point_file(a->in);
    if (a->volume) run<3>(*a, table);
    else run<2>(*a, table);
  });
}

}  // namespace trivar::cli
