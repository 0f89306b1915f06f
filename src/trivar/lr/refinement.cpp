#include "trivar/lr/refinement.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/lr/selection.hpp"

namespace trivar {

const char* to_string(Strategy s) {
  switch (s) {
    case Strategy::fullspan: return "fullspan";
    case Strategy::minspan: return "minspan";
    case Strategy::structured: return "structured";
  }
  return "?";
}

Strategy parse_strategy(const std::string& name) {
  for (Strategy s : {Strategy::fullspan, Strategy::minspan, Strategy::structured})
    if (name == to_string(s)) return s;
  throw Error("unknown refinement strategy '" + name + "' (expected fullspan, minspan or structured)");
}

namespace {

void check_options(const RefineOptions& opts) {
  require(opts.multiplicity >= 1, "refine: multiplicity " + std::to_string(opts.multiplicity) + " is not positive");
  require(opts.max_aspect_ratio <= 0.0 || opts.max_aspect_ratio >= 1.0,
          "refine: max_aspect_ratio " + std::to_string(opts.max_aspect_ratio) + " is below 1");
}

// Whether the box is cut in direction k under the aspect-ratio rule (see refinement.hpp).
template <int D>
bool cuts(const Box<D>& b, int k, double R) {
  if (R <= 0.0) return true;
  int longest = 0;
  for (int j = 1; j < D; ++j)
    if (b.extent(j) > b.extent(longest)) longest = j;
  return k == longest || 0.5 * b.extent(k) >= b.extent(longest) / R;
}

template <int D>
double across(const Box<D>& b, int k) {
  double v = 1.0;
  for (int j = 0; j < D; ++j)
    if (j != k) v *= b.extent(j);
  return v;
}

// MINSPAN's rectangle across direction k on element `el` spans the support of one B-spline on the element: the
// one of smallest extent across k (the product of its other sides; in 2D its length along the rectangle). Among
// equally small ones the one most centred on the element wins: per direction j != k, the numbers of its knots
// up to the element's start and before the element's end each closest to (p_j + 2) / 2 (for cubics: the element
// in its second knot interval); a later candidate, in id order, wins when it is at least as centred in every
// such direction on both sides. In 2D this is LRsplines' rule (getMinspanLines), so both tools refine the
// same meshes alike. (Choosing the extent of each direction from a different B-spline, as LRsplines does for
// volumes, can end a rectangle inside an element in 3D.)
template <int D>
Box<D> minimal_support(const LRSpline<D>& lr, std::span<const int> support, const Box<D>& el, int k) {
  Box<D> best{};
  double best_measure = 0.0;
  std::array<int, 2 * D> best_offcentre{};
  bool first = true;
  for (int b : support) {
    const auto& fn = lr.basis_function(b);
    const Box<D> s = fn.support();
    const double measure = across(s, k);
    if (!first && measure > best_measure) continue;
    std::array<int, 2 * D> offcentre{};
    bool centred = true;
    for (int j = 0; j < D; ++j) {
      if (j == k) continue;
      const auto& y = fn.knots[static_cast<std::size_t>(j)];
      const int centre = (lr.degree(j) + 2) / 2;
      const auto at = [&](auto it) { return std::abs(static_cast<int>(it - y.begin()) - centre); };
      offcentre[static_cast<std::size_t>(2 * j)] = at(std::upper_bound(y.begin(), y.end(), el.lo[j]));
      offcentre[static_cast<std::size_t>(2 * j + 1)] = at(std::lower_bound(y.begin(), y.end(), el.hi[j]));
      for (std::size_t side = 2 * static_cast<std::size_t>(j); side <= 2 * static_cast<std::size_t>(j) + 1; ++side)
        centred = centred && offcentre[side] <= best_offcentre[side];
    }
    if (first || measure < best_measure || centred) {
      first = false;
      best = s;
      best_measure = measure;
      best_offcentre = offcentre;
    }
  }
  return best;
}

template <int D>
std::vector<int> union_of(std::span<const int> ids, auto&& lists) {
  std::vector<int> out;
  for (int i : ids) {
    const auto l = lists(i);
    out.insert(out.end(), l.begin(), l.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

template <int D>
std::vector<MeshRectangle<D>> element_rectangles(const LRSpline<D>& lr, std::span<const int> elements,
                                                 const RefineOptions& opts) {
  check_options(opts);
  const auto ids = checked_ids(elements, lr.num_elements(), "element");
  if (opts.strategy == Strategy::structured)
    return function_rectangles(lr, union_of<D>(ids, [&](int e) { return lr.element_support(e); }), opts);
  std::vector<MeshRectangle<D>> out;
  for (int e : ids) {
    const auto& el = lr.element(e);
    const auto support = lr.element_support(e);
    if (support.empty()) continue;
    // A surface's FULLSPAN rectangle is the supports' bounding box; a volume's are the cross-sections below.
    Box<D> span = Box<D>::empty();
    if (D == 2 && opts.strategy == Strategy::fullspan)
      for (int b : support) {
        const auto s = lr.basis_function(b).support();
        span.extend(s.lo.data());
        span.extend(s.hi.data());
      }
    for (int k = 0; k < D; ++k) {
      if (!cuts(el, k, opts.max_aspect_ratio)) continue;
      if (opts.strategy == Strategy::minspan) span = minimal_support(lr, support, el, k);
      const double mid = 0.5 * (el.lo[k] + el.hi[k]);
      if (D == 2 || opts.strategy != Strategy::fullspan) {
        out.push_back(MeshRectangle<D>::make(k, mid, span.lo, span.hi, opts.multiplicity));
        continue;
      }
      // In 3D the supports' cross-sections need not fill their bounding box, whose corners can then end inside
      // elements: one rectangle per distinct cross-section, together covering their union.
      const std::size_t first = out.size();
      for (int b : support) {
        const auto r = MeshRectangle<D>::make(k, mid, lr.basis_function(b).support().lo,
                                              lr.basis_function(b).support().hi, opts.multiplicity);
        if (std::none_of(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
                         [&](const MeshRectangle<D>& o) { return o.extent.lo == r.extent.lo && o.extent.hi == r.extent.hi; }))
          out.push_back(r);
      }
    }
  }
  return out;
}

template <int D>
std::vector<MeshRectangle<D>> function_rectangles(const LRSpline<D>& lr, std::span<const int> functions,
                                                  const RefineOptions& opts) {
  check_options(opts);
  const auto ids = checked_ids(functions, lr.num_basis(), "B-spline");
  if (opts.strategy != Strategy::structured)
    return element_rectangles(lr, union_of<D>(ids, [&](int b) { return lr.basis_elements(b); }), opts);
  std::vector<MeshRectangle<D>> out;
  for (int b : ids) {
    const auto& fn = lr.basis_function(b);
    const Box<D> S = fn.support();
    for (int k = 0; k < D; ++k) {
      if (!cuts(S, k, opts.max_aspect_ratio)) continue;
      const auto& y = fn.knots[k];
      for (std::size_t i = 0; i + 1 < y.size(); ++i)
        if (y[i] < y[i + 1])
          out.push_back(MeshRectangle<D>::make(k, 0.5 * (y[i] + y[i + 1]), S.lo, S.hi, opts.multiplicity));
    }
  }
  return out;
}

template <int D>
int refine_elements(LRSpline<D>& lr, std::span<const int> elements, const RefineOptions& opts) {
  const auto rects = element_rectangles(lr, elements, opts);
  return lr.insert(std::span<const MeshRectangle<D>>(rects));
}

template <int D>
int refine_functions(LRSpline<D>& lr, std::span<const int> functions, const RefineOptions& opts) {
  const auto rects = function_rectangles(lr, functions, opts);
  return lr.insert(std::span<const MeshRectangle<D>>(rects));
}

#define TRIVAR_INSTANTIATE(D)                                                                                      \
  template std::vector<MeshRectangle<D>> element_rectangles(const LRSpline<D>&, std::span<const int>,            \
                                                            const RefineOptions&);                               \
  template std::vector<MeshRectangle<D>> function_rectangles(const LRSpline<D>&, std::span<const int>,           \
                                                             const RefineOptions&);                              \
  template int refine_elements(LRSpline<D>&, std::span<const int>, const RefineOptions&);                         \
  template int refine_functions(LRSpline<D>&, std::span<const int>, const RefineOptions&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
