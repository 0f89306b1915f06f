// trivar export MODEL OUT [--tolerance t]: the boundary of a V-model (or of volumes) for manufacturing as
// binary STL, watertight by construction, or the cells with their attributes as VTK.
#include <filesystem>
#include <string>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/stl_writer.hpp"
#include "trivar/io/vmodel_vtk.hpp"
#include "trivar/model/model_tessellation.hpp"

namespace trivar::cli {

namespace {

// A spline file with volumes becomes a model of those cells.
VModel model_of(const std::string& path) {
  if (std::optional<VModel> m = read_model_if_any(path)) return std::move(*m);
  VModel m;
  for (const AnySpline& s : read_objects(path)) {
    require(parametric_dimension(s) == 3, "export: " + path + " holds a " + kind_name(parametric_dimension(s)) +
                                              "; only V-models and volumes have a boundary to export");
    m.add_cell(VCell(std::get<TensorSpline<3>>(s)));
  }
  m.glue();
  return m;
}

}  // namespace

void add_export_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("export", "Write the boundary of a V-model or volume as a watertight mesh (.stl), or its cells with attributes (.vtu)");
  struct Args {
    std::string in, out;
    double tolerance = 0.01;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("MODEL", a->in, "V-model (.json) or spline file with volumes (.json, .g2)")->required();
  cmd->add_option("OUT", a->out, "Output file (.stl, .vtu)")->required();
  cmd->add_option("--tolerance", a->tolerance, "Chordal tolerance in model units")
      ->check(positive())
      ->capture_default_str();
  cmd->callback([a] {
    const std::string ext = std::filesystem::path(a->out).extension().string();
    require(ext == ".stl" || ext == ".vtu", "export: unknown output format '" + ext + "' (expected .stl or .vtu)");
    const VModel m = model_of(a->in);
    if (ext == ".vtu") {
      io::write_vmodel_vtu(a->out, m);
      return;
    }
    const ModelTessellation t = tessellate_boundary(m, {.chordal_tolerance = a->tolerance});
    io::write_stl(a->out, t.mesh);
    std::printf("%s: %zu triangles, %zu vertices, watertight %s, enclosed volume %s\n", a->out.c_str(),
                t.mesh.triangles.size(), t.mesh.vertices.size(), is_watertight(t.mesh) ? "yes" : "no",
                fmt(enclosed_volume(t.mesh)).c_str());
  });
}

}  // namespace trivar::cli
