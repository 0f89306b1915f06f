// trivar solve poisson|elasticity|modes [MODEL_OR_SPLINE] [--problem NAME] [--degree p] [--refine N] [--study]
// [--adaptive --steps K --beta B] [--out DIR]:
// isogeometric analysis on a spline volume (or planar surface) or on a built-in benchmark problem.
#include <chrono>
#include <cstdio>
#include <memory>
#include <filesystem>
#include <functional>
#include <optional>

#include <Eigen/Dense>
#include <string>
#include <variant>

#include "cli.hpp"
#include "hier_cli.hpp"
#include "lr_cli.hpp"
#include "multiblock_cli.hpp"
#include "tspline_cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/adaptive_loop.hpp"
#include "trivar/iga/cell_materials.hpp"
#include "trivar/iga/side_faces.hpp"
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/convergence_table.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/eigen_modes.hpp"
#include "trivar/iga/error_indicator.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/refined_quadrature.hpp"
#include "trivar/iga/refined_elasticity.hpp"
#include "trivar/iga/refined_field.hpp"
#include "trivar/iga/refined_modes.hpp"
#include "trivar/iga/refined_space.hpp"
#include "trivar/cad/trimmed_form.hpp"
#include "trivar/iga/trimmed_model_space.hpp"
#include "trivar/iga/lr_solution_field.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/solution_field.hpp"
#include "trivar/iga_petsc/parallel_vtk.hpp"
#include "trivar/iga_petsc/petsc_problems.hpp"
#include "trivar/iga_petsc/petsc_session.hpp"
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
  double density = 1.0;
  std::string clamp = "x-";
  std::string physics = "elastic";
  bool study = false;
  bool adaptive = false;
  std::string space = "lr";
  int steps = 5;
  double beta = 0.3;
  int admissible = 0;
  std::string solver = "cg";
  std::string backend = "serial";
  std::string pc = "gamg";
  std::string out;
  bool force = false;
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

bool distributed(const SolveArgs& a) { return a.backend == "petsc"; }

// One thread per rank unless --threads says otherwise: mpirun starts a rank per core.
PetscSolverOptions petsc_options(const SolveArgs& a) {
  PetscSolverOptions o;
  o.preconditioner = a.pc;
  o.threads = a.threads == 0 ? 1 : a.threads;
  return o;
}

// The ranks, the processor time of the phases and the peak resident memory of each rank (collective).
void print_ranks() {
  const std::vector<double> peak = peak_memory_per_rank();
  const PhaseCpuSeconds& cpu = last_phase_cpu_seconds();
  std::string line = "ranks " + std::to_string(peak.size()) + ", CPU per rank (slowest): assembly " + secs(cpu.assembly) +
                     " s, solve " + secs(cpu.solve) + " s, peak memory per rank (MB):";
  for (double b : peak) line += " " + std::to_string(static_cast<long>(b / 1e6));
  std::printf("%s\n", line.c_str());
}

std::string solver_name(const SolveArgs& a) { return distributed(a) ? "cg+" + a.pc : a.solver; }

// The input file, read (and a model glued) once: a V-model, a single spline, or several blocks (a multi-block
// model).
struct FileInput {
  std::optional<VModel> model;
  std::optional<AnySpline> spline;
  std::vector<AnySpline> blocks;
  int dimension() const { return model ? 3 : parametric_dimension(*spline); }
};

FileInput read_input(const SolveArgs& a) {
  FileInput in;
  in.model = read_model_if_any(a.file);
  if (in.model) {
    if (!in.model->is_glued()) in.model->glue();
    return in;
  }
  std::vector<AnySpline> objects = read_objects(a.file);
  if (objects.size() > 1) {
    in.blocks = std::move(objects);
    return in;
  }
  require(objects.size() == 1, "solve: " + a.file + " holds no objects");
  in.spline = std::move(objects.front());
  require(in.dimension() >= 2, "solve: " + a.file + " holds a curve; analysis needs a volume or a planar surface");
  return in;
}

// The analysis space of an input file: a model's cells as a multipatch space (with their material
// attributes), or a volume / planar surface as one patch, refined to the requested space.
template <int D>
struct FileSpace {
  MultipatchSpace<D> space;
  std::function<ElasticMaterial(int, const double*)> material_at;  // null for a spline file
};

template <int D>
FileSpace<D> space_from_file(const SolveArgs& a, const FileInput& in) {
  FileSpace<D> f;
  if constexpr (D == 3) {
    if (in.model) {
      f.space = multipatch_space(*in.model, a.degree, a.refine);
      f.material_at = cell_materials(*in.model, {a.youngs, a.poisson, a.density});
      return f;
    }
  }
  const auto* g = std::get_if<TensorSpline<D>>(&*in.spline);
  require(g != nullptr, "solve: " + a.file + " holds a " + kind_name(in.dimension()) +
                            "; analysis needs a volume or a planar surface");
  f.space = single_patch_space(make_tensor_space(*g, a.degree, a.refine));
  return f;
}

// The supports of --clamp (iga/side_faces.hpp), with the option named in messages.
template <int D>
std::vector<Face> faces_on_side(const MultipatchSpace<D>& space, const std::string& side) {
  try {
    return faces_in_side_plane(space, side);
  } catch (const Error& e) {
    throw Error(std::string("solve: --") + e.what());
  }
}

// The --out folder, under the rules of trivar/core/output_folder.hpp; files are staged until commit().
OutputFolderOptions out_options(const SolveArgs& a) {
  std::vector<std::string> inputs;
  if (!a.file.empty()) inputs.push_back(a.file);
  return {"solve", inputs, a.force};
}

std::unique_ptr<OutputFolder> prepare_out(const SolveArgs& a) {
  return std::make_unique<OutputFolder>(a.out, out_options(a));
}

