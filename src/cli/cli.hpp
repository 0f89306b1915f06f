#pragma once
// Shared vocabulary of the `trivar` command-line tool: exit codes, the run context every subcommand
// writes its result into, file helpers and number formatting. One file per subcommand registers itself
// through the add_*_command functions declared here.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <optional>

#include "trivar/am/dithering.hpp"
#include "trivar/am/slicer.hpp"
#include "trivar/core/output_folder.hpp"
#include "trivar/model/vmodel.hpp"
#include "trivar/spline/any_spline.hpp"

namespace trivar::cli {

// Documented in docs/cli.md; scripts rely on them.
enum ExitCode : int {
  kSuccess = 0,
  kBadInput = 1,   // trivar::Error or another exception: bad file, bad parameter, I/O failure
  kUsage = 2,      // command line could not be parsed
  kInvalid = 3,    // check: the Jacobian determinant is proven to change sign or vanish
  kOutside = 4,    // invert: the point is not in the image of the domain
  kUndecided = 5,  // check: neither proven valid nor invalid; invert: inside but Newton did not converge
};

struct Context {
  int threads = 0;  // --threads; 0 means all available
  int exit_code = kSuccess;
};

void add_info_command(CLI::App& app, Context& ctx);
void add_eval_command(CLI::App& app, Context& ctx);
void add_convert_command(CLI::App& app, Context& ctx);
void add_refine_command(CLI::App& app, Context& ctx);
void add_elevate_command(CLI::App& app, Context& ctx);
void add_check_command(CLI::App& app, Context& ctx);
void add_make_command(CLI::App& app, Context& ctx);
// make extrude|ruled|loft|coons: constructors from input splines, registered under `make`.
void add_make_constructors(CLI::App& make);
// make ball|cylinder|cone|torus: V-model primitives, registered under `make`.
void add_make_primitives(CLI::App& make);

// Material options of commands that write V-models: --materials m [--blend radial|axial] gives every cell an
// attribute "material" of m fractions blending linearly between m stations of a normalised coordinate;
// --material-field takes the fractions as formulas in x, y, z.
struct MaterialArgs {
  int materials = 0;
  std::string blend = "radial";
  std::vector<std::string> field;
};
void add_material_options(CLI::App* cmd, MaterialArgs& a, const char* axial_meaning);
// m formulas blending linearly between m equally spaced stations of rho (a formula in [0, 1]): the degree-1
// B-splines on those stations, a partition of unity with material i pure at rho = i / (m - 1).
std::vector<std::string> blend_components(int m, const std::string& rho);
// Materials "M1".."Mm" with distinct display colours.
MaterialTable default_materials(int m);
// Glues the cells into a V-model with the material attribute and writes it. `radial` and `axial` are the
// normalised coordinates (formulas in x, y, z, 0 to 1 across the part) the blend follows.
void write_model(const std::vector<TensorSpline<3>>& cells, const MaterialArgs& a, const std::string& radial,
                 const std::string& axial, const std::string& out);
void write_model(std::vector<VCell> cells, const MaterialArgs& a, const std::string& radial, const std::string& axial,
                 const std::string& out);
// make vmodel PART.stp: trimmed V-models of the solids of a STEP file.
void add_make_vmodel(CLI::App& make);
// info on a STEP file: the B-rep as the geometry kernel reads it (solids, shells, faces by surface kind, what
// is not a solid, faces that cannot be mapped); text or JSON.
// kernel_volume: also OpenCASCADE's own volume of each solid (`info --kernel-volume`).
void print_brep_info(const std::string& file, bool kernel_volume);
nlohmann::json brep_info_json(const std::string& file, bool kernel_volume);
void add_invert_command(CLI::App& app, Context& ctx);
void add_export_command(CLI::App& app, Context& ctx);
void add_slice_command(CLI::App& app, Context& ctx);
void add_demo_command(CLI::App& app, Context& ctx);
void add_solve_command(CLI::App& app, Context& ctx);
// fit POINTS: an LR spline approximating scattered data (cmd_fit.cpp).
void add_fit_command(CLI::App& app, Context& ctx);
// stitch A B [C ...]: surfaces sharing sides joined C0 or C1 (cmd_stitch.cpp).
void add_stitch_command(CLI::App& app, Context& ctx);
void add_boolean_command(CLI::App& app, Context& ctx);

// True for ISO 10303-21 files: .stp, .step, .p21 (case-insensitive).
bool is_step_file(const std::string& path);
// All objects of a spline file (.json, .g2); throws trivar::Error naming the file on any problem.
std::vector<AnySpline> read_objects(const std::string& path);
// The V-model in a .json file whose "kind" is "vmodel" (glued), or nothing for any other file; throws
// trivar::Error naming the file when it is a malformed model.
std::optional<VModel> read_model_if_any(const std::string& path);
// The V-model in `path`, or the volumes of a spline file glued into one (each a cell); throws trivar::Error
// naming `command` when the file holds curves or surfaces.
VModel read_model(const std::string& path, const std::string& command);
// The model's materials, or one neutral material "part" when it has none.
MaterialTable materials_or_default(const VModel& m);
// Slices a model with materials into the output folder DIR (trivar/core/output_folder.hpp: a fresh folder, one
// trivar wrote before, or with `folder.force` any folder; only trivar's file names are ever replaced): per layer
// a palette PNG (or one 1-bit PNG per material) of the dithered materials, and manifest.json. `source` names the
// model in the manifest. Throws trivar::Error "<folder.command>: ..." for a model without materials, a z range
// outside the model, more memory than available, or bad options.
am::SliceSummary slice_to_directory(const VModel& model, const am::SliceOptions& opts, const std::string& dir,
                                    bool per_material, am::DitherMethod method, const std::string& source,
                                    const OutputFolderOptions& folder);
// Prints a V-model's description (text, or one JSON document).
void print_model_info(const std::string& path, const VModel& model, bool json);

// The single object of a file, for commands that act on one spline.
AnySpline read_single(const std::string& path, const std::string& command);

// Option checks with one-line messages: a number >= min, or > 0.
CLI::Validator at_least(double min);
CLI::Validator positive();

// "curve", "surface", "volume".
const char* kind_name(int parametric_dim);
// Shortest text that parses back to the same double.
std::string fmt(double x);
// Values joined by `sep`.
std::string fmt(const double* x, int n, const char* sep = " ");

}  // namespace trivar::cli
