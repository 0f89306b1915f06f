#include "cli.hpp"


#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/io/json_format.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/vmodel_json.hpp"

namespace trivar::cli {

bool is_step_file(const std::string& path) { return io::format_of(path) == io::FileFormat::step; }

std::vector<AnySpline> read_objects(const std::string& path) { return io::read_spline_file(path); }

std::optional<VModel> read_model_if_any(const std::string& path) {
  if (io::file_extension(path) != ".json") return std::nullopt;
  const nlohmann::json doc = io::read_json_document(path);
  if (!io::is_vmodel_json(doc)) return std::nullopt;
  return io::vmodel_from_json(doc, path);
}

VModel read_model(const std::string& path, const std::string& command) {
  if (std::optional<VModel> m = read_model_if_any(path)) return std::move(*m);
  VModel m;
  for (const AnySpline& s : read_objects(path)) {
    require(parametric_dimension(s) == 3, [&] {
      return command + ": " + path + " holds a " + kind_name(parametric_dimension(s)) + "; only V-models and volumes have an inside";
    });
    m.add_cell(VCell(std::get<TensorSpline<3>>(s)));
  }
  m.glue();
  return m;
}

MaterialTable materials_or_default(const VModel& m) {
  return m.materials().empty() ? MaterialTable({{"part", {200, 200, 200, 255}}}) : m.materials();
}

AnySpline read_single(const std::string& path, const std::string& command) {
  std::vector<AnySpline> objects = read_objects(path);
  require(objects.size() == 1, command + ": " + path + " holds " + std::to_string(objects.size()) +
                                   " objects; this command takes a file with exactly one");
  return std::move(objects.front());
}

namespace {

CLI::Validator number_check(const std::string& description, bool (*ok)(double, double), double bound) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double x = 0;
        if (!CLI::detail::lexical_cast(text, x)) return "'" + text + "' is not a number";
        return ok(x, bound) ? std::string() : "must be " + description + ", got " + text;
      },
      description);
}

}  // namespace

CLI::Validator at_least(double min) {
  return number_check(">= " + fmt(min), [](double x, double b) { return x >= b; }, min);
}

CLI::Validator positive() {
  return number_check("> 0", [](double x, double b) { return x > b; }, 0.0);
}

const char* kind_name(int parametric_dim) {
  switch (parametric_dim) {
    case 1: return "curve";
    case 2: return "surface";
    default: return "volume";
  }
}

std::string fmt(double x) { return format_number(x); }

std::string fmt(const double* x, int n, const char* sep) {
  std::string s;
  for (int i = 0; i < n; ++i) {
    if (i) s += sep;
    s += fmt(x[i]);
  }
  return s;
}

}  // namespace trivar::cli
