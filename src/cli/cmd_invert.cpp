// trivar invert FILE x [y [z]]: the parameter of a model-space point (point inversion).
#include <cstdio>
#include <string>
#include <variant>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/point_inversion.hpp"

namespace trivar::cli {

namespace {

template <int D>
int invert_point(const TensorSpline<D>& s, const std::vector<double>& x, const InversionOptions& opts) {
  require(static_cast<int>(x.size()) == s.dim(), "invert: the spline has control dimension " + std::to_string(s.dim()) +
                                                     ", got " + std::to_string(x.size()) + " coordinates");
  const InversionResult<D> r = invert(s, x.data(), opts);
  if (!r.found) {
    std::printf("outside\n");  // provably no parameter maps to x: there is nothing else to report
    return kOutside;
  }
  std::printf("param: %s\n", fmt(r.param.data(), D).c_str());
  std::printf("residual: %s\n", fmt(r.residual).c_str());
  std::printf("%s\n", r.converged ? "converged" : "not converged");
  return r.converged ? kSuccess : kUndecided;
}

}  // namespace

void add_invert_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("invert", "Find the parameter of a point (exit 4 when it is outside the model)");
  struct Args {
    std::string file;
    std::vector<double> x;
    InversionOptions opts;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("FILE", a->file, "Spline file with one object whose control dimension equals its parametric one")
      ->required();
  cmd->add_option("POINT", a->x, "Model-space point x [y [z]]")->required()->expected(1, 3);
  cmd->add_option("--tolerance", a->opts.tolerance, "Accepted residual, relative to the control bounding-box diagonal")
      ->check(positive())
      ->capture_default_str();
  cmd->callback([a, &ctx] {
    const AnySpline s = read_single(a->file, "invert");
    ctx.exit_code = std::visit([&](const auto& spline) { return invert_point(spline, a->x, a->opts); }, s);
  });
}

}  // namespace trivar::cli
