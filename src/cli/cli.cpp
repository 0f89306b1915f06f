#include "cli.hpp"


#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/io/spline_file.hpp"

namespace trivar::cli {

std::vector<AnySpline> read_objects(const std::string& path) { return io::read_spline_file(path); }

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