// Pieces of a VTU file, one per patch.
template <int D>
std::vector<AnySpline> patch_pieces(const MultipatchSpace<D>& space) {
  std::vector<AnySpline> pieces;
  for (const auto& p : space.patches) pieces.emplace_back(p.geometry);
  return pieces;
}

// A field given per patch as a spline over the patch's parameters.
template <int D>
io::VtkPointField spline_field(const std::string& name, const std::vector<TensorSpline<D>>& per_patch) {
  return {name, per_patch.front().dim(), [&per_patch](int piece, std::span<const double> u, std::span<double> out) {
            per_patch[static_cast<std::size_t>(piece)].eval(io::param_of<D>(u), out.data());
          }};
}

// One discretisation of a static problem: its space, how to solve it, the exact solution when known.
template <int D>
struct Discretisation {
  MultipatchSpace<D> space;
  int components = 1;
  std::function<SolveResult(const SolveArgs&)> solve;
  ExactSolution<D> exact;  // null when unknown
  // Elasticity: the material of a patch at a point, for the von Mises output.
  std::function<ElasticMaterial(int patch, const double* x)> material;
};

// Von Mises stress of a displacement field at a parameter of a patch: displacement gradient from the
// parametric derivatives of field and geometry, grad_x u = (du/du) J^{-1}.
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

// With the PETSc back end: <stem>.pvtu and one piece per rank (iga_petsc/parallel_vtk.hpp), written by
// write(folder) on every rank into the folder rank 0 stages; collective.
void write_parallel(const SolveArgs& a, const std::string& stem,
                    const std::function<void(const std::filesystem::path&)>& write) {
  std::unique_ptr<OutputFolder> out;
  std::string staging;
  const std::vector<std::string> names = parallel_vtu_files(stem, rank_partition().parts);
  on_every_rank([&] {
    if (rank_partition().part != 0) return;
    out = prepare_out(a);
    for (const std::string& n : names) staging = out->path(n).parent_path().string();
  });
  write(broadcast_from_rank0(staging));
  if (out) out->commit();
}

template <int D>
void write_solution(const std::filesystem::path& path, const Discretisation<D>& d, const Eigen::VectorXd& coefs) {
  const std::vector<TensorSpline<D>> fields = solution_fields(d.space, coefs, d.components);
  std::vector<io::VtkPointField> vtk{spline_field<D>(d.components == 1 ? "u" : "displacement", fields)};
  if (d.material)
    vtk.push_back({"von_mises", 1, [&](int piece, std::span<const double> u, std::span<double> out) {
                     const TensorSpline<D>& g = d.space.patches[static_cast<std::size_t>(piece)].geometry;
                     double x[D];
                     g.eval(io::param_of<D>(u), x);
                     out[0] = von_mises_at<D>(g, fields[static_cast<std::size_t>(piece)], d.material(piece, x),
                                              io::param_of<D>(u));
                   }});
  io::write_vtu(path.string(), patch_pieces(d.space), {}, vtk);
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
    const SolveResult r = d.solve(a);
    coefs = r.coefs;
    ConvergenceRow row;
    row.step = static_cast<int>(i);
    row.dofs = r.dofs;
    row.assembly_seconds = r.assembly_seconds;
    row.solve_seconds = r.solve_seconds;
    row.elements = 0;
    for (const auto& p : d.space.patches) {
      int e = 1;
      for (int k = 0; k < D; ++k) e *= p.geometry.knots(k).num_elements();
      row.elements += e;
    }
    std::string line = "dofs " + std::to_string(r.dofs);
    if (d.exact) {
      const ErrorNorms e = distributed(a) ? petsc_error_norms(d.space, r.coefs, d.components, d.exact, petsc_options(a).threads)
                                          : error_norms(d.space, r.coefs, d.components, d.exact, a.threads);
      row.l2 = e.l2;
      row.h1 = e.h1;
      line += ", L2 error " + sci(e.l2) + ", H1 error " + sci(e.h1);
    } else {
      row.l2 = row.h1 = -1;
    }
    line += ", assembly " + secs(r.assembly_seconds) + " s, solve " + secs(r.solve_seconds) + " s";
    if (r.stats.iterations > 0) line += " (" + std::to_string(r.stats.iterations) + " " + solver_name(a) + " iterations)";
    std::printf("%s\n", line.c_str());
    rows.push_back(row);
  }
  for (std::size_t i = 1; i < rows.size(); ++i)
    std::printf("elements %d: L2 rate %.2f, H1 rate %.2f\n", rows[i].elements, observed_rate(rows, i, D, false),
                observed_rate(rows, i, D, true));
  if (distributed(a)) print_ranks();
  if (!a.out.empty() && distributed(a)) {
    write_parallel(a, "solution", [&](const std::filesystem::path& folder) {
      write_parallel_vtu<D>(folder, "solution", last->space,
                            {{last->components == 1 ? "u" : "displacement", coefs, last->components}});
    });
  } else if (!a.out.empty()) {
    const auto out = prepare_out(a);
    write_solution<D>(out->path("solution.vtu"), *last, coefs);
    if (a.study) {
      write_convergence_csv(out->path("convergence.csv").string(), rows, D);
      write_convergence_svg(out->path("convergence.svg").string(), rows);
    }
    out->commit();
  }
}

template <int D>
Discretisation<D> poisson_discretisation(const MultipatchSpace<D>& space, const PoissonProblem<D>& problem,
                                         const ExactSolution<D>& exact) {
  return {space, 1,
          [space, problem](const SolveArgs& a) {
            if (distributed(a)) return petsc_solve_poisson(space, problem, petsc_options(a));
            return solve_poisson(space, problem, *make_solver(a.solver), a.threads);
          },
          exact, nullptr};
}

template <int D>
Discretisation<D> poisson_discretisation(const PoissonBenchmark<D>& b) {
  return poisson_discretisation(single_patch_space(b.space), b.problem, b.exact);
}

