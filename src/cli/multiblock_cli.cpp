#include "multiblock_cli.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>
#include <variant>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/fit/multiblock_adaptive.hpp"
#include "trivar/fit/multiblock_space.hpp"
#include "trivar/iga/convergence_table.hpp"
#include "trivar/iga/refined_elasticity.hpp"
#include "trivar/iga/refined_modes.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/side_faces.hpp"
#include "trivar/iga_petsc/parallel_vtk.hpp"
#include "trivar/io/lr_vtk.hpp"

namespace trivar::cli {

namespace {

template <int D>
MultiblockSpace<D> matched(const std::string& path, const std::vector<AnyLRSpline>& objects) {
  std::vector<LRSpline<D>> blocks;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const auto* s = std::get_if<LRSpline<D>>(&objects[i]);
    require(s != nullptr, "solve: " + path + " block " + std::to_string(i) + " is a " + (D == 2 ? "volume" : "surface") +
                              ", block 0 a " + (D == 2 ? "surface" : "volume") + "; blocks are all planar surfaces or all volumes");
    blocks.push_back(*s);
  }
  const int n = static_cast<int>(blocks.size());
  MultiblockSpace<D> m;
  try {
    m = multiblock_space(std::move(blocks));
  } catch (const Error& e) {
    throw Error("solve: " + path + ": " + e.what());
  }
  // A block sharing no side with any other is almost always one that misses its neighbours (a gap, a different
  // curve), not a model of separate parts.
  std::vector<char> joined(static_cast<std::size_t>(n), 0);
  for (const BlockInterface<D>& f : m.interfaces) joined[static_cast<std::size_t>(f.block[0])] = joined[static_cast<std::size_t>(f.block[1])] = 1;
  for (int b = 0; b < n && n > 1; ++b)
    require(joined[static_cast<std::size_t>(b)], [&] {
      return "solve: " + path + ": block " + std::to_string(b) + " shares no side with another block (within 1e-8 of "
             "the model's size), so it cannot be matched into the multi-block model";
    });
  return m;
}

// The largest value and the mean of the last component over the union (Gauss points of every element).
template <int D>
std::pair<double, double> max_and_mean(const MultiblockSpace<D>& m, const Eigen::VectorXd& coefs, int components) {
  const RefinedSpace<D>& s = m.space;
  double volume = 0, integral = 0, largest = 0;
  RefinedPoint<D> p;
  std::vector<double> grad;
  const auto c = static_cast<Eigen::Index>(components - 1) * s.num_basis;
  for (const RefinedElement<D>& el : s.elements)
    for_each_element_point<D>(el, s.degrees[0] + 2, [&](const Param<D>& u, double w) {
      refined_point(s, el, u, p);
      const double dV = physical_gradients(p, grad) * w;
      double v = 0;
      for (std::size_t l = 0; l < el.ids.size(); ++l) v += coefs[c + el.ids[l]] * p.R[l];
      volume += dV;
      integral += v * dV;
      if (std::abs(v) > std::abs(largest)) largest = v;
    });
  return {largest, integral / volume};
}

// One VTU piece per block with the fields on its own mesh.
template <int D>
void write_fields(const MultiblockSpace<D>& m, const std::vector<std::pair<std::string, Eigen::VectorXd>>& fields,
                  int components, const std::string& vtu) {
  std::vector<std::vector<LRSpline<D>>> per_block;  // per field, one LR spline per block
  for (const auto& [name, coefs] : fields) per_block.push_back(multiblock_fields(m, coefs, components));
  std::vector<io::VtkPointField> vtk;
  for (std::size_t i = 0; i < fields.size(); ++i)
    vtk.push_back({fields[i].first, components, [&per_block, i](int piece, std::span<const double> u, std::span<double> out) {
                     per_block[i][static_cast<std::size_t>(piece)].eval(io::param_of<D>(u), out.data());
                   }});
  io::write_lr_vtu(vtu, std::vector<AnyLRSpline>(m.blocks.begin(), m.blocks.end()), {}, vtk);
}

// Adaptive Poisson (f = 1, u = 0 on the boundary of the union): one line per step; convergence.csv / .svg,
// mesh.vtu (the blocks' final meshes) and solution.vtu.
template <int D>
void solve_adaptive(MultiblockSpace<D>& m, const MultiblockSolveOptions& o, std::vector<std::string>& report) {
  PoissonProblem<D> pb;
  pb.source = [](const double*) { return 1.0; };
  pb.dirichlet.push_back({boundary_faces(m), {}, nullptr});
  RefinedPoissonSolve<D> distributed;
  if (o.petsc) distributed = [&o](const RefinedSpace<D>& s, const PoissonProblem<D>& p) { return petsc_solve_poisson(s, p, *o.petsc); };
  Eigen::VectorXd coefs;
  const std::vector<ConvergenceRow> rows = adaptive_poisson<D>(m, pb, nullptr, *o.adaptive, [&](const ConvergenceRow& r) {
    char line[200];
    std::snprintf(line, sizeof line, "step %d: dofs %d, elements %d, estimate %.3e, assembly %.3f s, solve %.3f s", r.step, r.dofs,
                  r.elements, r.estimate, r.assembly_seconds, r.solve_seconds);
    report.emplace_back(line);
  }, &coefs, o.threads, distributed);
  report.push_back("final model: " + std::to_string(m.space.num_basis) + " functions, " + std::to_string(m.space.num_elements()) +
                   " elements, " + std::to_string(m.interfaces.size()) + " interfaces (matched again after every step)");
  if (!o.path) return;
  write_convergence_csv(o.path("convergence.csv"), rows, D);
  write_convergence_svg(o.path("convergence.svg"), rows);
  io::write_lr_vtu(o.path("mesh.vtu"), std::vector<AnyLRSpline>(m.blocks.begin(), m.blocks.end()));
  write_fields(m, {{"u", coefs}}, 1, o.path("solution.vtu"));
}

template <int D>
void solve(const std::string& path, const std::vector<AnyLRSpline>& objects, const MultiblockSolveOptions& o) {
  MultiblockSpace<D> m = matched<D>(path, objects);
  const RefinedSpace<D>& space = m.space;
  int partial = 0;
  for (const BlockInterface<D>& f : m.interfaces)
    for (std::size_t k = 0; k < 2; ++k) {
      const LRSpline<D>& b = m.blocks[static_cast<std::size_t>(f.block[k])];
      for (int a = 0; a < D; ++a)
        if (a != f.side[k].dir && (std::min(f.lo[k][a], f.hi[k][a]) != b.domain().lo[a] || std::max(f.lo[k][a], f.hi[k][a]) != b.domain().hi[a])) {
          ++partial;
          break;
        }
    }
  // Printed with the results, so a failing solve writes nothing to stdout.
  std::vector<std::string> report{"multi-block: " + std::to_string(m.blocks.size()) + " blocks, " +
                                  std::to_string(m.interfaces.size()) + " interfaces (" + std::to_string(partial) +
                                  " of them on part of a block side: T-joints), " + std::to_string(space.num_basis) +
                                  " functions, " + std::to_string(space.num_elements()) + " elements"};

  ElasticityProblem<D> elastic;
  elastic.material = o.material;
  const bool elastic_kind = o.kind == "elasticity" || (o.kind == "modes" && o.physics == "elastic");
  require(!elastic_kind || elastic.material.valid(), "solve: --youngs and --density must be positive, --poisson-ratio in (-1, 0.5)");
  if (elastic_kind && o.clamp != "none") {
    try {
      elastic.displacement.push_back({faces_in_side_plane(space, o.clamp), {}, nullptr});
    } catch (const Error& e) {
      throw Error(std::string("solve: --") + e.what());
    }
  }
  const std::vector<Face> boundary = boundary_faces(m);
  const int components = elastic_kind ? D : 1;
  std::vector<std::pair<std::string, Eigen::VectorXd>> fields;
  if (o.adaptive) {
    solve_adaptive(m, o, report);
    for (const std::string& line : report) std::printf("%s\n", line.c_str());
    if (o.print_ranks) o.print_ranks();
    return;
  }
  if (o.kind == "modes") {
    const ModesResult r = o.petsc ? (elastic_kind ? petsc_elastic_modes(space, elastic, o.modes, *o.petsc)
                                                  : petsc_laplace_modes(space, boundary, o.modes, *o.petsc))
                                  : (elastic_kind ? elastic_modes(space, elastic, o.modes, o.threads)
                                                  : laplace_modes(space, boundary, o.modes, o.threads));
    for (int i = 0; i < o.modes; ++i) {
      std::string line = "mode " + std::to_string(i + 1) + ": " + (elastic_kind ? "omega^2 " : "lambda ") + fmt(r.values[i]);
      if (elastic_kind) line += ", frequency " + fmt(std::sqrt(std::max(0.0, r.values[i])) / (2 * M_PI));
      report.push_back(line);
      fields.emplace_back("mode_" + std::to_string(i + 1), r.vectors.col(i));
    }
    char line[96];
    std::snprintf(line, sizeof line, "dofs %d, assembly %.3f s, solve %.3f s", r.dofs, r.assembly_seconds, r.solve_seconds);
    report.emplace_back(line);
  } else {
    SolveResult r;
    if (o.kind == "poisson") {
      PoissonProblem<D> pb;
      pb.source = [](const double*) { return 1.0; };
      pb.dirichlet.push_back({boundary, {}, nullptr});
      r = o.petsc ? petsc_solve_poisson(space, pb, *o.petsc) : solve_poisson(space, pb, *make_solver(o.solver), o.threads);
    } else {
      require(o.clamp != "none", "solve: static elasticity needs supports (--clamp)");
      elastic.body_force = [](const double*, double* b) {
        for (int k = 0; k < D; ++k) b[k] = k == D - 1 ? -1.0 : 0.0;
      };
      r = o.petsc ? petsc_solve_elasticity(space, elastic, *o.petsc) : solve_elasticity(space, elastic, *make_solver(o.solver), o.threads);
    }
    const auto [largest, mean] = max_and_mean(m, r.coefs, components);
    const std::string what = components == 1 ? "u" : D == 2 ? "y-displacement" : "z-displacement";
    std::string line = "dofs " + std::to_string(r.dofs) + ", max " + what + " " + fmt(largest) + ", mean " + what + " " + fmt(mean);
    char times[96];
    std::snprintf(times, sizeof times, ", assembly %.3f s, solve %.3f s", r.assembly_seconds, r.solve_seconds);
    line += times;
    if (r.stats.iterations > 0)
      line += " (" + std::to_string(r.stats.iterations) + " " + (o.petsc ? "cg+" + o.petsc->preconditioner : o.solver) + " iterations)";
    report.push_back(line);
    fields.emplace_back(components == 1 ? "u" : "displacement", r.coefs);
  }
  const std::string stem = o.kind == "modes" ? "modes" : "solution";
  if (o.petsc && o.write_parallel) {
    std::vector<ParallelField> parallel;
    for (const auto& [name, coefs] : fields) parallel.push_back({name, coefs, components});
    o.write_parallel(stem, [&](const std::filesystem::path& folder) { write_parallel_vtu<D>(folder, stem, space, m.blocks, parallel); });
  } else if (o.path) {
    write_fields(m, fields, components, o.path(stem + ".vtu"));
  }
  for (const std::string& line : report) std::printf("%s\n", line.c_str());
  if (o.print_ranks) o.print_ranks();
}

}  // namespace

void solve_multiblock(const std::string& path, const std::vector<AnyLRSpline>& blocks, const MultiblockSolveOptions& o) {
  require(!blocks.empty(), "solve: " + path + " holds no blocks");
  if (std::holds_alternative<LRSpline<2>>(blocks.front())) solve<2>(path, blocks, o);
  else solve<3>(path, blocks, o);
}

}  // namespace trivar::cli
