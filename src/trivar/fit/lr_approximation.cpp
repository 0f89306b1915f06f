#include "trivar/fit/lr_approximation.hpp"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "trivar/core/error.hpp"
#include "trivar/fit/least_squares.hpp"
#include "trivar/fit/mba.hpp"
#include "trivar/lr/linear_independence.hpp"
#include "trivar/spline/knot_vector.hpp"

namespace trivar {
namespace {

template <int D>
Independence independence_of(const LRSpline<D>& lr) {
  if (peeling_test(lr).status == Independence::independent) return Independence::independent;
  return exact_test(lr).status;
}

void check_options(const ApproximationOptions& o) {
  require(o.tolerance > 0.0 && std::isfinite(o.tolerance), "fit: the tolerance must be a positive number");
  require(o.degree >= 1 && o.degree <= 5, "fit: degree " + std::to_string(o.degree) + " outside 1..5");
  require(o.initial_elements >= 1 && o.initial_elements <= 4096,
          "fit: " + std::to_string(o.initial_elements) + " initial elements, expected 1..4096");
  require(o.max_levels >= 0 && o.max_levels <= 30, "fit: " + std::to_string(o.max_levels) + " levels, expected 0..30");
  require(o.max_coefficients >= 0, "fit: the coefficient limit must be >= 0");
  require(o.mba_passes >= 1 && o.mba_passes <= 100, "fit: " + std::to_string(o.mba_passes) + " MBA passes, expected 1..100");
  require(o.smoothing >= 0.0 && std::isfinite(o.smoothing), "fit: the smoothing weight must be >= 0");
}

// The data in Morton order of a 2^10 grid over the box, and the permutation (sorted[i] = data[order[i]]): the fit
// visits the points element by element, and spatially sorted points make those visits stream through memory.
template <int D>
std::pair<ScatteredData<D>, std::vector<std::uint32_t>> spatially_sorted(const ScatteredData<D>& data, const Box<D>& box) {
  constexpr int kBits = 10;
  std::vector<std::uint64_t> key(data.size());
  for (std::size_t i = 0; i < data.size(); ++i) {
    std::uint64_t code = 0;
    for (int k = 0; k < D; ++k) {
      const double t = (data.params[i][k] - box.lo[k]) / (box.hi[k] - box.lo[k]);
      const auto c = static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * ((1 << kBits) - 1));
      for (int b = 0; b < kBits; ++b) code |= ((c >> b) & 1u) << (b * D + k);
    }
    key[i] = code;
  }
  std::vector<std::uint32_t> order(data.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
  ScatteredData<D> sorted;
  sorted.dim = data.dim;
  sorted.params.resize(data.size());
  sorted.values.resize(data.values.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    sorted.params[i] = data.params[order[i]];
    std::copy_n(data.value(order[i]), data.dim, sorted.values.data() + i * static_cast<std::size_t>(data.dim));
  }
  return {std::move(sorted), std::move(order)};
}

// MBA refines the fitted function together with the identity map: one spline of D + dim values per B-spline (the
// parameters first), so a refinement re-expresses both in the same finer B-splines.
template <int D>
LRSpline<D> joined(const LRSpline<D>& space, int dim, const std::vector<double>& coefs) {
  const std::size_t n = static_cast<std::size_t>(space.num_basis()), width = static_cast<std::size_t>(D + dim);
  std::vector<double> all(n * width);
  const auto basis = space.basis_functions();
  for (std::size_t i = 0; i < n; ++i) {
    std::copy_n(basis[i].coef.begin(), D, all.begin() + static_cast<std::ptrdiff_t>(i * width));
    std::copy_n(coefs.begin() + static_cast<std::ptrdiff_t>(i) * dim, dim, all.begin() + static_cast<std::ptrdiff_t>(i * width + D));
  }
  return with_coefficients(space, D + dim, all);
}

// The inverse of joined: the identity map as a spline of D values, the fitted values into coefs.
template <int D>
LRSpline<D> split_joined(const LRSpline<D>& both, int dim, std::vector<double>& coefs) {
  const std::size_t n = static_cast<std::size_t>(both.num_basis());
  std::vector<double> identity(n * D);
  coefs.assign(n * static_cast<std::size_t>(dim), 0.0);
  const auto basis = both.basis_functions();
  for (std::size_t i = 0; i < n; ++i) {
    std::copy_n(basis[i].coef.begin(), D, identity.begin() + static_cast<std::ptrdiff_t>(i * D));
    std::copy_n(basis[i].coef.begin() + D, dim, coefs.begin() + static_cast<std::ptrdiff_t>(i) * dim);
  }
  return with_coefficients(both, D, identity);
}

}  // namespace

const char* to_string(FitMethod method) { return method == FitMethod::mba ? "mba" : "ls"; }

FitMethod parse_fit_method(const std::string& word) {
  if (word == "ls" || word == "least-squares") return FitMethod::least_squares;
  if (word == "mba") return FitMethod::mba;
  throw Error("fit: unknown method '" + word + "', expected ls or mba");
}

template <int D>
LRSpline<D> initial_space(const Box<D>& box, const ApproximationOptions& o, int refinements) {
  double longest = 0.0;
  for (int k = 0; k < D; ++k) longest = std::max(longest, box.hi[k] - box.lo[k]);
  std::array<KnotVector, D> knots;
  std::array<std::vector<double>, D> greville;
  for (int k = 0; k < D; ++k) {
    const int n = std::max(1, static_cast<int>(std::lround(o.initial_elements * (box.hi[k] - box.lo[k]) / longest)))
                  << refinements;
    knots[k] = KnotVector::open_uniform(o.degree, n, box.lo[k], box.hi[k]);
    greville[k] = knots[k].greville();
  }
  std::size_t count = 1;
  for (int k = 0; k < D; ++k) count *= greville[k].size();
  // Control point i = (greville_0[i_0], ..., greville_{D-1}[i_{D-1}]), first index fastest.
  std::vector<double> coefs(count * D);
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t rest = i;
    for (int k = 0; k < D; ++k) {
      const std::size_t n = greville[k].size();
      coefs[i * D + static_cast<std::size_t>(k)] = greville[k][rest % n];
      rest /= n;
    }
  }
  return LRSpline<D>(TensorSpline<D>(std::move(knots), D, false, std::move(coefs)));
}