template <int D>
Discretisation<D> elasticity_discretisation(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem,
                                            const ExactSolution<D>& exact) {
  return {space, D,
          [space, problem](const SolveArgs& a) {
            if (distributed(a)) return petsc_solve_elasticity(space, problem, petsc_options(a));
            return solve_elasticity(space, problem, *make_solver(a.solver), a.threads);
          },
          exact, [problem](int patch, const double* x) { return problem.material_of(patch, x); }};
}

template <int D>
Discretisation<D> elasticity_discretisation(const ElasticityBenchmark<D>& b) {
  return elasticity_discretisation(single_patch_space(b.space), b.problem, b.exact);
}

// The solution as point field "u" on the final mesh of an LR or hierarchical geometry, with the per-element
// indicator and errors as cell data (so ParaView shows where the estimator and the true error disagree).
template <int D, class Geometry>
void write_refined_solution(const std::filesystem::path& path, const Geometry& g, const PoissonBenchmark<D>& b,
                            const Eigen::VectorXd& coefs, int threads) {
  const RefinedSpace<D> space = refined_space(g, threads);
  const std::vector<double> eta = residual_indicators(space, b.problem, coefs, threads);
  std::vector<double> l2, h1;
  error_norms_per_element(space, coefs, 1, b.exact, l2, h1, threads);
  auto cell = [](const std::vector<double>& v, bool root) {
    return [&v, root](int, int e, std::span<double> out) {
      out[0] = root ? std::sqrt(v[static_cast<std::size_t>(e)]) : v[static_cast<std::size_t>(e)];
    };
  };
  const std::vector<io::LRVtkCellField> cells{
      {"estimate", 1, cell(eta, false)}, {"error_l2", 1, cell(l2, true)}, {"error_h1", 1, cell(h1, true)}};
  auto point_field = [](const auto& field) {
    return std::vector<io::VtkPointField>{{"u", 1, [&field](int, std::span<const double> u, std::span<double> out) {
                                             field.eval(io::param_of<D>(u), out.data());
                                           }}};
  };
  if constexpr (std::is_same_v<Geometry, LRSpline<D>>) {
    const LRSpline<D> field = lr_solution_field(g, coefs);
    io::write_lr_vtu(path.string(), AnyLRSpline(g), {}, point_field(field), cells);
  } else {
    // The solution's coefficients belong to the geometry's own functions (refined_space keeps their ids).
    const HierarchicalSpline<D> field(g.space(), 1, false, std::vector<double>(coefs.data(), coefs.data() + coefs.size()));
    io::write_hierarchical_vtu(path.string(), {AnyHierarchicalSpline(g)}, {}, point_field(field), cells);
  }
}

// Adaptive refinement from the problem's tensor space, on an LR or a hierarchical (HB, THB) space: one line per
// step, then the table, and for LR the mesh and the solution.
template <int D>
void run_adaptive(const SolveArgs& a, const PoissonBenchmark<D>& b) {
  require(!a.study, "solve: --study and --adaptive exclude each other");
  AdaptiveOptions o;
  o.steps = a.steps;
  o.beta = a.beta;
  o.admissible = a.admissible;
  require(a.admissible == 0 || (a.admissible >= 2 && a.space != "lr"),
          "solve: --admissible takes a class m >= 2 and applies to --space hb or thb");
  o.solver = a.solver;
  RefinedPoissonSolve<D> solve;
  if (distributed(a))
    solve = [&a](const RefinedSpace<D>& s, const PoissonProblem<D>& p) { return petsc_solve_poisson(s, p, petsc_options(a)); };
  // With the PETSc back end every rank runs the loop; rank 0 alone writes the (serial) outputs, after the last
  // collective call.
  const bool writes = !a.out.empty() && (!distributed(a) || rank_partition().part == 0);
  Eigen::VectorXd coefs;
  const auto print = [](const ConvergenceRow& r) {
    std::printf("step %d: dofs %d, elements %d, L2 error %s, H1 error %s, estimate %s, assembly %s s, solve %s s\n",
                r.step, r.dofs, r.elements, sci(r.l2).c_str(), sci(r.h1).c_str(), sci(r.estimate).c_str(),
                secs(r.assembly_seconds).c_str(), secs(r.solve_seconds).c_str());
  };
  if (a.space != "lr") {
    HierarchicalSpline<D> h(b.space.geometry, a.space == "hb" ? HierarchicalBasis::hb : HierarchicalBasis::thb);
    const auto rows = adaptive_poisson<D>(h, b.problem, b.exact, o, print, &coefs, a.threads, solve);
    if (distributed(a)) print_ranks();
    if (writes) {
      const auto out = prepare_out(a);
      write_convergence_csv(out->path("convergence.csv").string(), rows, D);
      write_convergence_svg(out->path("convergence.svg").string(), rows);
      io::write_hierarchical_vtu(out->path("mesh.vtu").string(), {AnyHierarchicalSpline(h)});
      write_refined_solution<D>(out->path("solution.vtu"), h, b, coefs, a.threads);
      out->commit();
    }
    return;
  }
  LRSpline<D> lr(b.space.geometry);
  const auto rows = adaptive_poisson<D>(lr, b.problem, b.exact, o, print, &coefs, a.threads, solve);
  if (distributed(a)) print_ranks();
  if (writes) {
    const auto out = prepare_out(a);
    write_convergence_csv(out->path("convergence.csv").string(), rows, D);
    write_convergence_svg(out->path("convergence.svg").string(), rows);
    io::write_lr_vtu(out->path("mesh.vtu").string(), AnyLRSpline(lr));
    write_refined_solution<D>(out->path("solution.vtu"), lr, b, coefs, a.threads);
    out->commit();
  }
}

// The material and supports of elasticity and free vibration on a file: cell attributes over the options,
// clamped on --clamp.
template <int D>
ElasticityProblem<D> file_elasticity(const SolveArgs& a, const FileSpace<D>& f) {
  ElasticityProblem<D> pb;
  pb.material = {a.youngs, a.poisson, a.density};
  require(pb.material.valid(), "solve: --youngs and --density must be positive, --poisson-ratio in (-1, 0.5)");
  pb.material_at = f.material_at;
  if (a.clamp != "none") pb.displacement.push_back({faces_on_side(f.space, a.clamp), {}, nullptr});
  return pb;
}

