// trivar solve poisson|elasticity|modes [MODEL_OR_SPLINE] [--problem NAME] [--degree p] [--refine N] [--study]
// [--adaptive --steps K --beta B] [--out DIR]:
// isogeometric analysis on a spline volume (or planar surface) or on a built-in benchmark problem.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>

#include <Eigen/Dense>
#include <string>
#include <variant>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/adaptive_loop.hpp"
#include "trivar/iga/convergence_table.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/eigen_modes.hpp"
#include "trivar/iga/error_indicator.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/lr_poisson.hpp"
#include "trivar/iga/lr_solution_field.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/solution_field.hpp"
#include "trivar/io/lr_vtk.hpp"
#include "trivar/io/vtk_writer.hpp"
#include "trivar/lr/any_lr_spline.hpp"

namespace trivar::cli {

namespace {

struct SolveArgs {
  std::string kind;
  std::string file;
  std::string problem;
  int degree = 2;
  int refine = 8;
  int modes = 4;
  double youngs = 1000.0;
  double poisson = 0.3;
  bool study = false;
  bool adaptive = false;
  int steps = 5;
  double beta = 0.3;
  std::string solver = "cg";
  std::string out;
  int threads = 0;
};

std::string sci(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3e", x);
  return buf;
}

std::string secs(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", x);
  return buf;
}

// The geometry of the input file as a D-dimensional patch, refined to the requested space.
template <int D>
TensorSpace<D> space_from_file(const SolveArgs& a) {
  if (auto model = read_model_if_any(a.file)) {
    require(D == 3 && model->num_cells() == 1,
            "solve: " + a.file + " is a model with " + std::to_string(model->num_cells()) +
                " cells; analysis runs on single-cell models");
    if constexpr (D == 3) return make_tensor_space(model->cell(0).geometry(), a.degree, a.refine);
  }
  const AnySpline s = read_single(a.file, "solve");
  const auto* g = std::get_if<TensorSpline<D>>(&s);
  require(g != nullptr, "solve: " + a.file + " holds a " + kind_name(parametric_dimension(s)) +
                            "; analysis needs a volume or a planar surface");
  return make_tensor_space(*g, a.degree, a.refine);
}

// Dimension of the analysis for a file: 3 for volumes and models, 2 for surfaces.
int file_dimension(const SolveArgs& a) {
  if (read_model_if_any(a.file)) return 3;
  const AnySpline s = read_single(a.file, "solve");
  const int d = parametric_dimension(s);
  require(d >= 2, "solve: " + a.file + " holds a curve; analysis needs a volume or a planar surface");
  return d;
}

std::filesystem::path prepare_out(const SolveArgs& a) {
  std::filesystem::path dir(a.out);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  require(!ec, "solve: cannot create output directory " + a.out + ": " + ec.message());
  return dir;
}

template <int D>
void write_fields(const std::filesystem::path& path, const TensorSpace<D>& space,
                  const std::vector<std::pair<std::string, TensorSpline<D>>>& fields) {
  std::vector<io::VtkPointField> vtk;
  for (const auto& [name, field] : fields)
    vtk.push_back({name, field.dim(), [&f = field](int, std::span<const double> u, std::span<double> out) {
                     Param<D> p;
                     for (int k = 0; k < D; ++k) p[k] = u[static_cast<std::size_t>(k)];
                     f.eval(p, out.data());
                   }});
  io::write_vtu(path.string(), AnySpline(space.geometry), {}, vtk);
}

// One discretisation of a static problem: its space, how to solve it, the exact solution when known.
template <int D>
struct Discretisation {
  TensorSpace<D> space;
  int components = 1;
  std::function<SolveResult(LinearSolver&, int threads)> solve;
  ExactSolution<D> exact;                    // null when unknown
  std::optional<ElasticMaterial> material;   // elasticity: von Mises output
};

// Von Mises stress of a displacement field at a parameter: displacement gradient from the parametric
// derivatives of field and geometry, grad_x u = (du/du) J^{-1}.
template <int D>
double von_mises_at(const TensorSpline<D>& geometry, const TensorSpline<D>& field, const ElasticMaterial& m,
                    const Param<D>& u) {
  double gd[(D + 1) * D], fd[(D + 1) * D];
  geometry.eval_derivs(u, 1, gd);
  field.eval_derivs(u, 1, fd);
  Eigen::Matrix<double, D, D> J, G;
  for (int c = 0; c < D; ++c)
    for (int a = 0; a < D; ++a) {
      J(c, a) = gd[(a + 1) * D + c];
      G(c, a) = fd[(a + 1) * D + c];
    }
  const Eigen::Matrix<double, D, D> grad = G * J.inverse();
  double g[D * D], sigma[D * D];
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) g[i * D + j] = grad(i, j);
  stress<D>(m, g, sigma);
  return von_mises<D>(m, sigma);
}

template <int D>
void write_solution(const std::filesystem::path& path, const Discretisation<D>& d, const Eigen::VectorXd& coefs) {
  const TensorSpline<D> field = solution_field(d.space, coefs, d.components);
  std::vector<io::VtkPointField> vtk;
  auto param = [](std::span<const double> u) {
    Param<D> p;
    for (int k = 0; k < D; ++k) p[k] = u[static_cast<std::size_t>(k)];
    return p;
  };
  vtk.push_back({d.components == 1 ? "u" : "displacement", d.components,
                 [&](int, std::span<const double> u, std::span<double> out) { field.eval(param(u), out.data()); }});
  if (d.material)
    vtk.push_back({"von_mises", 1, [&](int, std::span<const double> u, std::span<double> out) {
                     out[0] = von_mises_at<D>(d.space.geometry, field, *d.material, param(u));
                   }});
  io::write_vtu(path.string(), AnySpline(d.space.geometry), {}, vtk);
}

// Solves on `refine` elements per direction (with --study also on 2, 4, 8, ... below it), prints the summary
// line per solve and the observed rates, then writes the outputs.
template <int D>
void run_static(const SolveArgs& a, const std::function<Discretisation<D>(int)>& make) {
  std::vector<int> sizes;
  if (a.study)
    for (int n = 2; n < a.refine; n *= 2) sizes.push_back(n);
  sizes.push_back(a.refine);
  std::vector<ConvergenceRow> rows;
  Eigen::VectorXd coefs;
  std::optional<Discretisation<D>> last;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    last = make(sizes[i]);
    const Discretisation<D>& d = *last;
    auto solver = make_solver(a.solver);
    const SolveResult r = d.solve(*solver, a.threads);
    coefs = r.coefs;
    ConvergenceRow row;
    row.step = static_cast<int>(i);
    row.dofs = r.dofs;
    row.assembly_seconds = r.assembly_seconds;
    row.solve_seconds = r.solve_seconds;
    row.elements = 1;
    for (int k = 0; k < D; ++k) row.elements *= d.space.geometry.knots(k).num_elements();
    std::string line = "dofs " + std::to_string(r.dofs);
    if (d.exact) {
      const ErrorNorms e = error_norms<D>(d.space, r.coefs, d.components, d.exact, a.threads);
      row.l2 = e.l2;
      row.h1 = e.h1;
      line += ", L2 error " + sci(e.l2) + ", H1 error " + sci(e.h1);
    } else {
      row.l2 = row.h1 = -1;
    }
    line += ", assembly " + secs(r.assembly_seconds) + " s, solve " + secs(r.solve_seconds) + " s";
    if (r.stats.iterations > 0) line += " (" + std::to_string(r.stats.iterations) + " " + a.solver + " iterations)";
    std::printf("%s\n", line.c_str());
    rows.push_back(row);
  }
  for (std::size_t i = 1; i < rows.size(); ++i)
    std::printf("elements %d: L2 rate %.2f, H1 rate %.2f\n", rows[i].elements, observed_rate(rows, i, D, false),
                observed_rate(rows, i, D, true));
  if (!a.out.empty()) {
    const auto dir = prepare_out(a);
    write_solution<D>(dir / "solution.vtu", *last, coefs);
    if (a.study) {
      write_convergence_csv((dir / "convergence.csv").string(), rows, D);
      write_convergence_png((dir / "convergence.png").string(), rows);
    }
  }
}