template <int D>
Approximation<D> approximate(const ScatteredData<D>& data, const ApproximationOptions& o,
                             const std::function<void(const IterationReport&)>& progress, const Box<D>* domain) {
  check_options(o);
  validate(data, "fit");
  using Clock = std::chrono::steady_clock;
  require(data.size() < (std::size_t{1} << 31), "fit: more than 2^31 points");
  const Box<D> box = domain ? *domain : data.bounding_box();
  if (domain) {
    const Box<D> points = data.bounding_box();
    for (int k = 0; k < D; ++k)
      require(box.lo[k] < box.hi[k] && box.lo[k] <= points.lo[k] && points.hi[k] <= box.hi[k],
              "fit: the points reach beyond the given domain in direction " + std::to_string(k));
  }
  const auto [sorted, order] = spatially_sorted(data, box);
  LRSpline<D> space = initial_space(box, o);
  std::string status = "independent";  // a tensor basis
  std::vector<IterationReport> reports;
  std::string stop;
  const bool mba = o.method == FitMethod::mba;
  std::vector<double> coefs, errors(sorted.size());
  std::vector<double> residuals;  // MBA: f - s per point and component, carried from round to round
  for (int level = 0;; ++level) {
    const auto t0 = Clock::now();
    const PointsByElement where = locate_points(space, std::span<const Param<D>>(sorted.params), o.threads);
    if (mba && level > 0) {
      mba_update(space, sorted, where, std::span<double>(coefs), std::span<double>(residuals), o.mba_passes, o.threads);
      for (std::size_t i = 0; i < errors.size(); ++i) {
        double e = 0.0;
        for (int c = 0; c < data.dim; ++c) e = std::max(e, std::abs(residuals[i * static_cast<std::size_t>(data.dim) + static_cast<std::size_t>(c)]));
        errors[i] = e;
      }
    } else {
      LeastSquaresResult fit = least_squares_fit(space, sorted, where, o.smoothing, o.threads);
      coefs = std::move(fit.coefs);
      errors = std::move(fit.errors);
      if (mba) {  // the signed residuals the MBA rounds start from
        residuals.resize(sorted.values.size());
        with_coefficients(space, data.dim, coefs).eval_many(std::span<const Param<D>>(sorted.params), residuals, o.threads);
        for (std::size_t i = 0; i < residuals.size(); ++i) residuals[i] = sorted.values[i] - residuals[i];
      }
    }
    IterationReport r;
    r.level = level;
    r.coefficients = space.num_basis();
    r.elements = space.num_elements();
    r.independence = status;
    double sum = 0.0, sum2 = 0.0;
    std::vector<int> marked;
    for (int e = 0; e < space.num_elements(); ++e) {
      bool bad = false;
      for (int q = where.offsets[static_cast<std::size_t>(e)]; q < where.offsets[static_cast<std::size_t>(e) + 1]; ++q) {
        const double err = errors[static_cast<std::size_t>(where.points[static_cast<std::size_t>(q)])];
        r.max_error = std::max(r.max_error, err);
        sum += err;
        sum2 += err * err;
        if (err > o.tolerance) {
          ++r.outside;
          bad = true;
        }
      }
      if (bad || o.uniform) marked.push_back(e);
    }
    const double n = static_cast<double>(data.size());
    r.mean_error = sum / n;
    r.rms_error = std::sqrt(sum2 / n);

    if (r.outside == 0) stop = "tolerance reached";
    else if (level >= o.max_levels) stop = "level limit";
    if (stop.empty()) {
      // MBA refines the fitted function with the space.
      const auto start = [&] { return mba ? joined(space, data.dim, coefs) : space; };
      LRSpline<D> next = start();
      if (o.uniform && !mba) {
        next = initial_space(box, o, level + 1);
      } else if (o.uniform) {  // FULLSPAN on every element halves each: the next dyadic tensor spline, both maps kept
        refine_elements(next, std::span<const int>(marked), RefineOptions{Strategy::fullspan, 1, 0.0});
      } else {
        refine_elements(next, std::span<const int>(marked), RefineOptions{o.strategy, 1, 0.0});
        if (o.check_independence) {
          Independence s = independence_of(next);
          if (s == Independence::not_independent && o.strategy != Strategy::fullspan) {
            next = start();
            refine_elements(next, std::span<const int>(marked), RefineOptions{Strategy::fullspan, 1, 0.0});
            s = independence_of(next);
          }
          if (s == Independence::not_independent) stop = "refinement would make the basis linearly dependent";
          status = to_string(s);
        } else {
          status = "not_tested";
        }
      }
      if (stop.empty() && o.max_coefficients > 0 && next.num_basis() > o.max_coefficients) stop = "coefficient limit";
      if (stop.empty()) space = mba ? split_joined(next, data.dim, coefs) : std::move(next);
    }
    r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    reports.push_back(r);
    if (progress) progress(r);
    if (!stop.empty()) break;
  }
  const bool converged = reports.back().outside == 0;
  std::vector<double> point_errors(data.size());
  for (std::size_t i = 0; i < order.size(); ++i) point_errors[order[i]] = errors[i];
  LRSpline<D> fitted = with_coefficients(space, data.dim, coefs);
  return Approximation<D>{std::move(fitted), std::move(space), std::move(reports), std::move(point_errors), converged, stop};
}

template LRSpline<2> initial_space(const Box<2>&, const ApproximationOptions&, int);
template LRSpline<3> initial_space(const Box<3>&, const ApproximationOptions&, int);
template Approximation<2> approximate(const ScatteredData<2>&, const ApproximationOptions&,
                                      const std::function<void(const IterationReport&)>&, const Box<2>*);
template Approximation<3> approximate(const ScatteredData<3>&, const ApproximationOptions&,
                                      const std::function<void(const IterationReport&)>&, const Box<3>*);

}  // namespace trivar
