#pragma once
// Linear independence of a collection of LR B-splines (Dokken, Lyche, Pettersen 2013; seed 004, lecture 4).
//
// Peeling (overloading) test. Let P = prod_k (p_k + 1). An element is overloaded when more than P B-splines
// have support on it; a B-spline is overloaded when every element of its support is. On an element that is
// not overloaded the restrictions of its B-splines are linearly independent, because LR B-splines span the
// polynomials of degree p on every element (they are refined from a tensor basis), so exactly P of them
// restricted there form a basis of those polynomials. Hence a B-spline that is not overloaded has coefficient
// 0 in every linear relation. Peeling repeats the argument (as in LRsplines' isLinearIndepByOverloading and
// Dokken's description of the peeling algorithm): drop the B-splines known to have coefficient 0; an element on
// which exactly one B-spline is left forces that B-spline's coefficient to 0 too, so drop it and continue. If
// nothing is left the collection is independent; otherwise the test is inconclusive (not_tested). Cost linear
// in the total support size.
//
// Exact test: after peeling, the rank of the Bezier extraction rows of the B-splines that are left (their
// per-element Bernstein coefficients stacked; the peeled B-splines have coefficient 0 in any relation, so they
// need no columns), per connected block (B-splines linked through shared elements), in exact arithmetic: the
// knots are exact dyadic rationals and the Bernstein coefficients rational functions of them
// (bernstein_coefficients), so the rank is computed modulo the prime 2^61 - 1 and, where that shows a
// deficiency, confirmed over Q with GMP rationals (core/exact_rank.hpp: full rank modulo p implies full rank
// over Q). No tolerance: the answer is the rank of the B-splines as given by their double knots.
// Precondition of both: the restrictions of the collection to every element span the polynomials of degree p
// (true for LR B-splines refined from a tensor-product basis); the tests throw trivar::Error when an element has
// fewer than P B-splines, which shows that the precondition fails.
#include <span>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/lr/lr_bezier_extraction.hpp"
#include "trivar/lr/lr_bspline.hpp"
#include "trivar/lr/lr_spline.hpp"

namespace trivar {

enum class Independence { independent, not_independent, not_tested };

// "independent", "not_independent", "not_tested".
const char* to_string(Independence s);

struct PeelingResult {
  Independence status = Independence::not_tested;  // independent or not_tested (peeling proves no dependence)
  int overloaded_elements = 0;                      // elements with more than P B-splines
  int overloaded_basis = 0;                         // B-splines whose support has only overloaded elements
  std::vector<int> unresolved;                      // B-splines left after peeling, ascending
};

// Peeling on the incidence lists: element_basis[e] the B-splines on element e, basis_elements[b] the elements of
// B-spline b's support (element_basis transposed), P = prod (p_k + 1).
PeelingResult peel(int P, const Incidence& element_basis, const Incidence& basis_elements);

// Peeling of the B-splines `basis` (p_k + 2 local knots each) over the box partition `elements`.
template <int D>
PeelingResult peeling_test(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis,
                           std::span<const Box<D>> elements, int threads = 0);

// Peeling of an LR spline, on the support lists it keeps (no search for the elements of each support).
template <int D>
PeelingResult peeling_test(const LRSpline<D>& lr);

struct ExactResult {
  Independence status = Independence::not_tested;  // independent or not_independent
  int tested = 0;   // B-splines left by peeling, the rows of the rank problem
  int rank = 0;     // their rank
  int blocks = 0;   // connected blocks
  int rational_blocks = 0;  // blocks whose rank was computed over Q (deficient modulo p)
  int nullity() const { return tested - rank; }  // number of independent linear relations
};

template <int D>
ExactResult exact_test(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis, std::span<const Box<D>> elements,
                       int threads = 0);

// The exact test of an LR spline, on the support lists it keeps.
template <int D>
ExactResult exact_test(const LRSpline<D>& lr);

}  // namespace trivar
