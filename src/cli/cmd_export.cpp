// trivar export MODEL OUT [--tolerance t] [--allow-open]: the boundary of a V-model (or of volumes) for manufacturing as
// binary STL, watertight by construction, as 3MF or AMF with the material grading, or the cells with their
// attributes as VTK.
#include <algorithm>
#include <filesystem>
#include <string>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/amf_writer.hpp"
#include "trivar/io/stl_writer.hpp"
#include "trivar/io/threemf_writer.hpp"
#include "trivar/io/vmodel_vtk.hpp"
#include "trivar/model/material_fractions.hpp"
#include "trivar/model/model_tessellation.hpp"
#include "trivar/model/trimmed_tessellation.hpp"

namespace trivar::cli {

namespace {

// Material fractions of every boundary vertex, from the "material" attribute of the cell it lies on (1 for a
// model without materials). Cells without the attribute get the first material.
std::vector<double> vertex_fractions(const VModel& m, const ModelTessellation& t, int materials) {
  std::vector<double> f(t.mesh.vertices.size() * static_cast<std::size_t>(materials), 0.0);
  std::vector<double> value;
  for (std::size_t v = 0; v < t.cell.size(); ++v) {
    double* out = f.data() + v * static_cast<std::size_t>(materials);
    const VCell& c = m.cell(t.cell[v]);
    if (!c.has_attribute("material")) {
      out[0] = 1.0;
      continue;
    }
    value.resize(static_cast<std::size_t>(c.attribute("material").components()));
    c.eval_attribute("material", t.param[v], value.data());
    require(static_cast<int>(value.size()) == materials, [&] {
      return "export: cell " + std::to_string(t.cell[v]) + " has " + std::to_string(value.size()) +
             " material fractions but the model lists " + std::to_string(materials) + " materials";
    });
    material_fraction_sum(value, [&] { return cell_point(t.cell[v], t.param[v]); });
    std::copy(value.begin(), value.end(), out);
  }
  return f;
}

// AMF grading: the formulas of a material expression in x, y, z shared by every cell define the composite
// exactly; otherwise the volume is the first material and the vertex colours show the grading.
io::AmfGrading amf_grading(const VModel& m, int materials) {
  io::AmfGrading g;
  const Attribute* shared = nullptr;
  for (const VCell& c : m.cells()) {
    if (!c.has_attribute("material")) return g;
    const Attribute& a = c.attribute("material");
    if (a.kind() != Attribute::Kind::expression || a.space() != Attribute::Space::model || a.components() != materials)
      return g;
    if (shared && a.expressions().size() == shared->expressions().size())
      for (std::size_t i = 0; i < a.expressions().size(); ++i)
        if (a.expressions()[i].text() != shared->expressions()[i].text()) return g;
    shared = &a;
  }
  if (shared)
    for (const Expression& e : shared->expressions()) g.formulas.push_back(e.text());
  return g;
}

}  // namespace

void add_export_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("export", "Write the boundary of a V-model or volume as a watertight mesh (.stl; .3mf and .amf with graded materials), or its cells with attributes (.vtu)");
  struct Args {
    std::string in, out;
    double tolerance = 0.01;
    bool allow_open = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("MODEL", a->in, "V-model (.json) or spline file with volumes (.json, .g2)")->required();
  cmd->add_option("OUT", a->out, "Output file (.stl, .3mf, .amf, .vtu)")->required();
  auto* tolerance = cmd->add_option("--tolerance", a->tolerance,
                                    "Chordal tolerance in model units (trimmed models: the mesh made by make vmodel, "
                                    "which must be at least this fine)")
                        ->check(positive())
                        ->capture_default_str();
  cmd->add_flag("--allow-open", a->allow_open, "Write the mesh even when it is not watertight (otherwise an error)");
  cmd->callback([a, tolerance] {
    const bool tolerance_given = tolerance->count() > 0;
    const std::string ext = std::filesystem::path(a->out).extension().string();
    require(ext == ".stl" || ext == ".vtu" || ext == ".3mf" || ext == ".amf",
            "export: unknown output format '" + ext + "' (expected .stl, .3mf, .amf or .vtu)");
    const VModel m = read_model(a->in, "export");
    if (ext == ".vtu") {
      io::write_vmodel_vtu(a->out, m);
      return;
    }
    // Trimmed cells carry their boundary mesh, made within the chordal tolerance chosen at import.
    const bool trimmed = has_trimmed_cells(m);
    if (trimmed && tolerance_given)
      for (const VCell& c : m.cells())
        require(!c.is_trimmed() || c.trim()->boundary().chordal_tolerance <= a->tolerance, [&] {
          return "export: the trimmed boundary of " + a->in + " was meshed within " +
                 fmt(c.trim()->boundary().chordal_tolerance) + "; remake it finer (make vmodel --tolerance " +
                 fmt(a->tolerance) + ")";
        });
    const ModelTessellation t =
        trimmed ? trimmed_boundary_mesh(m) : tessellate_boundary(m, {.chordal_tolerance = a->tolerance});
    // Watertight is what the format promises a printer; an open mesh is written only when asked for. An empty
    // mesh is trivially closed but bounds nothing, so it is never written.
    require(!t.mesh.triangles.empty(), "export: the boundary mesh of " + a->in +
                                           " has no triangles (its cells enclose no volume); nothing written");
    const bool watertight = is_watertight(t.mesh);
    require(watertight || a->allow_open, "export: the boundary mesh of " + a->in + " is not watertight (" +
                                             std::to_string(t.mesh.triangles.size()) +
                                             " triangles); nothing written (--allow-open writes it anyway)");
    if (ext == ".stl") {
      io::write_stl(a->out, t.mesh);
    } else {
      const MaterialTable mats = materials_or_default(m);
      check_material_fractions(m);
      const std::vector<double> f = vertex_fractions(m, t, mats.size());
      if (ext == ".3mf")
        io::write_3mf(a->out, t.mesh, mats, f);
      else
        io::write_amf(a->out, t.mesh, mats, amf_grading(m, mats.size()), f);
    }
    std::printf("%s: %zu triangles, %zu vertices, watertight %s, enclosed volume %s\n", a->out.c_str(),
                t.mesh.triangles.size(), t.mesh.vertices.size(), watertight ? "yes" : "no",
                fmt(enclosed_volume(t.mesh)).c_str());
  });
}

}  // namespace trivar::cli
