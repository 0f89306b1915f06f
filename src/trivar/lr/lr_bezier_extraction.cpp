#include "trivar/lr/lr_bezier_extraction.hpp"

#include <algorithm>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/knot_refinement.hpp"

namespace trivar {

namespace {

// Static k-d tree over points (element centres), median split cycling through the directions; answers "which
// points lie in the open box".
template <int D>
class CentreTree {
public:
  explicit CentreTree(std::span<const Box<D>> elements) : idx_(elements.size()), pts_(elements.size()) {
    std::vector<Param<D>> c(elements.size());
    for (std::size_t e = 0; e < elements.size(); ++e) c[e] = elements[e].center();
    for (std::size_t e = 0; e < idx_.size(); ++e) idx_[e] = static_cast<int>(e);
    build(c, 0, static_cast<int>(idx_.size()), 0);
    for (std::size_t i = 0; i < idx_.size(); ++i) pts_[i] = c[static_cast<std::size_t>(idx_[i])];
  }

  void query(const Box<D>& box, std::vector<int>& out) const { query(box, 0, static_cast<int>(idx_.size()), 0, out); }

private:
  static constexpr int kLeaf = 8;
  std::vector<int> idx_;
  std::vector<Param<D>> pts_;

  void build(const std::vector<Param<D>>& c, int lo, int hi, int depth) {
    if (hi - lo <= kLeaf) return;
    const int axis = depth % D, mid = (lo + hi) / 2;
    std::nth_element(idx_.begin() + lo, idx_.begin() + mid, idx_.begin() + hi, [&](int a, int b) {
      return c[static_cast<std::size_t>(a)][static_cast<std::size_t>(axis)] <
             c[static_cast<std::size_t>(b)][static_cast<std::size_t>(axis)];
    });
    build(c, lo, mid, depth + 1);
    build(c, mid + 1, hi, depth + 1);
  }

  static bool inside(const Param<D>& p, const Box<D>& b) {
    for (int k = 0; k < D; ++k)
      if (!(b.lo[k] < p[static_cast<std::size_t>(k)] && p[static_cast<std::size_t>(k)] < b.hi[k])) return false;
    return true;
  }