// A file: Poisson with f = 1 and u = 0 on the whole boundary; elasticity clamped on --clamp under a unit body
// force along -z (-y in 2-D).
template <int D>
void run_file(const SolveArgs& a, const FileInput& in) {
  const FileSpace<D> f = space_from_file<D>(a, in);
  if (a.kind == "poisson") {
    PoissonProblem<D> pb;
    pb.source = [](const double*) { return 1.0; };
    pb.dirichlet.push_back({f.space.boundary, {}, nullptr});
    run_static<D>(a, [&](int) { return poisson_discretisation<D>(f.space, pb, nullptr); });
  } else {
    ElasticityProblem<D> pb = file_elasticity(a, f);
    pb.body_force = [](const double*, double* b) {
      for (int k = 0; k < D; ++k) b[k] = k == D - 1 ? -1.0 : 0.0;
    };
    run_static<D>(a, [&](int) { return elasticity_discretisation<D>(f.space, pb, nullptr); });
  }
}

// Laplace eigenvalues (u = 0 on `dirichlet`) or, with an elasticity problem, free vibration: prints every mode
// (against `exact` when given) and writes modes.vtu.
template <int D>
void modes(const SolveArgs& a, const MultipatchSpace<D>& space, const ElasticityProblem<D>* elastic,
           const std::vector<double>& exact) {
  const ModesResult r =
      distributed(a) ? (elastic ? petsc_elastic_modes(space, *elastic, a.modes, petsc_options(a))
                                : petsc_laplace_modes(space, space.boundary, a.modes, petsc_options(a)))
      : elastic      ? elastic_modes(space, *elastic, a.modes, a.threads)
                     : laplace_modes(space, space.boundary, a.modes, a.threads);
  for (int i = 0; i < a.modes; ++i) {
    std::string line = "mode " + std::to_string(i + 1) + ": " + (elastic ? "omega^2 " : "lambda ") + sci(r.values[i]);
    if (elastic) line += ", frequency " + sci(std::sqrt(std::max(0.0, r.values[i])) / (2 * M_PI));
    if (!exact.empty()) {
      const double ex = exact[static_cast<std::size_t>(i)];
      line += " (exact " + sci(ex) + ", relative error " + sci(std::abs(r.values[i] - ex) / ex) + ")";
    }
    std::printf("%s\n", line.c_str());
  }
  std::printf("dofs %d, assembly %s s, solve %s s\n", r.dofs, secs(r.assembly_seconds).c_str(),
              secs(r.solve_seconds).c_str());
  if (distributed(a)) print_ranks();
  if (!a.out.empty() && distributed(a)) {
    std::vector<ParallelField> fields;
    for (int i = 0; i < a.modes; ++i) fields.push_back({"mode_" + std::to_string(i + 1), r.vectors.col(i), elastic ? D : 1});
    write_parallel(a, "modes", [&](const std::filesystem::path& folder) { write_parallel_vtu<D>(folder, "modes", space, fields); });
  } else if (!a.out.empty()) {
    const int components = elastic ? D : 1;
    std::vector<std::vector<TensorSpline<D>>> fields;
    for (int i = 0; i < a.modes; ++i) fields.push_back(solution_fields(space, r.vectors.col(i), components));
    std::vector<io::VtkPointField> vtk;
    for (int i = 0; i < a.modes; ++i)
      vtk.push_back(spline_field<D>("mode_" + std::to_string(i + 1), fields[static_cast<std::size_t>(i)]));
    const auto out = prepare_out(a);
    io::write_vtu(out->path("modes.vtu").string(), patch_pieces(space), {}, vtk);
    out->commit();
  }
}

template <int D>
void file_modes(const SolveArgs& a, const FileInput& in) {
  const FileSpace<D> f = space_from_file<D>(a, in);
  if (a.physics == "laplace") {
    modes<D>(a, f.space, nullptr, {});
  } else {
    const ElasticityProblem<D> pb = file_elasticity(a, f);
    modes<D>(a, f.space, &pb, {});
  }
}

