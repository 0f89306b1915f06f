// trivar convert IN OUT: between spline formats by extension (.json, .g2) and to VTK (.vtu) for viewing;
// V-models to .vtu (every cell a piece, attributes as point data) or .json; LR splines between .lr, .g2, .json
// and .vtu, tensor surfaces and volumes to LR for .lr output or with --lr; STEP (.stp, .step) in both
// directions: the B-spline and locally refined geometry of a STEP file out, any spline, LR or V-model file's
// objects (a V-model's cell volumes) in.
#include <cstdio>
#include <filesystem>
#include <type_traits>
#include <variant>
#include <string>

#include "cli.hpp"
#include "hier_cli.hpp"
#include "lr_cli.hpp"
#include "step_cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/step/step_file.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/io/vmodel_vtk.hpp"
#include "trivar/io/vtk_writer.hpp"
#include "tspline_cli.hpp"

namespace trivar::cli {

void add_convert_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("convert", "Convert a spline file; the format follows the extension (.json .g2 .vtu; every object is one VTU piece)");
  struct Args {
    std::string in, out;
    int samples = 4;
    bool lr = false, bezier = false, sampled = false, control_net = false, parametric_mesh = false, strict = false;
    TSplineConvertOptions t_spline;
    // The VTK cells the flags ask for (Bezier unless --samples, --control-net or --parametric-mesh).
    io::VtkOptions tensor_vtk() const {
      return {control_net ? io::VtkCells::control_net : sampled ? io::VtkCells::sampled : io::VtkCells::bezier,
              samples};
    }
    io::LRVtkOptions lr_vtk() const {
      return {parametric_mesh ? io::LRVtkCells::parametric_mesh : sampled ? io::LRVtkCells::sampled : io::LRVtkCells::bezier,
              samples};
    }
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("IN", a->in, "Input spline file (.json, .g2, .lr, .xml), STEP file (.stp, .step) or V-model (.json)")->required();
  cmd->add_option("OUT", a->out, "Output file (.json, .g2, .lr, .xml, .vtu, .stp, .step)")->required();
  auto* samples = cmd->add_option("--samples", a->samples,
                                  "VTK: linear cells sampling every element at N points per direction instead of "
                                  "one exact Bezier cell per element")
                      ->check(at_least(1))
                      ->each([a](const std::string&) { a->sampled = true; });
  cmd->add_flag("--bezier", a->bezier, "VTK: one exact rational Bezier cell per element (the default)")->excludes(samples);
  cmd->add_flag("--control-net", a->control_net, "VTK: write the control net (points and polygon lines) instead of the geometry");
  cmd->add_flag("--lr", a->lr, "Convert tensor surfaces and volumes to LR splines (implied by an .lr output)");
  cmd->add_flag("--parametric-mesh", a->parametric_mesh, "VTK of LR splines: the mesh in parameter space instead of the geometry");
  cmd->add_flag("--strict", a->strict,
                "STEP input: refuse departures from ISO 10303-21 (lower-case keywords, stray bytes in strings, "
                "dangling references, reference cycles) instead of warning");
  cmd->add_option("--step-form", a->t_spline.step_form,
                  "T-spline to STEP: t-spline (the T_SPLINE_SURFACE entities of the three layers, AP238) or part42 "
                  "(an ISO 10303-42 locally refined surface of T-spline type)")
      ->check(CLI::IsMember({"t-spline", "part42"}));
  cmd->add_option("--tolerance", a->t_spline.tolerance,
                  "T-spline to .stl/.obj (and .vtu with --triangles): chordal tolerance (default 1e-3 of the size); T-spline with "
                  "star points to patches: largest deviation from the limit surface (default 1e-6 of the size)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--triangles", a->t_spline.triangles, "T-spline to .vtu: the tessellation instead of exact Bezier cells");
  cmd->callback([a] {
    if (is_t_spline_file(a->in)) {
      convert_tspline(a->in, a->out, a->t_spline);
      return;
    }
    require(!a->strict || is_step_file(a->in), "convert: --strict applies to STEP input, not " + a->in);
    if (is_step_file(a->out)) {
      require(!is_step_file(a->in), "convert: " + a->in + " is already a STEP file");
      if (const auto h = read_hierarchical_if_any(a->in)) {
        write_hierarchical_file(a->out, *h, "convert");
        std::printf("%s: %zu hierarchical object%s as HB B-spline collections (AP242, ISO 10303-21)\n", a->out.c_str(),
                    h->size(), h->size() == 1 ? "" : "s");
        return;
      }
      std::vector<AnySpline> splines;
      std::vector<AnyLRSpline> lr;
      if (const std::optional<VModel> model = read_model_if_any(a->in)) {
        for (const VCell& c : model->cells()) splines.emplace_back(c.geometry());
      } else if (std::optional<std::vector<AnyLRSpline>> l = read_lr_if_any(a->in)) {
        lr = std::move(*l);
      } else {
        splines = read_objects(a->in);
      }
      io::step::GeometryFileOptions options;
      options.description = "trivar geometry from " + a->in;
      io::step::write_step(a->out, splines, lr, options);
      std::printf("%s: %zu B-spline object%s, %zu locally refined (AP242, ISO 10303-21)\n", a->out.c_str(),
                  splines.size(), splines.size() == 1 ? "" : "s", lr.size());
      return;
    }
    if (is_step_file(a->in)) {
      io::step::StepContents c = read_step_warning(a->in, a->strict);
      require(!c.splines.empty() || !c.lr_splines.empty(), "convert: " + a->in + " holds no B-spline or locally refined geometry");
      if (c.lr_splines.empty() && !a->lr && !is_lr_extension(a->out)) {
        if (std::filesystem::path(a->out).extension() == ".vtu")
          io::write_vtu(a->out, c.splines, a->tensor_vtk());
        else
          io::write_spline_file(a->out, c.splines);
        return;
      }
      require(c.splines.empty() || a->lr || is_lr_extension(a->out),
              "convert: " + a->in + " holds " + std::to_string(c.splines.size()) + " B-spline and " +
                  std::to_string(c.lr_splines.size()) + " locally refined objects; one output file holds one kind: "
                  "give --lr to write all as LR splines");
      for (const AnySpline& s : c.splines) {
        std::visit(
            [&](const auto& t) {
              constexpr int D = std::decay_t<decltype(t)>::kDim;
              if constexpr (D == 1) throw Error("convert: " + a->in + " holds a curve, which has no LR form; convert without --lr");
              else c.lr_splines.emplace_back(LRSpline<D>(t));
            },
            s);
      }
      write_lr_file(a->out, c.lr_splines, "convert", a->lr_vtk());
      return;
    }
    if (const auto h = read_hierarchical_if_any(a->in)) {
      require(!a->lr, "convert: --lr applies to tensor splines, not to the hierarchical splines of " + a->in);
      write_hierarchical_file(a->out, *h, "convert", a->lr_vtk());
      return;
    }
    if (const std::optional<VModel> model = read_model_if_any(a->in)) {
      const std::string ext = std::filesystem::path(a->out).extension().string();
      require(ext == ".vtu" || ext == ".json",
              "convert: a V-model converts to .vtu (cells with attributes) or .json, not '" + ext + "'");
      if (ext == ".vtu")
        io::write_vmodel_vtu(a->out, *model, a->tensor_vtk());
      else
        io::write_vmodel(a->out, *model);
      return;
    }
    std::optional<std::vector<AnyLRSpline>> lr = read_lr_if_any(a->in);
    if (lr || a->lr || is_lr_extension(a->out)) {
      require(!a->control_net, "convert: --control-net applies to tensor splines, not LR splines");
      if (!lr) lr = read_as_lr(a->in, "convert");
      write_lr_file(a->out, *lr, "convert", a->lr_vtk());
      return;
    }
    require(!a->parametric_mesh, "convert: --parametric-mesh applies to LR splines; give --lr to convert " + a->in);
    const std::vector<AnySpline> objects = read_objects(a->in);
    if (std::filesystem::path(a->out).extension() == ".vtu") {
      io::write_vtu(a->out, objects, a->tensor_vtk());
      return;
    }
    io::write_spline_file(a->out, objects);
  });
}

}  // namespace trivar::cli
