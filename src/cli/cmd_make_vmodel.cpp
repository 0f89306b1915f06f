// trivar make vmodel PART.stp -o PART.json: one trimmed V-model per solid of a STEP file. The cell is the
// identity trivariate on a box around the solid, trimmed by the solid's exact faces (the cad layer).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli.hpp"
#include "trivar/cad/step_import.hpp"
#include "trivar/core/error.hpp"

namespace trivar::cli {

namespace {

// "part.json" for one solid; "part.0.json", "part.1.json", ... for several.
std::string output_name(const std::string& out, std::size_t index, std::size_t count) {
  if (count == 1) return out;
  const std::filesystem::path p(out);
  return (p.parent_path() / (p.stem().string() + "." + std::to_string(index) + p.extension().string())).string();
}

}  // namespace

void add_make_vmodel(CLI::App& make) {
  auto* cmd = make.add_subcommand("vmodel", "Trimmed V-models of the B-rep solids of a STEP file: per solid one cell, "
                                            "a box trivariate trimmed by the solid's exact NURBS faces");
  struct Args : MaterialArgs {
    std::string in, out;
    double tolerance = 0;
    int solid = -1;
    bool kernel_volume = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("STEP", a->in, "STEP file (.stp, .step) with one or more solids")->required();
  cmd->add_option("--tolerance", a->tolerance,
                  "Chordal tolerance of the trimmed boundary's mesh, in model units (default: 1e-3 of the part's "
                  "diagonal); export writes this mesh")
      ->check(positive());
  cmd->add_option("--solid", a->solid, "Convert only this solid (0-based, in file order)")->check(at_least(0));
  cmd->add_flag("--kernel-volume", a->kernel_volume,
                "Also compute OpenCASCADE's own volume of each solid and print it beside trivar's (a cross-check "
                "that costs extra time)");
  add_material_options(cmd, *a, "along z");
  cmd->add_option("-o,--output", a->out,
                  "Output V-model (.json); several solids give PART.0.json, PART.1.json, ... beside it")
      ->required();
  cmd->callback([a] {
    require(is_step_file(a->in), "make vmodel: " + a->in + " is not a STEP file (.stp, .step, .p21)");
    const cad::StepImport im = cad::import_step(a->in, {.chordal_tolerance = a->tolerance, .kernel_volume = a->kernel_volume});
    if (im.solids.empty()) {
      std::string what;
      for (const std::string& s : im.report.not_solid) what += (what.empty() ? "" : "; ") + s;
      throw Error("make vmodel: " + a->in + ": no solid" + (what.empty() ? "" : " (" + what + ")"));
    }
    require(a->solid < static_cast<int>(im.solids.size()), [&] {
      return "make vmodel: --solid " + std::to_string(a->solid) + " but " + a->in + " has " +
             std::to_string(im.solids.size()) + " solids";
    });
    // Everything is checked before anything is written.
    std::vector<std::size_t> chosen;
    for (std::size_t i = 0; i < im.solids.size(); ++i)
      if (a->solid < 0 || static_cast<int>(i) == a->solid) chosen.push_back(i);
    for (std::size_t i : chosen)
      if (!im.solids[i].solid) {
        std::string faces;
        int n = 0;
        for (const cad::UnmappedFace& f : im.report.unmapped) {
          if (n++ < 3) faces += (faces.empty() ? "" : "; ") + f.name + ": " + f.reason;
        }
        throw Error("make vmodel: " + a->in + ": " + im.solids[i].name + ": " + std::to_string(im.report.unmapped.size()) +
                    " face" + (im.report.unmapped.size() == 1 ? "" : "s") + " could not be mapped (" + faces +
                    (n > 3 ? "; ..." : "") + "); nothing written");
      }
    for (const std::string& r : im.report.repairs) std::fprintf(stderr, "trivar: warning: %s: %s\n", a->in.c_str(), r.c_str());
    for (const std::string& r : im.report.open_boundaries) std::fprintf(stderr, "trivar: warning: %s: %s\n", a->in.c_str(), r.c_str());
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      const cad::ImportedSolid& s = im.solids[chosen[k]];
      Box<3> box = s.solid->bounding_box();
      const double grow = 1e-3 * box.diagonal();
      for (int d = 0; d < 3; ++d) {
        box.lo[d] -= grow;
        box.hi[d] += grow;
      }
      const auto c = box.center();
      const std::string radial = "sqrt((x - " + fmt(c[0]) + ")^2 + (y - " + fmt(c[1]) + ")^2 + (z - " + fmt(c[2]) +
                                 ")^2) / (" + fmt(box.diagonal() / 2) + ")";
      const std::string axial = "(z - " + fmt(box.lo[2]) + ") / (" + fmt(box.extent(2)) + ")";
      const std::string out = output_name(a->out, k, chosen.size());
      std::vector<VCell> cells;
      cells.emplace_back(identity_box(box), s.solid);
      write_model(std::move(cells), *a, radial, axial, out);
      std::printf("%s: %s, %zu faces, volume %s%s\n", out.c_str(), s.name.c_str(), s.solid->boundary().faces.size(),
                  fmt(s.solid->volume()).c_str(),
                  s.kernel_volume ? (" (OpenCASCADE " + fmt(*s.kernel_volume) + ")").c_str() : "");
    }
  });
}

}  // namespace trivar::cli