  void query(const Box<D>& box, int lo, int hi, int depth, std::vector<int>& out) const {
    if (hi - lo <= kLeaf) {
      for (int i = lo; i < hi; ++i)
        if (inside(pts_[static_cast<std::size_t>(i)], box)) out.push_back(idx_[static_cast<std::size_t>(i)]);
      return;
    }
    const int axis = depth % D, mid = (lo + hi) / 2;
    const double v = pts_[static_cast<std::size_t>(mid)][static_cast<std::size_t>(axis)];
    if (box.lo[axis] < v) query(box, lo, mid, depth + 1, out);
    if (inside(pts_[static_cast<std::size_t>(mid)], box)) out.push_back(idx_[static_cast<std::size_t>(mid)]);
    if (box.hi[axis] > v) query(box, mid + 1, hi, depth + 1, out);
  }
};

}  // namespace

template <int D>
Incidence support_elements(std::span<const LRBSpline<D>> basis, std::span<const Box<D>> elements, int threads) {
  const CentreTree<D> tree(elements);
  const int nb = static_cast<int>(basis.size());
  // Contiguous chunks of B-splines, each filling its own buffer, then concatenated in order.
  const int chunks = std::max(1, std::min(nb, 64 * resolve_threads(threads)));
  std::vector<std::vector<int>> ids(static_cast<std::size_t>(chunks));
  std::vector<int> counts(static_cast<std::size_t>(nb));
  parallel_for(chunks, threads, [&](std::ptrdiff_t c) {
    const int b0 = static_cast<int>(c * nb / chunks), b1 = static_cast<int>((c + 1) * nb / chunks);
    auto& out = ids[static_cast<std::size_t>(c)];
    for (int b = b0; b < b1; ++b) {
      const std::size_t start = out.size();
      tree.query(basis[static_cast<std::size_t>(b)].support(), out);
      std::sort(out.begin() + static_cast<std::ptrdiff_t>(start), out.end());
      counts[static_cast<std::size_t>(b)] = static_cast<int>(out.size() - start);
    }
  });
  Incidence r;
  r.offsets.resize(static_cast<std::size_t>(nb) + 1);
  for (std::size_t b = 0; b < static_cast<std::size_t>(nb); ++b) r.offsets[b + 1] = r.offsets[b] + counts[b];
  r.ids.reserve(static_cast<std::size_t>(r.offsets.back()));
  for (const auto& v : ids) r.ids.insert(r.ids.end(), v.begin(), v.end());
  return r;
}

template <int D>
Incidence element_supports(std::span<const LRBSpline<D>> basis, std::span<const Box<D>> elements, int threads) {
  return support_elements<D>(basis, elements, threads).transposed(static_cast<int>(elements.size()));
}

template <int D>
Eigen::MatrixXd extraction_operator(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis,
                                    std::span<const int> ids, const Box<D>& element) {
  int cols = 1;
  for (int k = 0; k < D; ++k) cols *= degrees[static_cast<std::size_t>(k)] + 1;
  Eigen::MatrixXd C(static_cast<Eigen::Index>(ids.size()), cols);
  double rows[D][kMaxDegree + 1];
  for (std::size_t r = 0; r < ids.size(); ++r) {
    const LRBSpline<D>& bs = basis[static_cast<std::size_t>(ids[r])];
    for (int k = 0; k < D; ++k) {
      const auto& t = bs.knots[static_cast<std::size_t>(k)];
      require(static_cast<int>(t.size()) == degrees[static_cast<std::size_t>(k)] + 2, [&] {
        return "extraction_operator: B-spline " + std::to_string(ids[r]) + " has " + std::to_string(t.size()) +
               " knots in direction " + std::to_string(k) + ", expected p + 2 = " +
               std::to_string(degrees[static_cast<std::size_t>(k)] + 2);
      });
      bernstein_coefficients<double>(t, element.lo[k], element.hi[k], rows[k]);
    }
    std::array<int, D> j{};
    for (int c = 0; c < cols; ++c) {
      double v = bs.gamma;
      for (int k = 0; k < D; ++k) v *= rows[k][j[static_cast<std::size_t>(k)]];
      C(static_cast<Eigen::Index>(r), c) = v;
      for (int k = 0; k < D; ++k) {
        if (++j[static_cast<std::size_t>(k)] <= degrees[static_cast<std::size_t>(k)]) break;
        j[static_cast<std::size_t>(k)] = 0;
      }
    }
  }
  return C;
}

template <int D>
BezierElement<D> bezier_element(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis,
                                std::span<const int> ids, const Box<D>& element, int dim, bool rational) {
  const Eigen::MatrixXd C = extraction_operator<D>(degrees, basis, ids, element);
  BezierElement<D> e;
  e.domain = element;
  for (int k = 0; k < D; ++k) e.degrees[static_cast<std::size_t>(k)] = degrees[static_cast<std::size_t>(k)];
  e.dim = dim;
  e.rational = rational;
  const int st = e.stride();
  e.coefs.assign(static_cast<std::size_t>(C.cols() * st), 0.0);
  for (Eigen::Index r = 0; r < C.rows(); ++r) {
    const auto& c = basis[static_cast<std::size_t>(ids[static_cast<std::size_t>(r)])].coef;
    require(static_cast<int>(c.size()) == st, [&] {
      return "bezier_element: B-spline " + std::to_string(ids[static_cast<std::size_t>(r)]) + " has " +
             std::to_string(c.size()) + " coefficient values, expected " + std::to_string(st);
    });
    for (Eigen::Index j = 0; j < C.cols(); ++j)
      for (int s = 0; s < st; ++s) e.coefs[static_cast<std::size_t>(j * st + s)] += C(r, j) * c[static_cast<std::size_t>(s)];
  }
  return e;
}

template <int D>
std::vector<BezierElement<D>> bezier_elements(const Ints<D>& degrees, std::span<const LRBSpline<D>> basis,
                                              std::span<const Box<D>> elements, int dim, bool rational,
                                              int threads) {
  const Incidence on = element_supports<D>(basis, elements, threads);
  std::vector<BezierElement<D>> out(elements.size());
  parallel_for(static_cast<std::ptrdiff_t>(elements.size()), threads, [&](std::ptrdiff_t e) {
    out[static_cast<std::size_t>(e)] =
        bezier_element<D>(degrees, basis, on[static_cast<int>(e)], elements[static_cast<std::size_t>(e)], dim, rational);
  });
  return out;
}

#define TRIVAR_INSTANTIATE(D)                                                                                   \
  template Incidence support_elements<D>(std::span<const LRBSpline<D>>, std::span<const Box<D>>, int);          \
  template Incidence element_supports<D>(std::span<const LRBSpline<D>>, std::span<const Box<D>>, int);          \
  template Eigen::MatrixXd extraction_operator<D>(const Ints<D>&, std::span<const LRBSpline<D>>,                \
                                                  std::span<const int>, const Box<D>&);                         \
  template BezierElement<D> bezier_element<D>(const Ints<D>&, std::span<const LRBSpline<D>>, std::span<const int>, \
                                              const Box<D>&, int, bool);                                        \
  template std::vector<BezierElement<D>> bezier_elements<D>(const Ints<D>&, std::span<const LRBSpline<D>>,      \
                                                            std::span<const Box<D>>, int, bool, int);
TRIVAR_INSTANTIATE(1)
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
