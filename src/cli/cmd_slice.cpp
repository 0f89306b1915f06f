// trivar slice MODEL --out DIR [--layer t] [--dpi X[xY]] [--mode palette|per-material]
// [--dither error-diffusion|ordered] [--z-range z0 z1] [--tracing none|previous-point|previous-line|full] [--force]:
// printer bitmaps of a graded V-model, one material per pixel, with a JSON manifest, written through an
// OutputFolder (trivar/core/output_folder.hpp), so a failed or interrupted run leaves no partial output and
// nothing trivar did not write is removed.
#include <unistd.h>

#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "trivar/am/dithering.hpp"
#include "trivar/am/layer_slicer.hpp"
#include "trivar/am/slicer.hpp"
#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/io/png_writer.hpp"

namespace trivar::cli {

namespace {

// "600" or "600x300": the resolution in x and y.
std::array<double, 2> parse_dpi(const std::string& text) {
  const std::size_t x = text.find('x');
  try {
    std::size_t used = 0;
    const double a = std::stod(text.substr(0, x), &used);
    require(used == (x == std::string::npos ? text.size() : x), "");
    double b = a;
    if (x != std::string::npos) {
      b = std::stod(text.substr(x + 1), &used);
      require(used == text.size() - x - 1, "");
    }
    require(a > 0 && b > 0 && std::isfinite(a) && std::isfinite(b), "");
    return {a, b};
  } catch (const std::exception&) {
    throw Error("slice: --dpi must be a positive number or XxY (e.g. 600x300), got '" + text + "'");
  }
}

std::string hex(const Rgba& c) {
  char buf[10];
  std::snprintf(buf, sizeof buf, "#%02X%02X%02X%02X", c.r, c.g, c.b, c.a);
  return buf;
}

// Layer k's file stem, zero-padded to the width of the largest layer number (at least 5 digits).
std::string layer_stem(int k, int layers) {
  const int width = std::max(5, static_cast<int>(std::to_string(std::max(layers - 1, 0)).size()));
  std::string n = std::to_string(k);
  return "layer_" + std::string(static_cast<std::size_t>(std::max(0, width - static_cast<int>(n.size()))), '0') + n;
}

// Bytes one layer holds while it is sliced, dithered and encoded: the cell index (int) and material fractions
// (float per material) of every pixel, its label, and the PNG's raw rows and compressed data.
double layer_bytes(const am::SliceGrid& g, int materials) {
  const double per_pixel = static_cast<double>(sizeof(int) + sizeof(float) * static_cast<std::size_t>(materials) + 3);
  return static_cast<double>(g.width) * g.height * per_pixel;
}

}  // namespace

am::SliceSummary slice_to_directory(const VModel& model, const am::SliceOptions& opts, const std::string& dir,
                                    bool per_material, am::DitherMethod method, const std::string& source,
                                    const OutputFolderOptions& folder_options) {
  const std::string& command = folder_options.command;
  require(!model.materials().empty(), command + ": " + source + " has no materials (build it with --materials or "
                                      "--material-field, or list \"materials\" in the model file)");
  const MaterialTable& materials = model.materials();
  if (opts.z_range) {
    // Layers outside the part would all be empty: almost certainly a wrong range, never a useful job.
    const Box<3> bb = model.bounding_box();
    const auto [z0, z1] = *opts.z_range;
    require(z0 < bb.hi[2] && z1 > bb.lo[2], command + ": --z-range " + fmt(z0) + " " + fmt(z1) +
                                                " does not meet the model, whose z extent is [" + fmt(bb.lo[2]) +
                                                ", " + fmt(bb.hi[2]) + "]");
  }
  const am::DitherOptions dither{method};
  const std::vector<Rgba> palette = io::material_palette(materials);
  const am::SliceGrid grid = am::slice_grid(model, opts);
  const int total_layers = grid.layers;
  const int in_flight = std::min(resolve_threads(opts.threads), total_layers);
  require_memory(layer_bytes(grid, materials.size()) * in_flight,
                 command + ": " + std::to_string(in_flight) + " layer" + (in_flight == 1 ? "" : "s") + " of " +
                     std::to_string(grid.width) + " x " + std::to_string(grid.height) + " pixels at once (--dpi " +
                     fmt(opts.dpi_x) + "x" + fmt(opts.dpi_y) + ", --threads " + std::to_string(in_flight) + ")");
  OutputFolder out(dir, folder_options);
  std::mutex counts_mutex;
  std::vector<long long> counts(static_cast<std::size_t>(materials.size()), 0);
  const bool tty = ::isatty(fileno(stderr)) != 0;
  std::mutex names_mutex;
  const am::SliceSummary summary = am::slice_model(
      model, opts,
      [&](am::SliceLayer& layer) {
        require(layer.fractions.channels() == materials.size(), [&] {
          return command + ": the cells' material attribute has " + std::to_string(layer.fractions.channels()) +
                 " fractions but the model lists " + std::to_string(materials.size()) + " materials";
        });
        const LabelImage labels = am::dither(layer.fractions, dither);
        std::vector<long long> local(counts.size(), 0);
        for (std::size_t p = 0; p < labels.pixel_count(); ++p)
          if (const int l = labels.data()[p]; l > 0) ++local[static_cast<std::size_t>(l - 1)];
        {
          const std::lock_guard lock(counts_mutex);
          for (std::size_t m = 0; m < counts.size(); ++m) counts[m] += local[m];
        }
        const std::string stem = layer_stem(layer.index, total_layers);
        const auto path = [&](const std::string& name) {
          const std::lock_guard lock(names_mutex);
          return out.path(name).string();
        };
        if (!per_material) {
          io::write_palette_png(path(stem + ".png"), labels, palette);
        } else {
          for (int m = 0; m < materials.size(); ++m)
            io::write_bitmap_png(path(stem + "_" + materials[m].name + ".png"), labels, m + 1);
        }
      },
      [&](int done, int total) {
        if (tty) std::fprintf(stderr, "\rslicing: %d/%d layers%s", done, total, done == total ? "\n" : "");
      });

  nlohmann::json manifest{
      {"trivar", 1},
      {"kind", "slices"},
      {"model", source},
      {"layers", summary.layers},
      {"layer_thickness", opts.layer_thickness},
      {"dpi", {opts.dpi_x, opts.dpi_y}},
      {"pixel_size", {25.4 / opts.dpi_x, 25.4 / opts.dpi_y}},
      {"image_size", {summary.width, summary.height}},
      {"rows", "row 0 of the raster is the lowest y; PNG files show the layer from above, +y up"},
      {"mode", per_material ? "per-material" : "palette"},
      {"dither", method == am::DitherMethod::ordered ? "ordered" : "error-diffusion"},
      {"tracing", am::to_string(opts.tracing)},
      {"files", !per_material ? "layer_NNNNN.png (index 0 empty, index k+1 material k)"
                              : "layer_NNNNN_<material>.png (1-bit, white = material)"},
      {"statistics",
       {{"pixels", summary.pixels},
        {"inside_pixels", summary.inside_pixels},
        {"full_solves", summary.full_solves},
        {"full_solve_percent", summary.full_solve_percent()},
        {"max_residual", summary.max_residual},
        {"seconds", summary.seconds}}}};
  for (int m = 0; m < materials.size(); ++m)
    manifest["materials"].push_back({{"name", materials[m].name},
                                     {"color", hex(materials[m].colour)},
                                     {"palette_index", m + 1},
                                     {"pixels", counts[static_cast<std::size_t>(m)]}});
  write_file_atomically(out.path("manifest.json").string(),
                        [&](std::ostream& os) { os << manifest.dump(2) << '\n'; });
  out.commit();
  return summary;
}

void add_slice_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("slice", "Slice a graded V-model into printer bitmaps: one material per pixel, "
                                          "one palette PNG (or one 1-bit PNG per material) per layer");
  struct Args {
    std::string in, out, dpi = "600", mode = "palette", dither = "error-diffusion", tracing = "full";
    double layer = 0.027;
    std::vector<double> z_range;
    bool force = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("MODEL", a->in, "V-model (.json) or spline file with volumes")->required();
  cmd->add_option("--out", a->out, "Output folder: new, empty, or written by trivar before (see --force)")->required();
  cmd->add_flag("--force", a->force, "Write into a non-empty folder trivar did not write (only trivar's file names are replaced)");
  cmd->add_option("--layer", a->layer, "Layer thickness in model units (mm)")->check(positive())->capture_default_str();
  cmd->add_option("--dpi", a->dpi, "Resolution in dots per inch: X or XxY (e.g. 600x300)")->capture_default_str();
  cmd->add_option("--mode", a->mode, "palette: one indexed PNG per layer (index 0 empty, k+1 material k); "
                                     "per-material: one 1-bit PNG per material and layer")
      ->check(CLI::IsMember({"palette", "per-material"}))
      ->capture_default_str();
  cmd->add_option("--dither", a->dither, "Material choice per pixel: vector error diffusion or ordered (Bayer)")
      ->check(CLI::IsMember({"error-diffusion", "ordered"}))
      ->capture_default_str();
  cmd->add_option("--z-range", a->z_range, "Slice only z0 <= z <= z1")->expected(2);
  cmd->add_option("--tracing", a->tracing, "Start of each pixel's point inversion: none (robust search everywhere), "
                                           "previous-point, previous-line or full")
      ->check(CLI::IsMember({"none", "previous-point", "previous-line", "full"}))
      ->capture_default_str();
  cmd->callback([a, &ctx] {
    const std::array<double, 2> dpi = parse_dpi(a->dpi);
    const VModel model = read_model(a->in, "slice");
    am::SliceOptions opts;
    opts.layer_thickness = a->layer;
    opts.dpi_x = dpi[0];
    opts.dpi_y = dpi[1];
    opts.threads = ctx.threads;
    opts.tracing = am::parse_tracing(a->tracing);
    if (!a->z_range.empty()) {
      require(a->z_range[0] < a->z_range[1], "slice: --z-range must satisfy z0 < z1, got " + fmt(a->z_range[0]) +
                                                 " " + fmt(a->z_range[1]));
      opts.z_range = std::array<double, 2>{a->z_range[0], a->z_range[1]};
    }
    const am::DitherMethod method = a->dither == "ordered" ? am::DitherMethod::ordered : am::DitherMethod::error_diffusion;
    const am::SliceSummary summary =
        slice_to_directory(model, opts, a->out, a->mode == "per-material", method, a->in, {"slice", {a->in}, a->force});
    std::printf("%s\n", am::format_summary(summary).c_str());
    std::printf("output: %s (%d layers, manifest.json)\n", a->out.c_str(), summary.layers);
  });
}

}  // namespace trivar::cli