// A locally refined file (an LR spline, or a G+Smo HB / THB geometry) solved on its own space: Poisson with f = 1
// and u = 0 on the whole boundary, elasticity clamped on --clamp under a unit body force along -z (-y in 2-D), or
// eigenmodes (elastic with --clamp, or Laplace with u = 0 on the boundary). The solution or the modes go to
// solution.vtu / modes.vtu on the geometry's mesh (with --backend petsc rank 0 writes them after the solve).
template <int D, class Geometry>
void run_refined_file(const SolveArgs& a, const Geometry& g) {
  const RefinedSpace<D> space = refined_space(g, a.threads);
  std::vector<Face> boundary;
  for (int dir = 0; dir < D; ++dir)
    for (int side = 0; side < 2; ++side) boundary.push_back(Face{dir, side, 0});
  ElasticityProblem<D> elastic;
  elastic.material = {a.youngs, a.poisson, a.density};
  require(a.kind == "poisson" || a.physics == "laplace" || elastic.material.valid(),
          "solve: --youngs and --density must be positive, --poisson-ratio in (-1, 0.5)");
  const bool elastic_kind = a.kind == "elasticity" || (a.kind == "modes" && a.physics == "elastic");
  if (elastic_kind && a.clamp != "none") {
    try {
      elastic.displacement.push_back({faces_in_side_plane(space, a.clamp), {}, nullptr});
    } catch (const Error& e) {
      throw Error(std::string("solve: --") + e.what());
    }
  }
  std::vector<std::pair<std::string, Eigen::VectorXd>> fields;
  const int components = a.kind == "poisson" || (a.kind == "modes" && a.physics == "laplace") ? 1 : D;
  if (a.kind == "modes") {
    const ModesResult r = a.physics == "laplace"
                              ? (distributed(a) ? petsc_laplace_modes(space, boundary, a.modes, petsc_options(a))
                                                : laplace_modes(space, boundary, a.modes, a.threads))
                              : (distributed(a) ? petsc_elastic_modes(space, elastic, a.modes, petsc_options(a))
                                                : elastic_modes(space, elastic, a.modes, a.threads));
    for (int i = 0; i < a.modes; ++i) {
      std::string line = "mode " + std::to_string(i + 1) + ": " + (components == 1 ? "lambda " : "omega^2 ") + sci(r.values[i]);
      if (components > 1) line += ", frequency " + sci(std::sqrt(std::max(0.0, r.values[i])) / (2 * M_PI));
      std::printf("%s\n", line.c_str());
      fields.emplace_back("mode_" + std::to_string(i + 1), r.vectors.col(i));
    }
    std::printf("dofs %d, assembly %s s, solve %s s\n", r.dofs, secs(r.assembly_seconds).c_str(),
                secs(r.solve_seconds).c_str());
  } else {
    SolveResult r;
    if (a.kind == "poisson") {
      PoissonProblem<D> pb;
      pb.source = [](const double*) { return 1.0; };
      pb.dirichlet.push_back({boundary, {}, nullptr});
      r = distributed(a) ? petsc_solve_poisson(space, pb, petsc_options(a)) : solve_poisson(space, pb, *make_solver(a.solver), a.threads);
    } else {
      require(a.clamp != "none", "solve: static elasticity needs supports (--clamp)");
      elastic.body_force = [](const double*, double* b) {
        for (int k = 0; k < D; ++k) b[k] = k == D - 1 ? -1.0 : 0.0;
      };
      r = distributed(a) ? petsc_solve_elasticity(space, elastic, petsc_options(a))
                         : solve_elasticity(space, elastic, *make_solver(a.solver), a.threads);
    }
    std::string line = "dofs " + std::to_string(r.dofs) + ", elements " + std::to_string(space.num_elements());
    double umax = 0;
    for (int i = 0; i < space.num_basis; ++i) {
      double norm2 = 0;
      for (int c = 0; c < components; ++c) norm2 += r.coefs[c * space.num_basis + i] * r.coefs[c * space.num_basis + i];
      umax = std::max(umax, std::sqrt(norm2));
    }
    line += std::string(", max |") + (components == 1 ? "u" : "displacement") + "| coefficient " + sci(umax) +
            ", assembly " + secs(r.assembly_seconds) + " s, solve " + secs(r.solve_seconds) + " s";
    if (r.stats.iterations > 0) line += " (" + std::to_string(r.stats.iterations) + " " + solver_name(a) + " iterations)";
    std::printf("%s\n", line.c_str());
    fields.emplace_back(components == 1 ? "u" : "displacement", r.coefs);
  }
  if (distributed(a)) print_ranks();
  if (a.out.empty()) return;
  const std::string stem = a.kind == "modes" ? "modes" : "solution";
  if (distributed(a)) {
    std::vector<ParallelField> parallel;
    for (const auto& [name, coefs] : fields) parallel.push_back({name, coefs, components});
    write_parallel(a, stem, [&](const std::filesystem::path& folder) {
      write_parallel_vtu<D>(folder, stem, space, g, parallel);
    });
    return;
  }
  const auto out = prepare_out(a);
  std::vector<io::VtkPointField> vtk;
  for (const auto& [name, coefs] : fields)
    vtk.push_back({name, components, [&space, &c = coefs, components](int, std::span<const double> u, std::span<double> v) {
                     refined_field_value(space, c, components, io::param_of<D>(u), v.data());
                   }});
  const std::string file = out->path(stem + ".vtu").string();
  if constexpr (std::is_same_v<Geometry, LRSpline<D>>)
    io::write_lr_vtu(file, AnyLRSpline(g), {}, vtk);
  else
    io::write_hierarchical_vtu(file, {AnyHierarchicalSpline(g)}, {}, vtk);
  out->commit();
}

template <int D>
void run_refined_geometry(const SolveArgs& a, const LRSpline<D>& g) {
  run_refined_file<D>(a, g);
}
template <int D>
void run_refined_geometry(const SolveArgs& a, const HierarchicalSpline<D>& g) {
  run_refined_file<D>(a, g);
}

// Several blocks in one file: matched across their interfaces (T-joints allowed) and solved on the one conforming
// space, as they are (like LR files, --degree and --refine do not apply).
void run_multiblock(const SolveArgs& a, const std::vector<AnyLRSpline>& blocks) {
  require(!a.adaptive || a.kind == "poisson", "solve: --adaptive on a multi-block model takes poisson");
  require(!a.adaptive || a.space == "lr", "solve: --adaptive on a multi-block model refines its LR blocks (--space lr)");
  MultiblockSolveOptions o;
  o.kind = a.kind;
  o.physics = a.physics;
  o.clamp = a.clamp;
  o.solver = a.solver;
  o.material = {a.youngs, a.poisson, a.density};
  o.modes = a.modes;
  o.threads = a.threads;
  if (a.adaptive) {
    AdaptiveOptions adaptive;
    adaptive.steps = a.steps;
    adaptive.beta = a.beta;
    adaptive.solver = a.solver;
    o.adaptive = adaptive;
  }
  std::unique_ptr<OutputFolder> out;
  if (distributed(a)) {
    o.petsc = petsc_options(a);
    o.print_ranks = print_ranks;
    if (!a.out.empty() && !a.adaptive)
      o.write_parallel = [&a](const std::string& stem, const std::function<void(const std::filesystem::path&)>& write) {
        write_parallel(a, stem, write);
      };
  }
  // Serial outputs: the serial back end's, or the adaptive loop's, which rank 0 writes after the last collective
  // call.
  if (!a.out.empty() && !o.write_parallel) {
    const auto prepare = [&] {
      out = prepare_out(a);
      o.path = [&out](const std::string& name) { return out->path(name).string(); };
    };
    if (!distributed(a)) prepare();
    else on_every_rank([&] { if (rank_partition().part == 0) prepare(); });
  }
  solve_multiblock(a.file, blocks, o);
  if (out) out->commit();
}

