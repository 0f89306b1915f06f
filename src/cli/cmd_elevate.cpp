// trivar elevate FILE --by T -o OUT: p-refinement (degree elevation, geometry unchanged).
#include <string>
#include <variant>
#include <vector>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/spline/degree_elevation.hpp"

namespace trivar::cli {

void add_elevate_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("elevate", "Raise the polynomial degree (geometry unchanged)");
  struct Args {
    std::string in, out;
    std::vector<int> by{1};
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("FILE", a->in, "Input spline file (.json, .g2)")->required();
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2)")->required();
  cmd->add_option("--by", a->by, "Degrees to add: one value for every direction, or one per direction")
      ->expected(1, 3)
      ->check(at_least(0))
      ->capture_default_str();
  cmd->callback([a] {
    std::vector<AnySpline> objects = read_objects(a->in);
    for (AnySpline& o : objects)
      o = std::visit(
          [&](const auto& s) {
            constexpr int D = std::decay_t<decltype(s)>::kDim;
            const int n = static_cast<int>(a->by.size());
            require(n == 1 || n == D, "elevate: --by takes 1 or " + std::to_string(D) + " values for a " + kind_name(D) +
                                          ", got " + std::to_string(n));
            Ints<D> by;
            for (int k = 0; k < D; ++k) by[k] = a->by[n == 1 ? 0 : k];
            return AnySpline(elevate_degree(s, by));
          },
          o);
    io::write_spline_file(a->out, objects);
  });
}

}  // namespace trivar::cli
