#pragma once
// Adaptive approximation of scattered data by an LR spline (the method of SINTEF's LRSurfApprox, Skytt, Barrowclough
// and Dokken 2015): start from a coarse tensor spline over the points' bounding box, then repeat
//   fit (penalised least squares, least_squares.hpp) -> error per point -> refine every element holding a point
//   whose error exceeds the tolerance (FULLSPAN / MINSPAN / STRUCTURED, refinement.hpp)
// until every point is within the tolerance, or a limit on refinement levels or coefficients is reached. After
// each refinement the basis is checked for linear independence (peeling, then the exact rank where peeling is
// inconclusive); a dependent refinement is undone and replaced by FULLSPAN on the same elements, and when that is
// dependent too the loop stops with the last independent spline (seed 004: discard the problematic refinement).
// The fit of each round is either the penalised least squares on the whole space, or (FitMethod::mba, after a
// least-squares fit of the coarse start spline, as LRSurfApprox switches methods) one multilevel B-spline
// approximation pass (mba.hpp) that adds to the previous round's function, kept exactly through the refinement,
// a correction of the residual: no linear system however many coefficients, at the price of more coefficients
// or rounds for the same tolerance.
// The same code fits surfaces (D = 2: terrain heights over x, y) and volumes (D = 3: scalar fields, material
// fractions over x, y, z).
#include <functional>
#include <string>
#include <vector>

#include "trivar/fit/scattered_data.hpp"
#include "trivar/lr/refinement.hpp"

namespace trivar {

enum class FitMethod { least_squares, mba };

struct ApproximationOptions {
  FitMethod method = FitMethod::least_squares;
  int mba_passes = 3;           // MBA passes per round, each fitting what the last left (fewer coefficients than 1)
  double tolerance = 0.0;       // absolute, > 0, on the largest component error of every point
  int degree = 2;               // in every direction, 1..5
  int initial_elements = 4;     // along the longest side of the box; other sides in proportion (at least 1)
  int max_levels = 10;          // refinement rounds after the first fit
  int max_coefficients = 0;     // stop before a refinement would exceed it (0: no limit)
  Strategy strategy = Strategy::fullspan;
  double smoothing = 1e-9;      // dimensionless weight of the thin-plate energy (least_squares.hpp; not MBA)
  bool check_independence = true;
  bool uniform = false;         // refine every element (a uniform tensor spline, for comparison)
  int threads = 1;
};

struct IterationReport {
  int level = 0;                // 0 for the first fit
  int coefficients = 0;
  int elements = 0;
  double max_error = 0.0, mean_error = 0.0, rms_error = 0.0;
  std::size_t outside = 0;      // points whose error exceeds the tolerance
  double seconds = 0.0;         // this round: locating, fitting, errors, refinement
  std::string independence;     // of the basis that was fitted: "independent", "not_tested" (check off) ...
};

template <int D>
struct Approximation {
  LRSpline<D> spline;           // data.dim values per coefficient
  // The same B-splines with the identity map as coefficients (u, v[, w] exactly): carried through every
  // refinement from the initial tensor spline, because Greville abscissae reproduce the parameters only there.
  LRSpline<D> parameters;
  std::vector<IterationReport> iterations;
  std::vector<double> errors;   // per point, the final error
  bool converged = false;       // every point within the tolerance
  std::string stop_reason;      // "tolerance reached", "level limit", "coefficient limit", ...
};

// Throws trivar::Error for bad options or data (validate) before any work.
// "ls" or "mba" (what the CLI and reports print); parse_fit_method throws trivar::Error naming other words.
const char* to_string(FitMethod method);
FitMethod parse_fit_method(const std::string& word);

// domain: the box the spline is built on (it must hold every point); null: the points' bounding box.
template <int D>
Approximation<D> approximate(const ScatteredData<D>& data, const ApproximationOptions& options,
                             const std::function<void(const IterationReport&)>& progress = {},
                             const Box<D>* domain = nullptr);

// The coarse tensor spline the loop starts from (degree and element counts of `options`): the identity map of
// the box, D values per B-spline (its Greville abscissae).
template <int D>
LRSpline<D> initial_space(const Box<D>& box, const ApproximationOptions& options, int refinements = 0);

}  // namespace trivar