// The single locally refined geometry of a file, solved by run_refined_file (several LR surfaces: a multi-block
// model); false for any other file.
bool run_if_refined(const SolveArgs& a) {
  const auto single = [&](const auto& objects) {
    require(objects.size() == 1, "solve: " + a.file + " holds " + std::to_string(objects.size()) +
                                     " objects; analysis takes one locally refined spline");
    return objects.front();
  };
  if (const auto lr = read_lr_if_any(a.file)) {
    if (lr->size() > 1) {
      run_multiblock(a, *lr);
      return true;
    }
    std::visit([&](const auto& g) { run_refined_geometry(a, g); }, single(*lr));
    return true;
  }
  if (const auto h = read_hierarchical_if_any(a.file)) {
    std::visit([&](const auto& g) { run_refined_geometry(a, g); }, single(*h));
    return true;
  }
  return false;
}

bool has_trimmed_cells(const FileInput& in) {
  if (!in.model) return false;
  for (const VCell& c : in.model->cells())
    if (c.is_trimmed()) return true;
  return false;
}

// Trimmed cells (an imported part, a Boolean's result): one tensor space on the box around all cells with
// detrimmed quadrature (iga/trimmed_model_space.hpp), continuous across the faces the cells share. The sides of
// the box that hold faces of a cell carry the strong conditions (Poisson: u = 0 there; elasticity: --clamp
// names one of them); the rest of the model's boundary is free (natural). Elasticity takes each cell's
// material attributes.
void run_trimmed(const SolveArgs& a, const VModel& m) {
  const auto t0 = std::chrono::steady_clock::now();
  const TrimmedModelSpace tm = trimmed_model_space(m, a.degree, a.refine, a.threads);
  const RefinedSpace<3>& space = tm.space;
  const std::vector<Face>& sides = tm.sides;
  const double build = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (m.num_cells() == 1)
    std::printf("trimmed cell: %d elements (%d cut, %d outside), quadrature %s s\n", space.num_elements(), tm.cut,
                tm.outside, secs(build).c_str());
  else
    std::printf("trimmed cells: %d, sharing %d faces; %d elements (%d cut, %d outside), quadrature %s s\n",
                m.num_cells(), tm.interfaces.shared, space.num_elements(), tm.cut, tm.outside, secs(build).c_str());
  if (a.kind == "modes") {
    // Laplace modes with u = 0 on the sides of the box holding faces of the model (natural on the trimming
    // boundary), or free vibration with each cell's material (clamped with --clamp, else free).
    const bool elastic = a.physics == "elastic";
    ModesResult r;
    if (!elastic) {
      require(!sides.empty(), "solve: " + a.file + ": no face of the trimmed model lies on a side of its bounding box, "
                                  "so there is nowhere to hold u = 0");
      r = laplace_modes(space, sides, a.modes, a.threads);
    } else {
      ElasticityProblem<3> pb;
      pb.material = {a.youngs, a.poisson, a.density};
      require(pb.material.valid(), "solve: --youngs and --density must be positive, --poisson-ratio in (-1, 0.5)");
      const auto materials = cell_materials(m, pb.material);
      pb.material_at = [&tm, materials](int, const double* x) { return materials(std::max(tm.cell_at(x), 0), x); };
      if (a.clamp != "none") pb.displacement.push_back({{Face{a.clamp[0] - 'x', a.clamp[1] == '-' ? 0 : 1, 0}}, {}, nullptr});
      r = elastic_modes(space, pb, a.modes, a.threads);
    }
    for (int i = 0; i < a.modes && i < static_cast<int>(r.values.size()); ++i) {
      std::string line = "mode " + std::to_string(i + 1) + ": " + (elastic ? "omega^2 " : "lambda ") + sci(r.values[i]);
      if (elastic) line += ", frequency " + sci(std::sqrt(std::max(0.0, r.values[i])) / (2 * M_PI));
      std::printf("%s\n", line.c_str());
    }
    std::printf("dofs %d, assembly %s s, solve %s s\n", r.dofs, secs(r.assembly_seconds).c_str(), secs(r.solve_seconds).c_str());
    return;
  }
  auto solver = make_solver(a.solver);
  SolveResult r;
  if (a.kind == "poisson") {
    require(!sides.empty(), "solve: " + a.file + ": no face of the trimmed model lies on a side of its bounding box, "
                                "so there is nowhere to hold u = 0");
    PoissonProblem<3> pb;
    pb.source = [](const double*) { return 1.0; };
    pb.dirichlet.push_back({sides, {}, nullptr});
    r = solve_poisson(space, pb, *solver, a.threads);
  } else {
    require(a.clamp != "none", "solve: static elasticity needs supports (--clamp)");
    const Face clamp{a.clamp[0] - 'x', a.clamp[1] == '-' ? 0 : 1, 0};
    require(std::any_of(sides.begin(), sides.end(), [&](const Face& f) { return f.dir == clamp.dir && f.side == clamp.side; }),
            "solve: --clamp " + a.clamp + ": no face of the trimmed model lies in that side plane of its bounding box");
    ElasticityProblem<3> pb;
    pb.material = {a.youngs, a.poisson, a.density};
    require(pb.material.valid(), "solve: --youngs and --density must be positive, --poisson-ratio in (-1, 0.5)");
    const auto materials = cell_materials(m, pb.material);
    pb.material_at = [&tm, materials](int, const double* x) { return materials(std::max(tm.cell_at(x), 0), x); };
    pb.displacement.push_back({{clamp}, {}, nullptr});
    pb.body_force = [](const double*, double* b) { b[0] = b[1] = 0, b[2] = -1; };
    r = solve_elasticity(space, pb, *solver, a.threads);
  }
  const int components = a.kind == "poisson" ? 1 : 3;
  // The field at a parameter of the box (the identity: a point).
  const auto field = [&](const Param<3>& u, double* v) { refined_field_value(space, r.coefs, components, u, v); };
  double volume = 0, mean = 0;
  for (const RefinedElement<3>& el : space.elements)
    for_each_element_point<3>(el, a.degree + 2, [&](const Param<3>& u, double w) {
      double v[3];
      field(u, v);
      volume += w;
      mean += w * v[components - 1];
    });
  std::string line = "dofs " + std::to_string(r.dofs) + ", assembly " + secs(r.assembly_seconds) + " s, solve " +
                     secs(r.solve_seconds) + " s";
  if (r.stats.iterations > 0) line += " (" + std::to_string(r.stats.iterations) + " " + a.solver + " iterations)";
  std::printf("%s\n", line.c_str());
  std::printf("volume %s (exact boundary %s), mean %s %s\n", fmt(volume).c_str(), fmt(m.volume()).c_str(),
              components == 1 ? "u" : "z-displacement", fmt(mean / volume).c_str());
  if (!a.out.empty()) {
    const auto out = prepare_out(a);
    const TensorSpline<3> geometry = identity_geometry(tm.box, a.degree, a.refine);
    std::vector<io::VtkPointField> vtk{
        {components == 1 ? "u" : "displacement", components,
         [&](int, std::span<const double> u, std::span<double> v) { field(io::param_of<3>(u), v.data()); }},
        {"inside", 1, [&](int, std::span<const double> u, std::span<double> v) {
           const Param<3> x = io::param_of<3>(u);
           v[0] = std::any_of(m.cells().begin(), m.cells().end(), [&](const VCell& c) { return c.trim()->contains(x); }) ? 1.0 : 0.0;
         }}};
    io::write_vtu(out->path("solution.vtu").string(), {AnySpline(geometry)}, {}, vtk);
    out->commit();
  }
}

