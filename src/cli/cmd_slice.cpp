// trivar slice MODEL --out DIR [--layer t] [--dpi X[xY]] [--mode palette|per-material]
// [--dither error-diffusion|ordered] [--z-range z0 z1] [--tracing none|previous-point|previous-line|full]: printer bitmaps of a graded V-model, one material per
// pixel, with a JSON manifest. The images are written to a temporary directory renamed to DIR at the end, so
// a failed run leaves no partial output.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "trivar/am/dithering.hpp"
#include "trivar/am/layer_slicer.hpp"
#include "trivar/am/slicer.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/png_writer.hpp"

namespace trivar::cli {

namespace {

namespace fs = std::filesystem;

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

}  // namespace

am::SliceSummary slice_to_directory(const VModel& model, const am::SliceOptions& opts, const std::string& dir,
                                    bool per_material, am::DitherMethod method, const std::string& source) {
  require(!model.materials().empty(), "slice: " + source + " has no materials (build it with --materials or "
                                      "--material-field, or list \"materials\" in the model file)");
  const MaterialTable& materials = model.materials();
  const am::DitherOptions dither{method};
  const std::vector<Rgba> palette = io::material_palette(materials);
  const int total_layers = am::slice_grid(model, opts).layers;
  // Everything goes to a sibling temporary directory first.
  const fs::path out = fs::absolute(dir);
  const fs::path tmp = out.parent_path() / (out.filename().string() + ".partial-" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  try {
    std::mutex counts_mutex;
    std::vector<long long> counts(static_cast<std::size_t>(materials.size()), 0);
    const bool tty = ::isatty(fileno(stderr)) != 0;
    const am::SliceSummary summary = am::slice_model(
        model, opts,
        [&](am::SliceLayer& layer) {
          require(layer.fractions.channels() == materials.size(), [&] {
            return "slice: the cells' material attribute has " + std::to_string(layer.fractions.channels()) +
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
          const std::string stem = (tmp / layer_stem(layer.index, total_layers)).string();
          if (!per_material) {
            io::write_palette_png(stem + ".png", labels, palette);
          } else {
            for (int m = 0; m < materials.size(); ++m)
              io::write_bitmap_png(stem + "_" + materials[m].name + ".png", labels, m + 1);
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
    std::ofstream(tmp / "manifest.json") << manifest.dump(2) << '\n';
    fs::remove_all(out);
    fs::rename(tmp, out);
    return summary;
  } catch (...) {
    fs::remove_all(tmp);
    throw;
  }
}

void add_slice_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("slice", "Slice a graded V-model into printer bitmaps: one material per pixel, "
                                          "one palette PNG (or one 1-bit PNG per material) per layer");
  struct Args {
    std::string in, out, dpi = "600", mode = "palette", dither = "error-diffusion", tracing = "full";
    double layer = 0.027;
    std::vector<double> z_range;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("MODEL", a->in, "V-model (.json) or spline file with volumes")->required();
  cmd->add_option("--out", a->out, "Output directory (replaced when it exists)")->required();
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
        slice_to_directory(model, opts, a->out, a->mode == "per-material", method, a->in);
    std::printf("%s\n", am::format_summary(summary).c_str());
    std::printf("output: %s (%d layers, manifest.json)\n", a->out.c_str(), summary.layers);
  });
}

}  // namespace trivar::cli