template <int D>
Discretisation<D> poisson_discretisation(const PoissonBenchmark<D>& b) {
  return {b.space, 1,
          [b](LinearSolver& s, int threads) { return solve_poisson(b.space, b.problem, s, threads); }, b.exact, {}};
}

template <int D>
Discretisation<D> elasticity_discretisation(const ElasticityBenchmark<D>& b) {
  return {b.space, D,
          [b](LinearSolver& s, int threads) { return solve_elasticity(b.space, b.problem, s, threads); }, b.exact,
          b.problem.material};
}

// The LR solution as point field "u" on the final mesh, with the per-element indicator and errors as cell data
// (so ParaView shows where the estimator and the true error disagree).
template <int D>
void write_lr_solution(const std::filesystem::path& path, const LRSpline<D>& lr, const PoissonBenchmark<D>& b,
                       const Eigen::VectorXd& coefs, int threads) {
  const LRSpline<D> field = lr_solution_field(lr, coefs);
  const auto elements = lr_element_bases(lr, threads);
  const std::vector<double> eta = residual_indicators(lr, elements, b.problem, coefs, threads);
  std::vector<double> l2, h1;
  error_norms_per_element(lr, elements, coefs, b.exact, l2, h1, threads);
  auto cell = [](const std::vector<double>& v, bool root) {
    return [&v, root](int, int e, std::span<double> out) {
      out[0] = root ? std::sqrt(v[static_cast<std::size_t>(e)]) : v[static_cast<std::size_t>(e)];
    };
  };
  io::write_lr_vtu(path.string(), AnyLRSpline(lr), {},
                   {{"u", 1,
                     [&](int, std::span<const double> u, std::span<double> out) {
                       Param<D> p;
                       for (int k = 0; k < D; ++k) p[k] = u[static_cast<std::size_t>(k)];
                       field.eval(p, out.data());
                     }}},
                   {{"estimate", 1, cell(eta, false)}, {"error_l2", 1, cell(l2, true)}, {"error_h1", 1, cell(h1, true)}});
}

