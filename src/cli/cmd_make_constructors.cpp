// trivar make extrude|ruled|loft|coons|sweep|morph ... -o FILE: volumes (or surfaces) built from input splines.
#include <array>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/model/coons.hpp"
#include "trivar/model/extrude.hpp"
#include "trivar/model/loft.hpp"
#include "trivar/model/metamorphosis.hpp"
#include "trivar/model/ruled.hpp"
#include "trivar/model/sweep.hpp"

namespace trivar::cli {

namespace {

// The objects of all files, in order.
std::vector<AnySpline> read_all(const std::vector<std::string>& paths) {
  std::vector<AnySpline> all;
  for (const std::string& p : paths)
    for (AnySpline& s : read_objects(p)) all.push_back(std::move(s));
  return all;
}

// Inputs of a constructor must all be curves or all be surfaces: the result is one dimension higher.
int common_dimension(const std::vector<AnySpline>& inputs, const std::string& command) {
  require(!inputs.empty(), command + ": no input objects");
  const int d = parametric_dimension(inputs.front());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const int di = parametric_dimension(inputs[i]);
    require(di == d, [&] {
      return command + ": input object " + std::to_string(i) + " is a " + kind_name(di) + " but object 0 is a " +
             kind_name(d) + "; all inputs must be of one kind";
    });
  }
  require(d <= 2, command + ": inputs must be curves or surfaces, got volumes");
  return d;
}

template <int D>
std::vector<TensorSpline<D>> as(const std::vector<AnySpline>& inputs) {
  std::vector<TensorSpline<D>> r;
  for (const AnySpline& s : inputs) r.push_back(std::get<TensorSpline<D>>(s));
  return r;
}

void add_extrude(CLI::App& make) {
  auto* cmd = make.add_subcommand("extrude", "Extrude a curve into a surface or a surface into a volume, along "
                                             "a vector (--direction) or a path curve (--path)");
  struct Args {
    std::string input, path, out;
    std::vector<double> direction;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("INPUT", a->input, "File with the curve or surface to extrude")->required();
  auto* dir = cmd->add_option("--direction", a->direction, "Extrusion vector, one value per control coordinate");
  auto* path = cmd->add_option("--path", a->path, "File with the path curve: the input slides along it");
  dir->excludes(path);
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2)")->required();
  cmd->callback([a] {
    require(!a->direction.empty() || !a->path.empty(), "make extrude: give --direction or --path");
    const std::vector<AnySpline> in{read_single(a->input, "make extrude")};
    const int d = common_dimension(in, "make extrude");
    AnySpline result;
    if (!a->path.empty()) {
      const AnySpline p = read_single(a->path, "make extrude");
      require(parametric_dimension(p) == 1, "make extrude: --path " + a->path + " must hold a curve");
      const auto& curve = std::get<TensorSpline<1>>(p);
      result = d == 1 ? AnySpline(extrude_along<2>(as<1>(in)[0], curve))
                      : AnySpline(extrude_along<3>(as<2>(in)[0], curve));
    } else {
      const Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(a->direction.data(),
                                                                  static_cast<Eigen::Index>(a->direction.size()));
      result = d == 1 ? AnySpline(extrude<2>(as<1>(in)[0], v)) : AnySpline(extrude<3>(as<2>(in)[0], v));
    }
    io::write_spline_file(a->out, {result});
  });
}

void add_ruled(CLI::App& make) {
  auto* cmd = make.add_subcommand("ruled", "Ruled surface between two curves or ruled volume between two surfaces "
                                           "(made compatible by degree elevation and knot merging)");
  struct Args {
    std::vector<std::string> inputs;
    std::string out;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("INPUTS", a->inputs, "Two files with one object each, or one file with two objects")
      ->required()
      ->expected(1, 2);
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2)")->required();
  cmd->callback([a] {
    const std::vector<AnySpline> in = read_all(a->inputs);
    require(in.size() == 2, "make ruled: needs exactly 2 input objects, got " + std::to_string(in.size()));
    const int d = common_dimension(in, "make ruled");
    const AnySpline result = d == 1 ? AnySpline(ruled<2>(as<1>(in)[0], as<1>(in)[1]))
                                    : AnySpline(ruled<3>(as<2>(in)[0], as<2>(in)[1]));
    io::write_spline_file(a->out, {result});
  });
}

void add_loft(CLI::App& make) {
  auto* cmd = make.add_subcommand("loft", "Spline surface through a sequence of curves, or volume through a "
                                          "sequence of surfaces");
  struct Args {
    std::vector<std::string> inputs;
    std::vector<double> params;
    int degree = 3;
    std::string out;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("INPUTS", a->inputs, "Files with the sections, in order (a file may hold several)")->required();
  cmd->add_option("--degree", a->degree, "Degree across the sections (lowered to sections - 1 when fewer)")
      ->check(at_least(1))
      ->capture_default_str();
  cmd->add_option("--params", a->params, "Section parameters, increasing from 0 to 1 (default: chord length)");
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2)")->required();
  cmd->callback([a] {
    const std::vector<AnySpline> in = read_all(a->inputs);
    require(in.size() >= 2, "make loft: needs at least 2 sections, got " + std::to_string(in.size()));
    const int d = common_dimension(in, "make loft");
    const int degree = std::min(a->degree, static_cast<int>(in.size()) - 1);
    auto build = [&]<int K>(std::integral_constant<int, K>) {
      return a->params.empty() ? AnySpline(loft<K + 1>(as<K>(in), degree))
                               : AnySpline(loft<K + 1>(as<K>(in), a->params, degree));
    };
    const AnySpline result = d == 1 ? build(std::integral_constant<int, 1>{}) : build(std::integral_constant<int, 2>{});
    io::write_spline_file(a->out, {result});
  });
}

void add_coons(CLI::App& make) {
  auto* cmd = make.add_subcommand("coons", "Boolean-sum (Coons) volume from six boundary surfaces in the order "
                                           "u=0, u=1, v=0, v=1, w=0, w=1");
  struct Args {
    std::vector<std::string> inputs;
    double tolerance = 1e-9;
    std::string out;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("FACES", a->inputs, "Six files with one surface each, or one file with six surfaces")->required();
  cmd->add_option("--tolerance", a->tolerance, "Largest mismatch of shared edges")
      ->check(positive())
      ->capture_default_str();
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2)")->required();
  cmd->callback([a] {
    const std::vector<AnySpline> in = read_all(a->inputs);
    require(in.size() == 6, "make coons: needs exactly 6 faces, got " + std::to_string(in.size()));
    require(common_dimension(in, "make coons") == 2, "make coons: the faces must be surfaces");
    const std::vector<TensorSpline<2>> f = as<2>(in);
    io::write_spline_file(a->out, {AnySpline(coons_volume({f[0], f[1], f[2], f[3], f[4], f[5]}, a->tolerance))});
  });
}

void add_sweep(CLI::App& make) {
  auto* cmd = make.add_subcommand("sweep", "Sweep a surface along a path curve with a rotation-minimising frame "
                                           "(approximate; prints the error bound)");
  struct Args {
    std::string profile, path, out;
    SweepOptions opts;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("PROFILE", a->profile, "File with the surface, placed at the start of the path")->required();
  cmd->add_option("PATH", a->path, "File with the path curve")->required();
  cmd->add_option("--sections", a->opts.sections, "Minimum number of elements along the path")
      ->check(at_least(1))
      ->capture_default_str();
  cmd->add_option("--degree", a->opts.degree, "Degree along the path")->check(at_least(1))->capture_default_str();
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2)")->required();
  cmd->callback([a] {
    const AnySpline profile = read_single(a->profile, "make sweep"), path = read_single(a->path, "make sweep");
    require(parametric_dimension(profile) == 2, "make sweep: " + a->profile + " must hold a surface");
    require(parametric_dimension(path) == 1, "make sweep: " + a->path + " must hold a curve");
    const SweepResult r = sweep(std::get<TensorSpline<2>>(profile), std::get<TensorSpline<1>>(path), a->opts);
    io::write_spline_file(a->out, {AnySpline(r.volume)});
    std::printf("max error %s\n", fmt(r.max_error).c_str());
  });
}

void add_morph(CLI::App& make) {
  auto* cmd = make.add_subcommand("morph", "Metamorphosis between two surfaces: a volume whose w = 0 and w = 1 "
                                           "faces are the inputs, with a smooth time blend");
  struct Args {
    std::vector<std::string> inputs;
    int smoothness = 0;
    std::string out;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("INPUTS", a->inputs, "Two files with one surface each, or one file with two")->required()->expected(1, 2);
  cmd->add_option("--smoothness", a->smoothness, "Vanishing time derivatives at both ends (0: linear, i.e. ruled)")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2)")->required();
  cmd->callback([a] {
    const std::vector<AnySpline> in = read_all(a->inputs);
    require(in.size() == 2, "make morph: needs exactly 2 surfaces, got " + std::to_string(in.size()));
    require(common_dimension(in, "make morph") == 2, "make morph: the inputs must be surfaces");
    io::write_spline_file(a->out, {AnySpline(metamorphosis(as<2>(in)[0], as<2>(in)[1], a->smoothness))});
  });
}

}  // namespace

void add_make_constructors(CLI::App& make) {
  add_extrude(make);
  add_ruled(make);
  add_loft(make);
  add_coons(make);
  add_sweep(make);
  add_morph(make);
}

}  // namespace trivar::cli
