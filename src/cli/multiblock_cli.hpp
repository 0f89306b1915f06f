#pragma once
// `trivar solve` on a multi-block file: several planar blocks (LR or B-spline surfaces) whose sides meet along
// common segments, or volumes whose faces meet over common parts (e.g. the output of `trivar stitch
// --multiblock`), T-joints allowed. The blocks are matched
// (fit/multiblock_space) and solved on the one conforming space by iga's locally refined solvers.
#include <string>
#include <vector>

#include "trivar/iga/elasticity.hpp"
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
  std::string vtu;  // solution.vtu / modes.vtu to write, or empty
};

// Poisson -lap u = 1 with u = 0 on the whole boundary of the union, elasticity clamped on --clamp under a unit body
// force along -y (-z for volumes), or eigenmodes; prints the matching (blocks, interfaces, T-joints, functions) and the solve, and
// writes one VTU piece per block. Throws trivar::Error "solve: <path>: ..." for blocks that cannot be matched.
void solve_multiblock(const std::string& path, const std::vector<AnyLRSpline>& blocks, const MultiblockSolveOptions& o);

}  // namespace trivar::cli