// Adaptive LR refinement from the problem's tensor space: one line per step, then the table, the mesh and the
// solution.
template <int D>
void run_adaptive(const SolveArgs& a, const PoissonBenchmark<D>& b) {
  require(!a.study, "solve: --study and --adaptive exclude each other");
  LRSpline<D> lr(b.space.geometry);
  AdaptiveOptions o;
  o.steps = a.steps;
  o.beta = a.beta;
  o.solver = a.solver;
  Eigen::VectorXd coefs;
  const auto rows = adaptive_poisson<D>(
      lr, b.problem, b.exact, o,
      [](const ConvergenceRow& r) {
        std::printf("step %d: dofs %d, L2 error %s, H1 error %s, estimate %s, assembly %s s, solve %s s\n", r.step,
                    r.dofs, sci(r.l2).c_str(), sci(r.h1).c_str(), sci(r.estimate).c_str(),
                    secs(r.assembly_seconds).c_str(), secs(r.solve_seconds).c_str());
      },
      &coefs, a.threads);
  if (!a.out.empty()) {
    const auto dir = prepare_out(a);
    write_convergence_csv((dir / "convergence.csv").string(), rows, D);
    write_convergence_png((dir / "convergence.png").string(), rows);
    io::write_lr_vtu((dir / "mesh.vtu").string(), AnyLRSpline(lr));
    write_lr_solution<D>(dir / "solution.vtu", lr, b, coefs, a.threads);
  }
}

// A file: Poisson with f = 1 and u = 0 on the whole boundary; elasticity clamped on the face u = 0 under a
// unit body force along -z (-y in 2-D).
template <int D>
void run_file(const SolveArgs& a) {
  require(!a.study, "solve: --study needs a problem with an exact solution (--problem)");
  const TensorSpace<D> space = space_from_file<D>(a);
  if (a.kind == "poisson") {
    PoissonBenchmark<D> b{space, {}, nullptr};
    b.problem.source = [](const double*) { return 1.0; };
    b.problem.dirichlet.push_back({all_faces<D>(), {}, nullptr});
    run_static<D>(a, [&](int) { return poisson_discretisation(b); });
  } else {
    ElasticityBenchmark<D> b{space, {}, nullptr};
    b.problem.material = {a.youngs, a.poisson};
    b.problem.displacement.push_back({{{0, 0}}, {}, nullptr});
    b.problem.body_force = [](const double*, double* f) {
      for (int k = 0; k < D; ++k) f[k] = k == D - 1 ? -1.0 : 0.0;
    };
    run_static<D>(a, [&](int) { return elasticity_discretisation(b); });
  }
}

template <int D>
void modes(const SolveArgs& a, const TensorSpace<D>& space, const std::vector<double>& exact) {
  const ModesResult r = laplace_modes(space, all_faces<D>(), a.modes, a.threads);
  for (int i = 0; i < a.modes; ++i) {
    std::string line = "mode " + std::to_string(i + 1) + ": lambda " + sci(r.values[i]);
    if (!exact.empty()) {
      const double ex = exact[static_cast<std::size_t>(i)];
      line += " (exact " + sci(ex) + ", relative error " + sci(std::abs(r.values[i] - ex) / ex) + ")";
    }
    std::printf("%s\n", line.c_str());
  }
  std::printf("dofs %d, assembly %s s, solve %s s\n", r.dofs, secs(r.assembly_seconds).c_str(),
              secs(r.solve_seconds).c_str());
  if (!a.out.empty()) {
    std::vector<std::pair<std::string, TensorSpline<D>>> fields;
    for (int i = 0; i < a.modes; ++i)
      fields.emplace_back("mode_" + std::to_string(i + 1), solution_field(space, r.vectors.col(i), 1));
    write_fields<D>(prepare_out(a) / "modes.vtu", space, fields);
  }
}

