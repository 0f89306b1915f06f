#pragma once
// `trivar solve` on a multi-block file: several planar blocks (LR or B-spline surfaces) whose sides meet along
// common segments, or volumes whose faces meet over common parts (e.g. the output of `trivar stitch
// --multiblock`), T-joints allowed. The blocks are matched
// (fit/multiblock_space) and solved on the one conforming space by iga's locally refined solvers.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "trivar/iga/adaptive_loop.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga_petsc/petsc_problems.hpp"
#include "trivar/lr/any_lr_spline.hpp"

namespace trivar::cli {

struct MultiblockSolveOptions {
  std::string kind;     // poisson, elasticity or modes
  std::string physics;  // modes: elastic or laplace
  std::string clamp;    // elasticity and elastic modes: x-, x+, y-, y+, z-, z+ or none
  std::string solver;
  ElasticMaterial material;
  int modes = 4;
  int threads = 0;
  // The path of an output file by name (solution.vtu, modes.vtu, mesh.vtu, convergence.csv, ...), or null: no output.
  std::function<std::string(const std::string& name)> path;
  // Adaptive refinement (poisson only): solve, estimate, mark over all blocks, refine inside them, match again.
  std::optional<AdaptiveOptions> adaptive;
  // --backend petsc: every rank runs the same solve with the distributed solvers; the per-rank line after the
  // results (print_ranks) and, for static problems and modes, <stem>.pvtu with one piece per rank through
  // write_parallel(stem, write(folder)) (collective) instead of `path`. The adaptive loop's outputs are serial
  // files that rank 0 alone writes through `path` (null on the other ranks).
  std::optional<PetscSolverOptions> petsc;
  std::function<void(const std::string& stem, const std::function<void(const std::filesystem::path&)>& write)> write_parallel;
  std::function<void()> print_ranks;
};

// Poisson -lap u = 1 with u = 0 on the whole boundary of the union (adaptively refined with o.adaptive),
// elasticity clamped on --clamp under a unit body force along -y (-z for volumes), or eigenmodes; prints the
// matching (blocks, interfaces, T-joints, functions) and the solve, and writes one VTU piece per block. Throws trivar::Error "solve: <path>: ..." for blocks that cannot be matched.
void solve_multiblock(const std::string& path, const std::vector<AnyLRSpline>& blocks, const MultiblockSolveOptions& o);

}  // namespace trivar::cli
