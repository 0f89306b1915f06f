// trivar stitch A B [C ...] --continuity C1 -o OUT: surfaces sharing sides (or volumes sharing faces) joined C0 or
// C1 into one LR spline (or, with --separate, two patches with matching knot lines and continuity across their
// common side).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <type_traits>
#include <string>
#include <variant>
#include <vector>

#include "cli.hpp"
#include "lr_cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/fit/multiblock_space.hpp"
#include "trivar/fit/multiblock_stitching.hpp"
#include "trivar/fit/patch_stitching.hpp"

namespace trivar::cli {
namespace {

AnyLRSpline read_patch(const std::string& path) {
  std::vector<AnyLRSpline> objects = read_as_lr(path, "stitch");
  require(objects.size() == 1, "stitch: " + path + " must hold one surface or volume (B-spline or LR), it holds " +
                                   std::to_string(objects.size()) + " objects");
  return std::move(objects[0]);
}

// Largest difference of the derivative across the seam between the two patches, each evaluated on its own side
// (on a 201-point line along a side, a 41 x 41 grid on a face).
template <int D>
double derivative_jump(const Stitched<D>& s) {
  const int dim = s.first.dim(), n = D == 2 ? 201 : 41;
  std::vector<double> x((D + 1) * static_cast<std::size_t>(dim)), y(x.size());
  int total = 1;
  for (int k = 1; k < D; ++k) total *= n;
  double jump = 0;
  for (int g = 0; g < total; ++g) {
    Param<D> u{};
    u[s.seam.dir] = s.seam.value(s.first);
    for (int k = 0, r = g; k < D; ++k) {
      if (k == s.seam.dir) continue;
      u[k] = s.first.domain().lo[k] + (s.first.domain().hi[k] - s.first.domain().lo[k]) * (r % n) / (n - 1.0);
      r /= n;
    }
    s.first.eval_first_derivatives(u, x.data());
    s.second.eval_first_derivatives(u, y.data());
    for (int j = 0; j < dim; ++j) {
      const auto k = static_cast<std::size_t>((1 + s.seam.dir) * dim + j);
      jump = std::max(jump, std::abs(x[k] - y[k]));
    }
  }
  return jump;
}

const char* side_name(DomainSide s) {
  static const char* sides[3][2] = {{"u = lo", "u = hi"}, {"v = lo", "v = hi"}, {"w = lo", "w = hi"}};
  return sides[s.dir][s.end];
}

// The interfaces of matched blocks, one line each: the common part on each side as [lo, hi] per direction along
// it, and whether it is part of a side (a T-joint).
template <int D>
void print_interfaces(const std::vector<LRSpline<D>>& blocks, const std::vector<BlockInterface<D>>& interfaces) {
  for (const BlockInterface<D>& f : interfaces) {
    const auto part = [&](int k, bool& whole) {
      const auto kk = static_cast<std::size_t>(k);
      const LRSpline<D>& b = blocks[static_cast<std::size_t>(f.block[kk])];
      std::string text;
      for (int a = 0; a < D; ++a) {
        if (a == f.side[kk].dir) continue;
        const double lo = std::min(f.lo[kk][a], f.hi[kk][a]), hi = std::max(f.lo[kk][a], f.hi[kk][a]);
        whole = whole && lo == b.domain().lo[a] && hi == b.domain().hi[a];
        text += (text.empty() ? "[" : " x [") + fmt(f.lo[kk][a]) + ", " + fmt(f.hi[kk][a]) + "]";
      }
      return text;
    };
    bool whole = true;
    const std::string p0 = part(0, whole), p1 = part(1, whole);
    std::printf("  block %d %s %s %s - block %d %s %s %s%s\n", f.block[0], D == 2 ? "side" : "face",
                side_name(f.side[0]), p0.c_str(), f.block[1], D == 2 ? "side" : "face", side_name(f.side[1]), p1.c_str(),
                whole ? "" : " (part of a side: T-joint)");
  }
}

// How --multiblock treats the blocks: matched only (a conforming C0 space), or stitched with a continuity.
struct MultiblockRun {
  double tolerance = 0.0;
  bool whole_lines = false;
  bool stitch = false;  // --continuity given: the geometry made C0 / C1 across every interface
  Continuity continuity = Continuity::C1;
  bool fit_speeds = false;
};

// --multiblock: the blocks (planar surfaces or volumes) made conforming across interfaces that need not match one
// to one (T-joints), written as separate LR splines, with the interfaces found and the functions identified across
// them; with a continuity, the blocks (surfaces in space too, rational too) stitched C0 / C1 across all interfaces.
template <int D>
void run_multiblock(std::vector<LRSpline<D>> blocks, const std::string& out, const MultiblockRun& run) {
  const auto total_basis = [](const std::vector<LRSpline<D>>& bs) {
    int n = 0;
    for (const LRSpline<D>& b : bs) n += b.num_basis();
    return n;
  };
  const int before = total_basis(blocks);
  if (run.stitch) {
    StitchOptions opts;
    opts.continuity = run.continuity;
    opts.tolerance = run.tolerance;
    const StitchedBlocks<D> s =
        stitch_blocks(std::move(blocks), opts, run.fit_speeds ? CrossSpeed::fitted : CrossSpeed::parametric);
    std::vector<AnyLRSpline> objects(s.blocks.begin(), s.blocks.end());
    write_lr_file(out, objects, "stitch");
    const int after = total_basis(s.blocks);
    std::printf("%s: %zu blocks, %zu interfaces, %s; B-splines %d before matching, %d after; %d conditions on %d "
                "control values, moved up to %s, %s jump %s\n",
                out.c_str(), s.blocks.size(), s.interfaces.size(), run.continuity == Continuity::C1 ? "C1" : "C0", before,
                after, s.conditions, s.unknowns, fmt(s.moved).c_str(),
                run.continuity == Continuity::C1 ? "derivative" : "value", fmt(s.jump).c_str());
    print_interfaces(s.blocks, s.interfaces);
    return;
  }
  const MultiblockSpace<D> m = multiblock_space(std::move(blocks), MultiblockOptions{run.tolerance, run.whole_lines});
  std::vector<AnyLRSpline> objects(m.blocks.begin(), m.blocks.end());
  write_lr_file(out, objects, "stitch");
  const int after = total_basis(m.blocks);
  std::printf("%s: %zu blocks, %zu interfaces; B-splines %d before matching, %d after, %d global functions "
              "(%d on the boundary)\n",
              out.c_str(), m.blocks.size(), m.interfaces.size(), before, after, m.space.num_basis,
              static_cast<int>(m.boundary.size()));
  print_interfaces(m.blocks, m.interfaces);
}

// The blocks of every file for --multiblock: all surfaces or all volumes.
void run_multiblock(const std::vector<std::string>& in, const std::string& out, const MultiblockRun& run) {
  std::vector<AnyLRSpline> objects;
  for (const std::string& path : in)
    for (AnyLRSpline& object : read_as_lr(path, "stitch")) objects.push_back(std::move(object));
  require(objects.size() >= 2, "stitch: --multiblock needs at least two blocks (in one file or several)");
  std::visit(
      [&](const auto& first) {
        using Spline = std::decay_t<decltype(first)>;
        std::vector<Spline> blocks;
        for (AnyLRSpline& object : objects) {
          require(std::holds_alternative<Spline>(object), "stitch: --multiblock takes blocks of one kind (all surfaces or all volumes)");
          blocks.push_back(std::get<Spline>(std::move(object)));
        }
        run_multiblock(std::move(blocks), out, run);
      },
      objects.front());
}

// Each file stitched to the union of those before it (of the same dimension as the first).
template <int D>
void join(LRSpline<D> joined, const std::vector<std::string>& in, bool separate, const StitchOptions& opts,
          std::vector<AnyLRSpline>& out, std::vector<std::string>& report) {
  for (std::size_t i = 1; i < in.size(); ++i) {
    AnyLRSpline object = read_patch(in[i]);
    require(std::holds_alternative<LRSpline<D>>(object), "stitch: " + in[i] + " holds a " +
                                                            (D == 2 ? "volume" : "surface") + ", " + in[0] +
                                                            " a " + (D == 2 ? "surface" : "volume"));
    const Stitched<D> s = [&] {
      try {
        return stitch(joined, std::get<LRSpline<D>>(object), opts);
      } catch (const Error& e) {
        throw Error(std::string(e.what()) + " (" + in[i] + ")");
      }
    }();
    report.push_back(in[i] + ": " + (D == 2 ? "side " : "face ") + side_name(s.seam) + ", gap " + fmt(s.seam_gap) +
                     ", control points moved up to " + fmt(s.moved) + ", derivative jump " + fmt(derivative_jump(s)));
    if (separate) {
      out = {AnyLRSpline(s.first), AnyLRSpline(s.second)};
      return;
    }
    joined = merge(s);
  }
  out.emplace_back(std::move(joined));
}

}  // namespace

void add_stitch_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("stitch", "Join surfaces that share sides (volumes that share faces) C0 or C1 into one LR spline");
  struct Args {
    std::vector<std::string> in;
    std::string out, continuity = "C1";
    double tolerance = 0.0;
    bool separate = false, multiblock = false, whole_lines = false, fit_speeds = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("FILES", a->in, "Surfaces or volumes (B-spline or LR: .g2, .json, .lr), each sharing a side with the union of "
                                  "those before it (--multiblock: every block of every file)")
      ->required()
      ->expected(1, 1000);
  cmd->add_option("-o,--output", a->out, "Output LR file (.lr, .g2, .json, .vtu)")->required();
  auto* continuity = cmd->add_option("--continuity", a->continuity,
                                     "C0 or C1 across every seam (with --multiblock: stitch the blocks' geometry)")
      ->check(CLI::IsMember({"C0", "C1", "c0", "c1"}))
      ->capture_default_str();
  cmd->add_option("--tolerance", a->tolerance,
                  "Largest distance between two sides that still count as one curve (default: 1e-8 of the patches' size)")
      ->check(positive());
  cmd->add_flag("--separate", a->separate,
                "Write the two stitched patches as two LR objects with matching seams instead of merging them (two "
                "inputs only)");
  cmd->add_flag("--multiblock", a->multiblock,
                "Make planar blocks whose sides meet along common segments, or volumes whose faces meet over common "
                "parts (T-joints allowed), conforming: adapt the knot lines along every interface, identify the "
                "B-splines across it, write the matched blocks");
  cmd->add_flag("--whole-lines", a->whole_lines,
                "With --multiblock: knot lines across whole blocks, so tensor blocks stay tensor splines");
  cmd->add_flag("--fit-speeds", a->fit_speeds,
                "With --multiblock --continuity C1: the ratio of the blocks' parametric speeds across each interface "
                "fitted to the input (blocks scaled differently across and along a seam) instead of taken from the "
                "parameter lengths along it");
  cmd->callback([a, continuity] {
    require(!a->separate || a->in.size() == 2, "stitch: --separate takes exactly two patches");
    require(a->multiblock || a->in.size() >= 2, "stitch: give at least two patches (one file: with --multiblock, holding several blocks)");
    require(!(a->multiblock && a->separate), "stitch: --multiblock and --separate exclude each other");
    require(a->multiblock || !a->whole_lines, "stitch: --whole-lines needs --multiblock");
    const bool stitch_blocks = a->multiblock && continuity->count() > 0;
    require(!(stitch_blocks && a->whole_lines), "stitch: --whole-lines takes no --continuity (it matches blocks for a tensor multipatch space)");
    require(!a->fit_speeds || (stitch_blocks && a->continuity != "C0" && a->continuity != "c0"),
            "stitch: --fit-speeds needs --multiblock --continuity C1");
    const Continuity c = (a->continuity == "C0" || a->continuity == "c0") ? Continuity::C0 : Continuity::C1;
    if (a->multiblock) {
      run_multiblock(a->in, a->out, MultiblockRun{a->tolerance, a->whole_lines, stitch_blocks, c, a->fit_speeds});
      return;
    }
    StitchOptions opts;
    opts.continuity = c;
    opts.tolerance = a->tolerance;
    std::vector<AnyLRSpline> out;
    std::vector<std::string> report;  // printed once everything is written
    std::visit([&](auto first) { join(std::move(first), a->in, a->separate, opts, out, report); }, read_patch(a->in[0]));
    write_lr_file(a->out, out, "stitch");
    for (const std::string& line : report) std::printf("%s\n", line.c_str());
  });
}

}  // namespace trivar::cli
