// Fixed work for instruction counting (bench/check runs it under callgrind): `bench_kernel_counts KERNEL R`
// prepares the inputs, runs the kernel once to warm caches and lazily built data, then R more times, and
// prints the number of units (points, pixels, functions) one run processes. The difference of the counts for
// two values of R divided by the units is the cost per unit, free of start-up and set-up.
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "bench_volumes.hpp"
#include "lr_diagonal.hpp"
#include "textbook_eval.hpp"
#include "trivar/am/slicer.hpp"
#include "trivar/lr/linear_independence.hpp"
#include "trivar/lr/lr_spline.hpp"
#include "trivar/model/ball.hpp"

using namespace trivar;

namespace {

constexpr std::size_t kPoints = 20000;

// A kernel: set-up done by the factory, the returned function runs the measured work and returns its units.
using Kernel = std::function<double()>;

std::map<std::string, std::function<Kernel()>> kernels() {
  static std::vector<double> out(kPoints * 12);
  return {
      {"spline_value",
       [] {
         return Kernel([s = bench::perturbed_cube(3, 8), u = bench::random_params<3>(kPoints)] {
           s.eval_batch(u, out, 1);
           return static_cast<double>(u.size());
         });
       }},
      {"spline_first",
       [] {
         return Kernel([s = bench::perturbed_cube(3, 8), u = bench::random_params<3>(kPoints)] {
           s.eval_derivs_batch(u, 1, out, 1);
           return static_cast<double>(u.size());
         });
       }},
      {"spline_grid",
       [] {
         std::array<std::vector<double>, 3> g;
         for (int k = 0; k < 3; ++k)
           for (int i = 0; i < 20 + 5 * (k / 2); ++i) g[k].push_back(i / (19.0 + 5 * (k / 2)));
         return Kernel([s = bench::perturbed_cube(3, 8), g] {
           s.eval_grid(g, out, 1);
           return static_cast<double>(g[0].size() * g[1].size() * g[2].size());
         });
       }},
      {"textbook_value",
       [] {
         const auto s = bench::perturbed_cube(3, 8);
         std::array<std::vector<double>, 3> t;
         for (int k = 0; k < 3; ++k) t[k] = s.knots(k).knots();
         bench::TextbookVolume tb(3, t, {s.coefs().begin(), s.coefs().end()});
         return Kernel([tb, u = bench::random_params<3>(kPoints)] {
           for (std::size_t i = 0; i < u.size(); ++i) tb.eval(u[i], out.data() + 3 * i);
           return static_cast<double>(u.size());
         });
       }},
      {"lr_value",
       [] {
         return Kernel([lr = LRSpline<3>(bench::perturbed_cube(3, 8)), u = bench::random_params<3>(kPoints)] {
           lr.eval_many(u, out, 1);
           return static_cast<double>(u.size());
         });
       }},
      {"lr_first",
       [] {
         return Kernel([lr = LRSpline<3>(bench::perturbed_cube(3, 8)), u = bench::random_params<3>(kPoints)] {
           lr.eval_first_derivatives_many(u, out, 1);
           return static_cast<double>(u.size());
         });
       }},
      {"lr_refine",
       [] {
         // Cubic 8^3, two FULLSPAN levels along the diagonal; units: the B-splines of the result.
         return Kernel([] {
           auto lr = bench::unit_lr<3>(8);
           for (int level = 0; level < 2; ++level) bench::refine_diagonal(lr, Strategy::fullspan);
           return static_cast<double>(lr.num_basis());
         });
       }},
      {"lr_peeling",
       [] {
         auto lr = bench::unit_lr<3>(8);
         for (int level = 0; level < 3; ++level) bench::refine_diagonal(lr, Strategy::fullspan);
         return Kernel([lr = std::move(lr)] {
           const PeelingResult r = peeling_test(lr);
           return static_cast<double>(lr.num_basis()) + 0.0 * r.overloaded_elements;
         });
       }},
      {"slicer_ball",
       [] {
         // A 400 x 200 pixel window at the middle of the ball of radius 20 at 600 x 300 dpi: every pixel inside.
         VModel v;
         for (const auto& c : make_ball({.radius = 20})) {
           VCell cell(c);
           cell.set_attribute("material", Attribute::expression({"1 - min(1, sqrt(x*x + y*y + z*z) / 20)",
                                                                 "min(1, sqrt(x*x + y*y + z*z) / 20)"},
                                                                Attribute::Space::model));
           v.add_cell(std::move(cell));
         }
         v.glue();
         am::SliceOptions o;
         o.dpi_x = 600;
         o.dpi_y = 300;
         o.image_size = {{400, 200}};
         o.origin = {{-200 * 25.4 / 600, -100 * 25.4 / 300}};
         o.z_range = {{0.3, 0.3 + o.layer_thickness}};
         o.threads = 1;
         return Kernel([v = std::move(v), o] {
           return static_cast<double>(am::slice_model(v, o, am::LayerConsumer{}).inside_pixels);
         });
       }},
  };
}

}  // namespace

int main(int argc, char** argv) {
  const auto all = kernels();
  if (argc != 3 || !all.count(argv[1])) {
    std::fprintf(stderr, "usage: bench_kernel_counts KERNEL REPEATS; kernels:");
    for (const auto& [name, make] : all) std::fprintf(stderr, " %s", name.c_str());
    std::fprintf(stderr, "\n");
    return 2;
  }
  const Kernel run = all.at(argv[1])();
  const double units = run();
  for (int r = std::atoi(argv[2]); r > 0; --r) run();
  std::printf("units %.0f\n", units);
  return 0;
}
