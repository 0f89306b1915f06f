// trivar solve poisson|modes [MODEL_OR_SPLINE] [--problem NAME] [--degree p] [--refine N] [--study] [--out DIR]:
// isogeometric analysis on a spline volume (or planar surface) or on a built-in benchmark problem.
#include <cstdio>
#include <filesystem>
#include <string>
#include <variant>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/convergence_table.hpp"
#include "trivar/iga/eigen_modes.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/solution_field.hpp"
#include "trivar/io/vtk_writer.hpp"

namespace trivar::cli {

namespace {

struct SolveArgs {
  std::string kind;
  std::string file;
  std::string problem;
  int degree = 2;
  int refine = 8;
  int modes = 4;
  bool study = false;
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

template <int D>
void run_poisson(const SolveArgs& a, const TensorSpace<D>& space, const PoissonProblem<D>& problem,
                 const ExactSolution<D>* exact, ConvergenceRow& row, Eigen::VectorXd& coefs) {
  auto solver = make_solver(a.solver);
  const SolveResult r = solve_poisson(space, problem, *solver, a.threads);
  coefs = r.coefs;
  row.dofs = r.dofs;
  row.assembly_seconds = r.assembly_seconds;
  row.solve_seconds = r.solve_seconds;
  row.elements = 1;
  for (int k = 0; k < D; ++k) row.elements *= space.geometry.knots(k).num_elements();
  std::string line = "dofs " + std::to_string(r.dofs);
  if (exact) {
    const ErrorNorms e = error_norms<D>(space, r.coefs, 1, *exact, a.threads);
    row.l2 = e.l2;
    row.h1 = e.h1;
    line += ", L2 error " + sci(e.l2) + ", H1 error " + sci(e.h1);
  } else {
    row.l2 = row.h1 = -1;
  }
  line += ", assembly " + secs(r.assembly_seconds) + " s, solve " + secs(r.solve_seconds) + " s";
  if (r.stats.iterations > 0) line += " (" + std::to_string(r.stats.iterations) + " " + a.solver + " iterations)";
  std::printf("%s\n", line.c_str());
}

template <int D>
void poisson_builtin(const SolveArgs& a) {
  std::vector<int> sizes;
  if (a.study) {
    for (int n = 2; n < a.refine; n *= 2) sizes.push_back(n);
  }
  sizes.push_back(a.refine);
  std::vector<ConvergenceRow> rows;
  Eigen::VectorXd coefs;
  PoissonBenchmark<D> last = sine_box<D>(a.degree, sizes.back());
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const PoissonBenchmark<D> b = sine_box<D>(a.degree, sizes[i]);
    ConvergenceRow row;
    row.step = static_cast<int>(i);
    run_poisson(a, b.space, b.problem, &b.exact, row, coefs);
    rows.push_back(row);
  }
  if (a.study)
    for (std::size_t i = 1; i < rows.size(); ++i)
      std::printf("elements %d: L2 rate %.2f, H1 rate %.2f\n", rows[i].elements, observed_rate(rows, i, D, false),
                  observed_rate(rows, i, D, true));
  if (!a.out.empty()) {
    const auto dir = prepare_out(a);
    write_fields<D>(dir / "solution.vtu", last.space, {{"u", solution_field(last.space, coefs, 1)}});
    if (a.study) {
      write_convergence_csv((dir / "convergence.csv").string(), rows, D);
      write_convergence_png((dir / "convergence.png").string(), rows);
    }
  }
}

template <int D>
void poisson_file(const SolveArgs& a) {
  require(!a.study, "solve: --study needs a problem with an exact solution (--problem)");
  const TensorSpace<D> space = space_from_file<D>(a);
  PoissonProblem<D> problem;
  problem.source = [](const double*) { return 1.0; };
  problem.dirichlet.push_back({all_faces<D>(), {}, nullptr});
  ConvergenceRow row;
  Eigen::VectorXd coefs;
  run_poisson<D>(a, space, problem, nullptr, row, coefs);
  if (!a.out.empty())
    write_fields<D>(prepare_out(a) / "solution.vtu", space, {{"u", solution_field(space, coefs, 1)}});
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
  if (a.kind == "poisson") {
    if (a.problem.empty()) {
      if (file_dimension(a) == 3)
        poisson_file<3>(a);
      else
        poisson_file<2>(a);
    } else if (a.problem == "sine-cube") {
      poisson_builtin<3>(a);
    } else if (a.problem == "sine-square") {
      poisson_builtin<2>(a);
    } else {
      throw Error("solve: unknown poisson problem '" + a.problem + "' (expected sine-cube or sine-square)");
    }
    return;
  }
  require(a.modes >= 1, "solve: --modes must be at least 1, got " + std::to_string(a.modes));
  if (a.problem.empty()) {
    if (file_dimension(a) == 3)
      modes<3>(a, space_from_file<3>(a), {});
    else
      modes<2>(a, space_from_file<2>(a), {});
  } else if (a.problem == "cube-modes") {
    Param<3> lo{0, 0, 0}, hi{1, 1, 1};
    modes<3>(a, {box_geometry<3>(lo, hi, a.degree, a.refine)}, unit_box_laplace_eigenvalues(3, a.modes));
  } else {
    throw Error("solve: unknown modes problem '" + a.problem + "' (expected cube-modes)");
  }
}

}  // namespace

void add_solve_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand("solve", "Isogeometric analysis: Poisson problems and Laplace eigenmodes");
  auto a = std::make_shared<SolveArgs>();
  cmd->add_option("KIND", a->kind, "poisson or modes")->required()->check(CLI::IsMember({"poisson", "modes"}));
  cmd->add_option("MODEL_OR_SPLINE", a->file, "Volume, planar surface or single-cell model (.json, .g2)");
  cmd->add_option("--problem", a->problem, "Built-in problem: sine-cube, sine-square (poisson), cube-modes (modes)");
  cmd->add_option("--degree", a->degree, "Spline degree (files: raised to at least this)")->default_val(2);
  cmd->add_option("--refine", a->refine, "Elements per direction (files: parts per element)")->default_val(8);
  cmd->add_option("--modes", a->modes, "Number of eigenmodes")->default_val(4);
  cmd->add_flag("--study", a->study, "Also solve on 2, 4, 8, ... elements per direction and report rates");
  cmd->add_option("--solver", a->solver, "cg, cg-ichol or cholmod")->default_val("cg");
  cmd->add_option("--out", a->out, "Directory for solution.vtu / modes.vtu, convergence.csv and .png");
  cmd->callback([a, &ctx] {
    a->threads = ctx.threads;
    run(*a);
  });
}

}  // namespace trivar::cli