// The unit cube, the domain of cube-modes and elastic-cube-modes.
MultipatchSpace<3> unit_cube(int degree, int elements) {
  const Param<3> lo{0, 0, 0}, hi{1, 1, 1};
  return single_patch_space(TensorSpace<3>{box_geometry<3>(lo, hi, degree, elements)});
}

void run(const SolveArgs& a) {
  require(a.degree >= 1, "solve: --degree must be at least 1, got " + std::to_string(a.degree));
  require(a.refine >= 1, "solve: --refine must be at least 1, got " + std::to_string(a.refine));
  require(a.problem.empty() != a.file.empty(), "solve: give either a model/spline file or --problem NAME");
  require(a.modes >= 1, "solve: --modes must be at least 1, got " + std::to_string(a.modes));
  if (!a.out.empty()) check_output_folder(a.out, out_options(a));
  require(!distributed(a) || !is_t_spline_file(a.file),
          "solve: --backend petsc solves tensor, multipatch, multi-block and --adaptive (LR, HB, THB) spaces, not T-splines");
  require(!distributed(a) || !a.study || a.out.empty(),
          "solve: --study writes its convergence table with the serial back end only");
  if (a.problem.empty()) {
    require(!a.study, "solve: --study needs a problem with an exact solution (--problem)");
    require(a.kind != "elasticity" || a.clamp != "none", "solve: static elasticity needs supports (--clamp)");
    if (is_t_spline_file(a.file)) {
      require(a.kind == "poisson", "solve: on a T-spline (" + a.file + ") only poisson is available");
      std::unique_ptr<OutputFolder> out;
      if (!a.out.empty()) out = prepare_out(a);
      solve_tspline_poisson(a.file, a.solver, out ? out->path("solution.vtu").string() : "", a.threads, a.refine);
      if (out) out->commit();
      return;
    }
    if (run_if_refined(a)) return;
    const FileInput in = read_input(a);
    if (!in.blocks.empty()) {
      std::vector<AnyLRSpline> blocks;
      for (std::size_t i = 0; i < in.blocks.size(); ++i) {
        if (const auto* s = std::get_if<TensorSpline<2>>(&in.blocks[i])) blocks.emplace_back(LRSpline<2>(*s));
        else if (const auto* v = std::get_if<TensorSpline<3>>(&in.blocks[i])) blocks.emplace_back(LRSpline<3>(*v));
        else throw Error("solve: " + a.file + " object " + std::to_string(i) + " is a curve; blocks are surfaces or volumes");
      }
      run_multiblock(a, blocks);
    } else if (has_trimmed_cells(in)) {
      require(!distributed(a), "solve: --backend petsc does not take trimmed cells");
      const int untrimmed = static_cast<int>(std::count_if(in.model->cells().begin(), in.model->cells().end(),
                                                           [](const VCell& c) { return !c.is_trimmed(); }));
      if (untrimmed == 0) {
        run_trimmed(a, *in.model);
      } else {
        // Untrimmed cells become trimmed cells of their own region, sharing their faces with the trimmed ones.
        const VModel all = cad::trimmed_form(*in.model);
        std::printf("mixed model: %d untrimmed cells trimmed to their own regions (one general fuse with the %d trimmed "
                    "cells)\n", untrimmed, in.model->num_cells() - untrimmed);
        run_trimmed(a, all);
      }
    } else if (a.kind == "modes" && in.dimension() == 3)
      file_modes<3>(a, in);
    else if (a.kind == "modes")
      file_modes<2>(a, in);
    else if (in.dimension() == 3)
      run_file<3>(a, in);
    else
      run_file<2>(a, in);
    return;
  }
  const std::string& p = a.problem;
  require(a.adaptive || a.space == "lr", "solve: --space is an option of --adaptive");
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
    modes<3>(a, unit_cube(a.degree, a.refine), nullptr, unit_box_laplace_eigenvalues(3, a.modes));
  } else if (a.kind == "modes" && p == "elastic-cube-modes") {
    const ElasticMaterial m{a.youngs, a.poisson, a.density};
    require(m.valid(), "solve: --youngs and --density must be positive, --poisson-ratio in (-1, 0.5)");
    const MultipatchSpace<3> space = unit_cube(a.degree, a.refine);
    ElasticityProblem<3> pb;
    pb.material = m;
    for (const Face& f : space.boundary) pb.displacement.push_back({{f}, {f.dir}, nullptr});
    modes<3>(a, space, &pb, roller_cube_eigenvalues(m, a.modes));
  } else {
    throw Error("solve: unknown " + a.kind + " problem '" + p +
                "' (poisson: sine-cube, sine-square, l-shape; elasticity: lame-cylinder, lame-ring, plate-hole; modes: "
                "cube-modes, elastic-cube-modes)");
  }
}

}  // namespace