void run(const SolveArgs& a) {
  require(a.degree >= 1, "solve: --degree must be at least 1, got " + std::to_string(a.degree));
  require(a.refine >= 1, "solve: --refine must be at least 1, got " + std::to_string(a.refine));
  require(a.problem.empty() != a.file.empty(), "solve: give either a model/spline file or --problem NAME");
  if (a.problem.empty()) {
    if (a.kind == "modes") {
      if (file_dimension(a) == 3)
        modes<3>(a, space_from_file<3>(a), {});
      else
        modes<2>(a, space_from_file<2>(a), {});
    } else if (file_dimension(a) == 3) {
      run_file<3>(a);
    } else {
      run_file<2>(a);
    }
    return;
  }
  const std::string& p = a.problem;
  require(!a.adaptive || (a.kind == "poisson" && (p == "l-shape" || p == "sine-square" || p == "sine-cube")),
          "solve: --adaptive is available for the poisson problems l-shape, sine-square and sine-cube");
  if (a.adaptive) {
    if (p == "sine-cube")
      run_adaptive<3>(a, sine_box<3>(a.degree, a.refine));
    else
      run_adaptive<2>(a, p == "l-shape" ? l_shape(a.degree, a.refine) : sine_box<2>(a.degree, a.refine));
  } else if (a.kind == "poisson" && p == "l-shape") {
    run_static<2>(a, [&](int n) { return poisson_discretisation(l_shape(a.degree, n)); });
  } else if (a.kind == "poisson" && p == "sine-cube") {
    run_static<3>(a, [&](int n) { return poisson_discretisation(sine_box<3>(a.degree, n)); });
  } else if (a.kind == "poisson" && p == "sine-square") {
    run_static<2>(a, [&](int n) { return poisson_discretisation(sine_box<2>(a.degree, n)); });
  } else if (a.kind == "elasticity" && p == "lame-cylinder") {
    run_static<3>(a, [&](int n) { return elasticity_discretisation(lame_cylinder<3>(a.degree, n)); });
  } else if (a.kind == "elasticity" && p == "lame-ring") {
    run_static<2>(a, [&](int n) { return elasticity_discretisation(lame_cylinder<2>(a.degree, n)); });
  } else if (a.kind == "elasticity" && p == "plate-hole") {
    run_static<2>(a, [&](int n) { return elasticity_discretisation(plate_with_hole(a.degree, n)); });
  } else if (a.kind == "modes" && p == "cube-modes") {
    require(a.modes >= 1, "solve: --modes must be at least 1, got " + std::to_string(a.modes));
    Param<3> lo{0, 0, 0}, hi{1, 1, 1};
    modes<3>(a, {box_geometry<3>(lo, hi, a.degree, a.refine)}, unit_box_laplace_eigenvalues(3, a.modes));
  } else {
    throw Error("solve: unknown " + a.kind + " problem '" + p +
                "' (poisson: sine-cube, sine-square, l-shape; elasticity: lame-cylinder, lame-ring, plate-hole; modes: cube-modes)");
  }
}

}  // namespace

void add_solve_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("solve", "Isogeometric analysis: Poisson problems and Laplace eigenmodes");
  auto a = std::make_shared<SolveArgs>();
  cmd->add_option("KIND", a->kind, "poisson, elasticity or modes")
      ->required()
      ->check(CLI::IsMember({"poisson", "elasticity", "modes"}));
  cmd->add_option("MODEL_OR_SPLINE", a->file, "Volume, planar surface or single-cell model (.json, .g2)");
  cmd->add_option("--problem", a->problem,
                  "Built-in problem: sine-cube, sine-square, l-shape (poisson), lame-cylinder, lame-ring, plate-hole (elasticity), "
                  "cube-modes (modes)");
  cmd->add_option("--degree", a->degree, "Spline degree (files: raised to at least this)")->default_val(2);
  cmd->add_option("--refine", a->refine, "Elements per direction (files: parts per element)")->default_val(8);
  cmd->add_option("--modes", a->modes, "Number of eigenmodes")->default_val(4);
  cmd->add_option("--youngs", a->youngs, "Young's modulus (elasticity on a file)")->default_val(1000.0);
  cmd->add_option("--poisson-ratio", a->poisson, "Poisson's ratio (elasticity on a file)")->default_val(0.3);
  cmd->add_flag("--study", a->study, "Also solve on 2, 4, 8, ... elements per direction and report rates");
  cmd->add_flag("--adaptive", a->adaptive, "Adaptive LR refinement: solve, estimate, mark (Dorfler), refine");
  cmd->add_option("--steps", a->steps, "Adaptive steps (solves)")->default_val(5);
  cmd->add_option("--beta", a->beta, "Dorfler marking fraction in (0, 1]")->default_val(0.3);
  cmd->add_option("--solver", a->solver, "cg, cg-ichol or cholmod")->default_val("cg");
  cmd->add_option("--out", a->out, "Directory for solution.vtu / modes.vtu, convergence.csv and .png");
  cmd->callback([a, &ctx] {
    a->threads = ctx.threads;
    run(*a);
  });
}

}  // namespace trivar::cli
