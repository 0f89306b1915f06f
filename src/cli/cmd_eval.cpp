// trivar eval FILE u [v [w]] [--derivs K] [--object N]: value and partial derivatives at one parameter (LR
// splines: K <= 1) of the file's single object, or of object N (0-based, as `info` numbers them).
#include <cstdio>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

#include "cli.hpp"
#include "hier_cli.hpp"
#include "lr_cli.hpp"
#include "tspline_cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/derivative_index.hpp"

namespace trivar::cli {

namespace {

// "S", "S_u", "S_uvv", ...: the derivative's multi-index spelled out.
template <int D>
std::string derivative_label(const std::array<int, D>& a) {
  std::string s = "S";
  for (int k = 0; k < D; ++k)
    if (a[k] > 0) {
      if (s.size() == 1) s += '_';
      s.append(static_cast<std::size_t>(a[k]), "uvw"[k]);
    }
  return s;
}

template <template <int> class Spline, int D>
void evaluate(const Spline<D>& s, const std::vector<double>& params, int order) {
  require(static_cast<int>(params.size()) == D, "eval: a " + std::string(kind_name(D)) + " takes " + std::to_string(D) +
                                                    " parameter" + (D > 1 ? "s" : "") + ", got " +
                                                    std::to_string(params.size()));
  const Box<D> dom = s.domain();
  Param<D> u;
  for (int k = 0; k < D; ++k) {
    u[k] = params[k];
    require(u[k] >= dom.lo[k] && u[k] <= dom.hi[k], "eval: parameter " + std::string(1, "uvw"[k]) + " = " +
                                                        fmt(u[k]) + " is outside the domain [" + fmt(dom.lo[k]) +
                                                        ", " + fmt(dom.hi[k]) + "]");
  }
  const auto indices = derivative_multi_indices<D>(order);
  std::vector<double> out(indices.size() * s.dim());
  if constexpr (std::is_same_v<Spline<D>, LRSpline<D>>) {
    require(order <= 1, "eval: LR splines evaluate first derivatives at most (--derivs 0 or 1), got " + std::to_string(order));
    if (order == 0) s.eval(u, out.data());
    else s.eval_first_derivatives(u, out.data());
  } else {
    s.eval_derivs(u, order, out.data());
  }
  std::size_t width = 0;
  for (const auto& a : indices) width = std::max(width, derivative_label<D>(a).size());
  for (std::size_t i = 0; i < indices.size(); ++i) {
    std::string label = derivative_label<D>(indices[i]);
    label.resize(width, ' ');
    std::printf("%s = %s\n", label.c_str(), fmt(out.data() + i * s.dim(), s.dim()).c_str());
  }
}

// Object `index` of `objects` (0-based), or the only one when no index is given.
template <class T>
const T& pick(const std::vector<T>& objects, const std::optional<int>& index, const std::string& file) {
  const std::string count = std::to_string(objects.size()) + " object" + (objects.size() == 1 ? "" : "s");
  if (!index) {
    require(objects.size() == 1, "eval: " + file + " holds " + count + "; choose one with --object N (0 to " +
                                     std::to_string(static_cast<long>(objects.size()) - 1) + ")");
    return objects.front();
  }
  require(*index >= 0 && static_cast<std::size_t>(*index) < objects.size(),
          "eval: --object " + std::to_string(*index) + " is out of range: " + file + " holds " + count +
              (objects.empty() ? "" : ", numbered 0 to " + std::to_string(objects.size() - 1)));
  return objects[static_cast<std::size_t>(*index)];
}

}  // namespace

void add_eval_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("eval", "Evaluate a spline and its partial derivatives at a parameter");
  struct Args {
    std::string file;
    std::vector<double> params;
    int derivs = 0;
    std::optional<int> object;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("FILE", a->file, "Spline file (.json, .g2, .xml, or LR: .lr, .g2, .json)")->required();
  cmd->add_option("PARAMS", a->params, "Parameters u [v [w]], one per parametric direction")->required()->expected(1, 3);
  cmd->add_option("--derivs", a->derivs, "Also print all partial derivatives up to this total order")
      ->check(CLI::Range(0, kMaxDerivativeOrder));
  cmd->add_option("--object", a->object, "Object to evaluate, 0-based as numbered by `info` (default: the only one)");
  cmd->callback([a] {
    if (is_t_spline_file(a->file)) {
      eval_tspline(a->file, a->params, a->derivs);
      return;
    }
    const auto eval = [&](const auto& spline) { evaluate(spline, a->params, a->derivs); };
    if (const auto lr = read_lr_if_any(a->file)) {
      std::visit(eval, pick(*lr, a->object, a->file));
      return;
    }
    if (const auto h = read_hierarchical_if_any(a->file)) {
      std::visit(eval, pick(*h, a->object, a->file));
      return;
    }
    std::visit(eval, pick(read_objects(a->file), a->object, a->file));
  });
}

}  // namespace trivar::cli