void add_solve_command(CLI::App& app, Context& ctx) {
  auto* cmd = app.add_subcommand(
      "solve", "Isogeometric analysis: Poisson, linear elasticity, free vibration and Laplace eigenmodes");
  auto a = std::make_shared<SolveArgs>();
  cmd->add_option("KIND", a->kind, "poisson, elasticity or modes")
      ->required()
      ->check(CLI::IsMember({"poisson", "elasticity", "modes"}));
  cmd->add_option("MODEL_OR_SPLINE", a->file,
                  "Volume, planar surface or V-model (.json, .g2), planar T-spline (.tsm, .stp), LR spline (.lr), or "
                  "several planar blocks in one file (a multi-block model, T-joints allowed)");
  cmd->add_option(
      "--problem", a->problem,
      "Built-in problem: sine-cube, sine-square, l-shape (poisson), lame-cylinder, lame-ring, plate-hole (elasticity), "
      "cube-modes, elastic-cube-modes (modes)");
  cmd->add_option("--degree", a->degree, "Spline degree (files: raised to at least this)")->default_val(2);
  cmd->add_option("--refine", a->refine, "Elements per direction (files: parts per element)")->default_val(8);
  cmd->add_option("--modes", a->modes, "Number of eigenmodes")->default_val(4);
  cmd->add_option("--youngs", a->youngs, "Young's modulus (elasticity on a file)")->default_val(1000.0);
  cmd->add_option("--poisson-ratio", a->poisson, "Poisson's ratio (elasticity on a file)")->default_val(0.3);
  cmd->add_option("--density", a->density, "Density (free vibration)")->default_val(1.0);
  cmd->add_option("--clamp", a->clamp,
                  "Supports of elasticity on a file: the boundary faces in the side plane x-, x+, y-, y+, z- or z+ "
                  "of the bounding box, or none")
      ->default_val("x-")
      ->check(CLI::IsMember({"none", "x-", "x+", "y-", "y+", "z-", "z+"}));
  cmd->add_option("--physics", a->physics, "modes on a file: elastic (free vibration) or laplace")
      ->default_val("elastic")
      ->check(CLI::IsMember({"elastic", "laplace"}));
  cmd->add_flag("--study", a->study, "Also solve on 2, 4, 8, ... elements per direction and report rates");
  cmd->add_flag("--adaptive", a->adaptive, "Adaptive refinement: solve, estimate, mark (Dorfler), refine");
  cmd->add_option("--space", a->space, "Locally refined space of --adaptive: lr (LR B-splines), hb or thb "
                                       "((truncated) hierarchical B-splines)")
      ->default_val("lr")
      ->check(CLI::IsMember({"lr", "hb", "thb"}));
  cmd->add_option("--steps", a->steps, "Adaptive steps (solves)")->default_val(5);
  cmd->add_option("--beta", a->beta, "Dorfler marking fraction in (0, 1]")->default_val(0.3);
  cmd->add_option("--admissible", a->admissible,
                  "HB/THB adaptive loop: keep the mesh admissible of class M >= 2 (at most M levels act on an element)");
  cmd->add_option("--solver", a->solver, "cg, cg-ichol or cholmod")->default_val("cg");
  cmd->add_option("--backend", a->backend,
                  "serial (one process) or petsc (distributed over the MPI ranks of mpirun -np N trivar solve ...; "
                  "one thread per rank unless --threads)")
      ->default_val("serial")
      ->check(CLI::IsMember({"serial", "petsc"}));
  cmd->add_option("--pc", a->pc,
                  "Preconditioner of --backend petsc: gamg, hypre (BoomerAMG), bjacobi (ICC blocks), jacobi, or mumps "
                  "(direct)")
      ->default_val("gamg")
      ->check(CLI::IsMember({"gamg", "hypre", "bjacobi", "jacobi", "mumps"}));
  cmd->add_option("--out", a->out, "Folder for solution.vtu / modes.vtu, convergence.csv and .svg: new, empty, "
                                   "or written by trivar before (see --force)");
  cmd->add_flag("--force", a->force, "Write into a non-empty folder trivar did not write (only trivar's file names are replaced)");
  cmd->callback([a, &ctx] {
    a->threads = ctx.threads;
    if (!distributed(*a)) return run(*a);
    PetscSession mpi;
    // Rank 0 speaks for all: every rank computes the same summary lines, and every rank agrees on a failure
    // (the phases one rank can fail alone agree inside), which rank 0 reports as the one error line.
    if (mpi.rank() > 0) require(std::freopen("/dev/null", "w", stdout) != nullptr, "solve: cannot silence rank output");
    try {
      on_every_rank([&] { run(*a); });
    } catch (...) {
      // Rank 0 reports the failure and gives the exit status; the other ranks end quietly with status 0, because
      // mpiexec stops the whole job when a rank exits non-zero and could stop rank 0 before its line is written.
      if (mpi.rank() == 0) throw;
    }
  });
}

}  // namespace trivar::cli
