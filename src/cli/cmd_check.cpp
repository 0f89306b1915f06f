// trivar check FILE: certified Jacobian validity of planar surfaces and volumes.
#include <cstdio>
#include <string>
#include <variant>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/jacobian.hpp"

namespace trivar::cli {

namespace {

// Prints the verdict lines of one object and returns its exit code.
template <int D>
int check(const TensorSpline<D>& s, const JacobianOptions& opts) {
  if constexpr (D == 1) {
    throw Error("check: the Jacobian check applies to planar surfaces and volumes, not curves");
  } else {
    require(s.dim() == D, std::string("check: the Jacobian determinant needs control dimension ") + std::to_string(D) +
                              " for a " + kind_name(D) + ", got " + std::to_string(s.dim()));
    const JacobianReport<D> r = check_jacobian(s, opts);
    const char* verdict = r.valid ? "valid" : r.invalid ? "invalid" : "undecided";
    std::printf("%s\n", verdict);
    std::printf("min det J >= %s\n", fmt(r.min_lower_bound).c_str());
    std::printf("min det J found %s at (%s)\n", fmt(r.min_value).c_str(), fmt(r.where.data(), D, ", ").c_str());
    std::printf("elements: %d, subdivisions: %d\n", r.elements, r.subdivisions);
    return r.valid ? kSuccess : r.invalid ? kInvalid : kUndecided;
  }
}

}  // namespace

void add_check_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("check", "Certify that det J > 0 everywhere (exit 0 valid, 3 invalid, 5 undecided)");
  struct Args {
    std::string file;
    JacobianOptions opts;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("FILE", a->file, "Spline file (.json, .g2): volumes, or surfaces with control dimension 2")->required();
  cmd->add_option("--max-depth", a->opts.max_depth, "Subdivision levels per element")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_option("--gap", a->opts.relative_gap, "Stop refining an element when its bounds agree to this relative gap")
      ->check(positive())
      ->capture_default_str();
  cmd->callback([a, &ctx] {
    const std::vector<AnySpline> objects = read_objects(a->file);
    // Several objects: the worst verdict decides (invalid over undecided over valid).
    int worst = kSuccess;
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (objects.size() > 1) std::printf("object %zu: ", i);
      const int code = std::visit([&](const auto& s) { return check(s, a->opts); }, objects[i]);
      if (code == kInvalid || (code == kUndecided && worst == kSuccess)) worst = code;
    }
    ctx.exit_code = worst;
  });
}

}  // namespace trivar::cli
