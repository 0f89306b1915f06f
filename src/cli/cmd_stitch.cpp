// trivar stitch A B [C ...] --continuity C1 -o OUT: surfaces sharing sides joined C0 or C1 into one LR spline
// (or, with --separate, two patches with matching knot lines and continuity across their common side).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "cli.hpp"
#include "lr_cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/fit/patch_stitching.hpp"

namespace trivar::cli {
namespace {

LRSpline<2> read_surface(const std::string& path) {
  std::vector<AnyLRSpline> objects = read_as_lr(path, "stitch");
  require(objects.size() == 1 && std::holds_alternative<LRSpline<2>>(objects[0]),
          "stitch: " + path + " must hold one surface (B-spline or LR), it holds " + std::to_string(objects.size()) +
              (objects.size() == 1 ? " volume" : " objects"));
  return std::get<LRSpline<2>>(objects[0]);
}

// Largest difference of the derivative across the seam between the two patches, each evaluated on its own side.
double derivative_jump(const Stitched& s) {
  const int dim = s.first.dim(), a = s.seam.along();
  std::vector<double> x(3 * static_cast<std::size_t>(dim)), y(x.size());
  double jump = 0;
  for (int i = 0; i <= 200; ++i) {
    Param<2> u{};
    u[s.seam.dir] = s.seam.value(s.first);
    u[a] = s.first.domain().lo[a] + (s.first.domain().hi[a] - s.first.domain().lo[a]) * i / 200.0;
    s.first.eval_first_derivatives(u, x.data());
    s.second.eval_first_derivatives(u, y.data());
    for (int j = 0; j < dim; ++j) {
      const auto k = static_cast<std::size_t>((1 + s.seam.dir) * dim + j);
      jump = std::max(jump, std::abs(x[k] - y[k]));
    }
  }
  return jump;
}

}  // namespace

void add_stitch_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("stitch", "Join surfaces that share sides C0 or C1 into one LR spline");
  struct Args {
    std::vector<std::string> in;
    std::string out, continuity = "C1";
    double tolerance = 0.0;
    bool separate = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("FILES", a->in, "Surfaces (B-spline or LR: .g2, .json, .lr), each sharing a side with the union of "
                                  "those before it")
      ->required()
      ->expected(2, 1000);
  cmd->add_option("-o,--output", a->out, "Output LR file (.lr, .g2, .json, .vtu)")->required();
  cmd->add_option("--continuity", a->continuity, "C0 or C1 across every seam")
      ->check(CLI::IsMember({"C0", "C1", "c0", "c1"}))
      ->capture_default_str();
  cmd->add_option("--tolerance", a->tolerance,
                  "Largest distance between two sides that still count as one curve (default: 1e-8 of the patches' size)")
      ->check(positive());
  cmd->add_flag("--separate", a->separate,
                "Write the two stitched patches as two LR objects with matching seams instead of merging them (two "
                "inputs only)");
  cmd->callback([a] {
    require(!a->separate || a->in.size() == 2, "stitch: --separate takes exactly two surfaces");
    StitchOptions opts;
    opts.continuity = (a->continuity == "C0" || a->continuity == "c0") ? Continuity::C0 : Continuity::C1;
    opts.tolerance = a->tolerance;
    LRSpline<2> joined = read_surface(a->in[0]);
    std::vector<AnyLRSpline> out;
    std::vector<std::string> report;  // printed once everything is written
    for (std::size_t i = 1; i < a->in.size(); ++i) {
      const LRSpline<2> next = read_surface(a->in[i]);
      const Stitched s = [&] {
        try {
          return stitch(joined, next, opts);
        } catch (const Error& e) {
          throw Error(std::string(e.what()) + " (" + a->in[i] + ")");
        }
      }();
      static const char* sides[2][2] = {{"u = lo", "u = hi"}, {"v = lo", "v = hi"}};
      report.push_back(a->in[i] + ": side " + sides[s.seam.dir][s.seam.end] + ", gap " + fmt(s.seam_gap) +
                       ", control points moved up to " + fmt(s.moved) + ", derivative jump " +
                       fmt(derivative_jump(s)));
      if (a->separate) {
        out = {AnyLRSpline(s.first), AnyLRSpline(s.second)};
        break;
      }
      joined = merge(s);
    }
    if (out.empty()) out.emplace_back(std::move(joined));
    write_lr_file(a->out, out, "stitch");
    for (const std::string& line : report) std::printf("%s\n", line.c_str());
  });
}

}  // namespace trivar::cli
