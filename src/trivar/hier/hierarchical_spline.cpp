#include "trivar/hier/hierarchical_spline.hpp"

#include <cmath>
#include <map>
#include <string>
#include <unordered_map>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"

namespace trivar {

namespace {

// Coefficients in the THB basis of `target` of the spline (source, coefs): the coefficient of tau (level l) is
// its entry in the level-l local expansion of the spline on a cell of level l in tau's support that Omega^{l+1}
// does not cover, where every coarser THB function is truncated away (on the uncovered part the spline is the
// polynomial of levels <= l, and a polynomial on part of a cell fixes it on the whole cell). The source must be
// a subspace of the target (same hierarchy, its domains inside the target's), and its hierarchy must hold the
// target's levels. keep(id) may give a known coefficient (returns false otherwise).
template <int D, class Keep>
std::vector<double> thb_coefficients(const HierarchicalSpace<D>& target, const HierarchicalSpace<D>& source,
                                     std::span<const double> coefs, int stride, Keep&& keep) {
  std::vector<double> out(static_cast<std::size_t>(target.num_basis()) * stride);
  const int P = target.local_size();
  std::vector<std::unordered_map<CellKey, std::vector<double>>> cache(static_cast<std::size_t>(target.num_levels()));
  typename HierarchicalSpace<D>::ExpansionCache ancestors;
  for (int id = 0; id < target.num_basis(); ++id) {
    double* c = out.data() + static_cast<std::size_t>(id) * stride;
    if (keep(id, c)) continue;
    const HierarchicalFunction<D> f = target.function(id);
    Ints<D> cell;
    require(target.uncovered_cell_in_support(f.level, f.index, cell), "hier: function is not active");
    auto& expansion = cache[static_cast<std::size_t>(f.level)][pack_key<D>(cell)];
    if (expansion.empty()) {
      expansion.resize(static_cast<std::size_t>(P) * stride);
      source.local_expansion(f.level, cell, coefs, stride, expansion.data(), ancestors);
    }
    int q = 0;
    for (int k = D - 1; k >= 0; --k) {
      const int first = target.hierarchy().axis(f.level, k).span(cell[k]) - target.degree(k);
      q = q * (target.degree(k) + 1) + (f.index[k] - first);
    }
    std::copy_n(expansion.begin() + static_cast<std::ptrdiff_t>(q) * stride, stride, c);
  }
  return out;
}

// HB coefficients in `target` of the same spline: level by level, the coefficient of tau is its THB
// coefficient minus the entry of the coarser HB part's local expansion (a HB function is not truncated, so the
// coarser functions overlap it).
template <int D>
std::vector<double> hb_from_thb(const HierarchicalSpace<D>& hb, std::span<const double> thb, int stride) {
  std::vector<double> out(thb.size(), 0.0);
  const int P = hb.local_size();
  typename HierarchicalSpace<D>::ExpansionCache ancestors;
  for (int l = 0, id = 0; l < hb.num_levels(); ++l) {
    std::unordered_map<CellKey, std::vector<double>> cache;
    const int end = id + hb.num_basis(l);
    for (; id < end; ++id) {
      const HierarchicalFunction<D> f = hb.function(id);
      Ints<D> cell;
      require(hb.uncovered_cell_in_support(l, f.index, cell), "hier: function is not active");
      auto& e = cache[pack_key<D>(cell)];
      if (e.empty()) {
        e.resize(static_cast<std::size_t>(P) * stride);
        hb.local_expansion(l, cell, out, stride, e.data(), ancestors);  // levels >= l are still zero in out
      }
      int q = 0;
      for (int k = D - 1; k >= 0; --k) {
        const int first = hb.hierarchy().axis(l, k).span(cell[k]) - hb.degree(k);
        q = q * (hb.degree(k) + 1) + (f.index[k] - first);
      }
      for (int s = 0; s < stride; ++s)
        out[static_cast<std::size_t>(id) * stride + s] = thb[static_cast<std::size_t>(id) * stride + s] -
                                                          e[static_cast<std::size_t>(q) * stride + s];
    }
  }
  return out;
}

}  // namespace

template <int D>
HierarchicalSpline<D>::HierarchicalSpline(const TensorSpline<D>& s, HierarchicalBasis basis)
    : space_(TensorHierarchy<D>(s.knot_vectors()), basis),
      dim_(s.dim()),
      rational_(s.is_rational()),
      coefs_(s.coefs().begin(), s.coefs().end()) {}

template <int D>
HierarchicalSpline<D>::HierarchicalSpline(HierarchicalSpace<D> space, int dim, bool rational, std::vector<double> coefs)
    : space_(std::move(space)), dim_(dim), rational_(rational), coefs_(std::move(coefs)) {
  require(dim >= 1, "hier: control dimension " + std::to_string(dim) + " must be at least 1");
  require(coefs_.size() == static_cast<std::size_t>(space_.num_basis()) * stride(), [&] {
    return "hier: " + std::to_string(coefs_.size()) + " coefficient values for " + std::to_string(space_.num_basis()) +
           " functions of " + std::to_string(stride()) + " values";
  });
  for (std::size_t i = 0; i < coefs_.size(); ++i)
    require(std::isfinite(coefs_[i]), [&] { return "hier: coefficient value " + std::to_string(i) + " is not finite"; });
  if (rational_ && space_.basis() == HierarchicalBasis::thb)
    for (int i = 0; i < space_.num_basis(); ++i)
      require(coef(i)[dim_] > 0, [&] { return "hier: weight of function " + std::to_string(i) + " is not positive"; });
}

template <int D>
HierarchicalSpline<D>::HierarchicalSpline(const HierarchicalSpline& o)
    : space_(o.space_), dim_(o.dim_), rational_(o.rational_), coefs_(o.coefs_) {
  const std::lock_guard lock(o.mutex_);
  evaluator_ = o.evaluator_;
}

template <int D>
HierarchicalSpline<D>& HierarchicalSpline<D>::operator=(const HierarchicalSpline& o) {
  if (this == &o) return *this;
  space_ = o.space_;
  dim_ = o.dim_;
  rational_ = o.rational_;
  coefs_ = o.coefs_;
  std::shared_ptr<const HierarchicalEvaluator<D>> ev;
  {
    const std::lock_guard lock(o.mutex_);
    ev = o.evaluator_;
  }
  const std::lock_guard lock(mutex_);
  evaluator_ = std::move(ev);
  return *this;
}

template <int D>
const HierarchicalEvaluator<D>& HierarchicalSpline<D>::evaluator() const {
  const std::lock_guard lock(mutex_);
  if (!evaluator_) evaluator_ = std::make_shared<const HierarchicalEvaluator<D>>(space_, dim_, rational_, coefs_);
  return *evaluator_;
}

template <int D>
template <class Refine>
int HierarchicalSpline<D>::refine(Refine&& how) {
  HierarchicalSpace<D> old = space_;
  const int n = how(space_);
  if (n == 0) return 0;
  const int st = stride();
  old.reserve_levels(space_.hierarchy().num_levels());
  if (space_.basis() == HierarchicalBasis::thb) {
    coefs_ = thb_coefficients<D>(space_, old, coefs_, st, [&](int id, double* c) {
      const HierarchicalFunction<D> f = space_.function(id);
      const int was = old.find_function(f.level, f.index);
      if (was < 0) return false;
      std::copy_n(coefs_.begin() + static_cast<std::ptrdiff_t>(was) * st, st, c);
      return true;
    });
  } else {
    // Two-scale relation: a function that left the active set passes its coefficient to its children.
    std::vector<double> out(static_cast<std::size_t>(space_.num_basis()) * st, 0.0);
    std::vector<std::map<CellKey, std::vector<double>>> pending(static_cast<std::size_t>(space_.num_levels()) + 1);
    for (int id = 0; id < old.num_basis(); ++id) {
      const HierarchicalFunction<D> f = old.function(id);
      const int now = space_.find_function(f.level, f.index);
      const double* c = coefs_.data() + static_cast<std::size_t>(id) * st;
      if (now >= 0) {
        for (int s = 0; s < st; ++s) out[static_cast<std::size_t>(now) * st + s] += c[s];
      } else {
        auto& v = pending[static_cast<std::size_t>(f.level)][pack_key<D>(f.index)];
        v.assign(c, c + st);
      }
    }
    const auto& h = space_.hierarchy();
    std::array<std::vector<double>, D> w;
    std::array<int, D> first;
    for (int l = 0; l < space_.num_levels(); ++l)
      for (const auto& [key, c] : pending[static_cast<std::size_t>(l)]) {
        const Ints<D> f = unpack_key<D>(key);
        for (int k = 0; k < D; ++k) {
          h.two_scale(l, k, f[k], first[k], w[k]);
        }
        Ints<D> a{}, size;
        for (int k = 0; k < D; ++k) size[k] = static_cast<int>(w[k].size());
        while (true) {
          double weight = 1.0;
          Ints<D> g;
          for (int k = 0; k < D; ++k) {
            weight *= w[k][static_cast<std::size_t>(a[k])];
            g[k] = first[k] + a[k];
          }
          if (weight != 0.0) {
            const int now = space_.find_function(l + 1, g);
            if (now >= 0) {
              for (int s = 0; s < st; ++s) out[static_cast<std::size_t>(now) * st + s] += weight * c[static_cast<std::size_t>(s)];
            } else {
              auto& v = pending[static_cast<std::size_t>(l) + 1][pack_key<D>(g)];
              v.resize(static_cast<std::size_t>(st), 0.0);
              for (int s = 0; s < st; ++s) v[static_cast<std::size_t>(s)] += weight * c[static_cast<std::size_t>(s)];
            }
          }
          int k = 0;
          while (k < D && ++a[k] == size[k]) a[k] = 0, ++k;
          if (k == D) break;
        }
      }
    coefs_ = std::move(out);
  }
  const std::lock_guard lock(mutex_);
  evaluator_.reset();
  return n;
}

template <int D>
int HierarchicalSpline<D>::refine_cells(int level, std::span<const Ints<D>> cells) {
  return refine([&](HierarchicalSpace<D>& s) { return s.refine_cells(level, cells); });
}

template <int D>
int HierarchicalSpline<D>::extend_domains(const std::vector<std::vector<Ints<D>>>& cells) {
  return refine([&](HierarchicalSpace<D>& s) { return s.extend_domains(cells); });
}

template <int D>
int HierarchicalSpline<D>::refine_elements(std::span<const int> elements) {
  return refine([&](HierarchicalSpace<D>& s) { return s.refine_elements(elements); });
}

template <int D>
int HierarchicalSpline<D>::refine_elements_admissible(std::span<const int> elements, int m) {
  return refine([&](HierarchicalSpace<D>& s) { return s.refine_elements_admissible(elements, m); });
}

template <int D>
int HierarchicalSpline<D>::refine_functions(std::span<const int> ids) {
  return refine([&](HierarchicalSpace<D>& s) { return s.refine_functions(ids); });
}

template <int D>
HierarchicalSpline<D> HierarchicalSpline<D>::with_basis(HierarchicalBasis basis) const {
  if (basis == space_.basis()) return *this;
  const HierarchicalSpace<D> target = space_.with_basis(basis);
  const int st = stride();
  if (basis == HierarchicalBasis::thb)
    return HierarchicalSpline(target, dim_, rational_,
                              thb_coefficients<D>(target, space_, coefs_, st, [](int, double*) { return false; }));
  const std::vector<double> thb = thb_coefficients<D>(space_, space_, coefs_, st, [&](int id, double* c) {
    std::copy_n(coefs_.begin() + static_cast<std::ptrdiff_t>(id) * st, st, c);
    return true;
  });
  return HierarchicalSpline(target, dim_, rational_, hb_from_thb<D>(target, thb, st));
}

template <int D>
void HierarchicalSpline<D>::eval_many(std::span<const Param<D>> u, std::span<double> out, int threads) const {
  require(out.size() >= u.size() * dim_, "hier: batch output buffer too small");
  const HierarchicalEvaluator<D>& ev = evaluator();
  parallel_for(static_cast<std::ptrdiff_t>(u.size()), threads,
               [&](std::ptrdiff_t i) { ev.eval(space_, u[static_cast<std::size_t>(i)], out.data() + i * dim_); });
}

template <int D>
std::vector<BezierElement<D>> HierarchicalSpline<D>::bezier_elements() const {
  const HierarchicalEvaluator<D>& ev = evaluator();
  std::vector<BezierElement<D>> out(static_cast<std::size_t>(space_.num_elements()));
  for (int e = 0; e < space_.num_elements(); ++e) {
    BezierElement<D>& b = out[static_cast<std::size_t>(e)];
    b.domain = space_.element_box(e);
    for (int k = 0; k < D; ++k) b.degrees[k] = space_.degree(k);
    b.dim = dim_;
    b.rational = rational_;
    const auto net = ev.net(e);
    b.coefs.assign(net.begin(), net.end());
  }
  return out;
}

template class HierarchicalSpline<2>;
template class HierarchicalSpline<3>;

}  // namespace trivar
