// trivar check FILE: certified Jacobian validity of planar surfaces and volumes, and of the cells of a V-model,
// with the validity of the trimming boundaries of trimmed cells.
#include <algorithm>
#include <cstdio>
#include <string>
#include <variant>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/model/trimmed_check.hpp"
#include "trivar/model/trimmed_interfaces.hpp"
#include "trivar/model/trimmed_tessellation.hpp"
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

// The trim lines of a trimmed cell; returns its exit code.
int check_trimmed(const TrimmedSolid& solid) {
  const TrimCheck t = check_trim(solid);
  std::printf("trim %s\n", t.valid ? "valid" : "invalid");
  std::printf("trimming loops: largest gap %s, largest gap to edges %s\n", fmt(t.largest_loop_gap).c_str(),
              fmt(t.largest_edge_gap).c_str());
  std::printf("boundary mesh: %s\n", t.watertight ? "watertight" : "not watertight");
  std::printf("inside volume %s (mesh %s, chordal band %s)\n", fmt(t.exact_volume).c_str(), fmt(t.mesh_volume).c_str(),
              fmt(t.volume_band).c_str());
  for (const std::string& d : t.defects) std::printf("defect: %s\n", d.c_str());
  return t.valid ? kSuccess : kInvalid;
}

// The V-topology of trimmed cells: every face two cells share is whole on both sides (exactly two cells), every
// cell's edge is used by an even number of its face loops and ends at its V-points, and the model's boundary
// (the shared faces left out) is closed, its Euler characteristic from V-points, V-curves and V-surfaces the
// mesh's.
int check_trimmed_interfaces(const VModel& m) {
  const TrimmedInterfaces t = trimmed_interfaces(m);
  const TriangleMesh b = trimmed_boundary_mesh(m).mesh;
  const bool closed = is_watertight(b);
  const int chi = euler_characteristic(b);
  std::printf("trimming faces: %d shared by two cells, %d on the boundary, %zu non-conforming\n", t.shared, t.boundary,
              t.non_conforming.size());
  std::printf("trimming edges: %zu V-curves, %zu V-points\n", t.curves.size(), t.points.size());
  std::printf("model boundary: V - E + F = %d, mesh %s, Euler characteristic %d\n", t.boundary_euler,
              closed ? "watertight" : "not watertight", chi);
  for (const TrimmedFaceRef& f : t.non_conforming)
    std::printf("defect: face %d of cell %d is only partly shared with another cell\n", f.face, f.cell);
  for (const std::string& d : t.defects) std::printf("defect: %s\n", d.c_str());
  if (!closed) std::printf("defect: the model's boundary mesh is not closed\n");
  const bool euler = t.boundary_euler == chi;
  if (closed && !euler)
    std::printf("defect: the boundary's V-points, V-curves and V-surfaces give Euler characteristic %d, its mesh %d\n",
                t.boundary_euler, chi);
  return t.non_conforming.empty() && t.defects.empty() && closed && euler ? kSuccess : kInvalid;
}

int worse(int a, int b) { return (b == kInvalid || (b == kUndecided && a == kSuccess)) ? b : a; }

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
    if (const std::optional<VModel> m = read_model_if_any(a->file)) {
      int worst = kSuccess;
      for (int i = 0; i < m->num_cells(); ++i) {
        const VCell& c = m->cell(i);
        if (m->num_cells() > 1) std::printf("cell %d: ", i);
        worst = worse(worst, check(c.geometry(), a->opts));
        if (c.is_trimmed()) worst = worse(worst, check_trimmed(*c.trim()));
      }
      if (std::all_of(m->cells().begin(), m->cells().end(), [](const VCell& c) { return c.is_trimmed(); }))
        worst = worse(worst, check_trimmed_interfaces(*m));
      ctx.exit_code = worst;
      return;
    }
    const std::vector<AnySpline> objects = read_objects(a->file);
    // Several objects: the worst verdict decides (invalid over undecided over valid).
    int worst = kSuccess;
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (objects.size() > 1) std::printf("object %zu: ", i);
      worst = worse(worst, std::visit([&](const auto& s) { return check(s, a->opts); }, objects[i]));
    }
    ctx.exit_code = worst;
  });
}

}  // namespace trivar::cli
