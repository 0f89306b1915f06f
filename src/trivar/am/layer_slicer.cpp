#include "trivar/am/layer_slicer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <utility>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/model/material_fractions.hpp"

namespace trivar::am {

namespace {

bool positive_finite(double v) { return std::isfinite(v) && v > 0; }

// A crossing of a row's centre line with an outline segment, with the cell parameters there (interpolated
// along the segment, whose chord is within the outline tolerance of the section curve).
struct Hit {
  int row;
  double x;
  Param<3> u;
  bool operator<(const Hit& o) const { return row != o.row ? row < o.row : x < o.x; }
};

// Chord iterations: Newton steps with the inverse Jacobian of a nearby solved pixel. Neighbouring pixels'
// Jacobians differ by O(pixel / cell size), so each step still gains about two digits, at the cost of one
// value evaluation instead of derivatives and a factorisation.
constexpr int kChordSteps = 3;
// Pixels between refreshes of the inverse Jacobian: the contraction of a chord step grows with the distance
// to where the Jacobian was taken, and a refresh costs about two value evaluations.
constexpr int kChordRefresh = 16;

bool jacobian_inverse(const TensorSpline<3>& s, const ElementPolynomials& poly, const Param<3>& u,
                      Eigen::Matrix3d& inv) {
  double d[12];
  if (poly.available())
    poly.eval_first(u, d);
  else
    s.eval_derivs(u, 1, d);
  Eigen::Matrix3d J;
  for (int k = 0; k < 3; ++k)
    for (int r = 0; r < 3; ++r) J(r, k) = d[3 * (1 + k) + r];
  bool invertible = false;
  double det = 0;
  J.computeInverseAndDetWithCheck(inv, det, invertible, 0.0);
  return invertible && inv.allFinite();
}

// True, with u and residual, when chord steps from u reach |s(u) - x| <= tol without leaving the domain
// (a root outside it belongs to another cell, or to none). `next` gets one more chord step from the accepted
// u, taken without evaluating: a better start for the following pixels than u itself, whose error is up to
// the tolerance and would be amplified by extrapolation. p gets s(u), for the material attribute.
// `value(u, p)` evaluates the cell's geometry.
template <class Value>
bool chord_solve(const Value& value, const Box<3>& dom, const Eigen::Matrix3d& inv, const double* x, double tol,
                 Param<3>& u, double& residual, Param<3>& next, double* p) {
  for (int k = 0; k < 3; ++k) u[k] = std::clamp(u[k], dom.lo[k], dom.hi[k]);
  for (int it = 0;; ++it) {
    value(u, p);
    const Eigen::Vector3d r(x[0] - p[0], x[1] - p[1], x[2] - p[2]);
    residual = r.norm();
    const Eigen::Vector3d du = inv * r;
    if (residual <= tol) {
      for (int k = 0; k < 3; ++k) next[k] = u[k] + du[k];
      return true;
    }
    if (it == kChordSteps || !(residual < std::numeric_limits<double>::infinity())) return false;
    for (int k = 0; k < 3; ++k) {
      u[k] += du[k];
      if (!(u[k] >= dom.lo[k] && u[k] <= dom.hi[k])) return false;
    }
  }
}

// Pixels of a cell to the left that the along-row guess extrapolates through (degree kStreakMax - 1). Cubic
// extrapolation (error O(h^4)) left the first chord evaluation above the inversion tolerance on 44 % of the
// ball r 20's pixels at 600 dpi: its truncation error is about the tolerance there. Quartic cuts that to 9 %;
// quintic amplifies the solved pixels' own error (up to the tolerance times the chord step's contraction) by
// the sum of its coefficients' magnitudes, 63 against 31, and was worse again (20 %).
constexpr int kStreakMax = 5;

// Material fractions are evaluated for runs of up to kFractionRun pixels of one cell at once (the attribute's
// formulas run over the whole run).
constexpr std::size_t kFractionRun = 64;

// The fractions of a run of pixels divided by their sums, as floats, into the row `out` at the pixels' columns
// `column` (mats values per pixel; M = mats at compile time, or 0 for a run-time count): false, with nothing
// written, unless every value is finite and non-negative and every sum positive and finite (the conditions of
// material_fraction_sum, checked for the whole run without a branch per value, so the loops vectorise).
template <std::size_t M>
bool normalise_fractions(std::span<const double> v, const int* column, float* out, std::size_t mats = M) {
  if (M != 0) mats = M;
  const std::size_t n = v.size() / mats;
  // Counted, not branched on; a NaN fails v >= 0, and non-negative values with a finite sum are finite.
  std::size_t bad = 0;
  for (double f : v) bad += !(f >= 0);
  double sums[kFractionRun];
  for (std::size_t q = 0; q < n; ++q) {
    double sum = v[mats * q];
    for (std::size_t m = 1; m < mats; ++m) sum += v[mats * q + m];
    sums[q] = sum;
  }
  for (std::size_t q = 0; q < n; ++q) bad += !(sums[q] > 0) + !(sums[q] <= std::numeric_limits<double>::max());
  if (bad != 0) return false;
  for (std::size_t q = 0; q < n; ++q) {
    float* o = out + mats * static_cast<std::size_t>(column[q]);
    for (std::size_t m = 0; m < mats; ++m) o[m] = static_cast<float>(v[mats * q + m] / sums[q]);
  }
  return true;
}

// PointInverter::newton's damped iteration (clamped to the domain, step halved until the residual drops) on
// the cell's element polynomials, with the explicit inverse of the 3 x 3 Jacobian: about a fifth of the
// instructions of the B-spline kernels with a rank-revealing QR. True, with u and the residual, when it meets
// tol; a singular Jacobian or a stall gives false, and the caller runs PointInverter::newton from the guess.
bool polynomial_newton(const ElementPolynomials& poly, const Box<3>& dom, const double* x, double tol, int max_it,
                       const Param<3>& guess, Param<3>& u, double& residual) {
  for (int k = 0; k < 3; ++k)
    u[k] = std::isfinite(guess[k]) ? std::clamp(guess[k], dom.lo[k], dom.hi[k]) : 0.5 * (dom.lo[k] + dom.hi[k]);
  double f[12], ft[12];
  auto evaluate = [&](const Param<3>& t, double* out, Eigen::Vector3d& res) {
    poly.eval_first(t, out);
    for (int d = 0; d < 3; ++d) res[d] = x[d] - out[d];
    return res.norm();
  };
  Eigen::Vector3d res, res_t;
  residual = evaluate(u, f, res);
  for (int it = 0; residual > tol && it < max_it; ++it) {
    Eigen::Matrix3d J, inv;
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) J(d, k) = f[3 * (1 + k) + d];
    bool invertible = false;
    double det = 0;
    J.computeInverseAndDetWithCheck(inv, det, invertible, 0.0);
    if (!invertible) return false;
    const Eigen::Vector3d du = inv * res;
    if (!du.allFinite()) return false;
    bool accepted = false;
    double alpha = 1.0;
    for (int h = 0; h < 12 && !accepted; ++h, alpha *= 0.5) {
      Param<3> t;
      bool moved = false;
      for (int k = 0; k < 3; ++k) {
        t[k] = std::clamp(u[k] + alpha * du[k], dom.lo[k], dom.hi[k]);
        moved = moved || t[k] != u[k];
      }
      if (!moved) return false;
      const double tn = evaluate(t, ft, res_t);
      if (tn < residual) {
        u = t;
        residual = tn;
        res = res_t;
        std::copy(ft, ft + 12, f);
        accepted = true;
      }
    }
    if (!accepted) return false;
  }
  return residual <= tol;
}

// First pixel index (0..n) along an axis whose centre origin + (index + 0.5) * size is >= v: rounded, then
// corrected so the comparison is exactly the one the centres give.
int first_centre_at_or_after(double origin, double size, int n, double v) {
  auto centre = [&](int i) { return origin + (i + 0.5) * size; };
  const double e = std::ceil((v - origin) / size - 0.5);
  int i = static_cast<int>(std::clamp(e, 0.0, static_cast<double>(n)));
  while (i > 0 && centre(i - 1) >= v) --i;
  while (i < n && centre(i) < v) ++i;
  return i;
}
int first_row_at_or_above(const SliceGrid& g, double y) { return first_centre_at_or_after(g.y0, g.dy, g.height, y); }
int first_column_at_or_right(const SliceGrid& g, double x) { return first_centre_at_or_after(g.x0, g.dx, g.width, x); }

// Crossings of the segment with the row centre lines y_j in [min y, max y): a vertex on a line belongs to the
// segment above it only, so a closed polygon crosses every line an even number of times. The end points are
// put in a canonical order first, so the same segment from two cells gives bit-identical crossings.
void add_hits(const SliceGrid& g, const OutlineSegment& s, std::vector<Hit>& hits) {
  double xa = s.x0, ya = s.y0, xb = s.x1, yb = s.y1;
  Param<3> ua = s.u0, ub = s.u1;
  if (ya == yb) return;
  if (ya > yb) {
    std::swap(xa, xb);
    std::swap(ya, yb);
    std::swap(ua, ub);
  }
  const int j0 = first_row_at_or_above(g, ya), j1 = first_row_at_or_above(g, yb);
  for (int j = j0; j < j1; ++j) {
    const double t = (g.y(j) - ya) / (yb - ya);
    Hit h{j, xa + (g.y(j) - ya) * (xb - xa) / (yb - ya), {}};
    for (int k = 0; k < 3; ++k) h.u[k] = ua[k] + t * (ub[k] - ua[k]);
    hits.push_back(h);
  }
}

}  // namespace

SliceGrid slice_grid(const VModel& model, const SliceOptions& o) {
  require(model.num_cells() > 0, "slicer: the model has no cells");
  require(model.is_glued(), "slicer: the model is not glued (glue it after adding cells)");
  require(positive_finite(o.layer_thickness),
          [&] { return "slicer: layer thickness must be positive, got " + std::to_string(o.layer_thickness); });
  require(positive_finite(o.dpi_x) && positive_finite(o.dpi_y),
          [&] { return "slicer: dpi must be positive, got " + std::to_string(o.dpi_x) + " x " + std::to_string(o.dpi_y); });
  const Box<3> bb = model.bounding_box();
  SliceGrid g;
  g.dx = 25.4 / o.dpi_x;
  g.dy = 25.4 / o.dpi_y;
  g.x0 = o.origin ? (*o.origin)[0] : bb.lo[0] - g.dx;
  g.y0 = o.origin ? (*o.origin)[1] : bb.lo[1] - g.dy;
  require(std::isfinite(g.x0) && std::isfinite(g.y0), "slicer: the build-plate origin must be finite");
  if (o.image_size) {
    g.width = (*o.image_size)[0];
    g.height = (*o.image_size)[1];
  } else {
    g.width = static_cast<int>(std::min(std::ceil((bb.hi[0] + g.dx - g.x0) / g.dx), 1e9));
    g.height = static_cast<int>(std::min(std::ceil((bb.hi[1] + g.dy - g.y0) / g.dy), 1e9));
  }
  require(g.width >= 1 && g.height >= 1, [&] {
    return "slicer: empty image " + std::to_string(g.width) + " x " + std::to_string(g.height) + " pixels";
  });
  const double z0 = o.z_range ? (*o.z_range)[0] : bb.lo[2];
  const double z1 = o.z_range ? (*o.z_range)[1] : bb.hi[2];
  require(std::isfinite(z0) && std::isfinite(z1) && z0 < z1,
          [&] { return "slicer: empty z range [" + std::to_string(z0) + ", " + std::to_string(z1) + "]"; });
  g.z0 = z0;
  g.thickness = o.layer_thickness;
  // The guard keeps an exact multiple (1.0 / 0.1 = 10.000000000000002) from adding an empty layer.
  const double n = std::ceil((z1 - z0) / o.layer_thickness * (1 - 1e-12));
  require(n <= 1e7, "slicer: more than 1e7 layers");
  g.layers = std::max(1, static_cast<int>(n));
  return g;
}

LayerSlicer::LayerSlicer(const VModel& model, const SliceOptions& options)
    : model_(model), options_(options), grid_(slice_grid(model, options)) {
  require(positive_finite(options.outline_tolerance), "slicer: outline tolerance must be positive");
  require(options.samples_per_span >= 1, "slicer: samples per span must be >= 1");
  const int n = model.num_cells();
  const VTopology& topo = model.topology();
  SectionOptions so;
  so.samples_per_span = options.samples_per_span;
  so.tolerance = options.outline_tolerance * std::min(grid_.dx, grid_.dy);
  const std::string name = options.material_attribute.value_or("material");
  int with_material = 0;
  for (int c = 0; c < n; ++c) {
    const VCell& cell = model.cell(c);
    sections_.emplace_back(cell.geometry(), so);
    inverters_.emplace_back(cell.geometry(), options.inversion);
    polynomials_.emplace_back(cell.geometry());
    Box<3> b;
    cell.geometry().control_bounds(b.lo.data(), b.hi.data());
    boxes_.push_back(b);
    domains_.push_back(cell.geometry().domain());
    std::array<bool, 6> boundary{};
    for (int f = 0; f < 6; ++f) boundary[f] = topo.halves[static_cast<std::size_t>(6 * c + f)].twin < 0;
    model_face_.push_back(boundary);
    with_material += cell.has_attribute(name) ? 1 : 0;
  }
  material_.assign(static_cast<std::size_t>(n), nullptr);
  require(with_material > 0 || !options.material_attribute,
          [&] { return "slicer: no cell has the material attribute '" + name + "'"; });
  if (with_material == 0) return;
  for (int c = 0; c < n; ++c) {
    require(model.cell(c).has_attribute(name), [&] {
      return "slicer: cell " + std::to_string(c) + " has no attribute '" + name +
             "' (other cells have it)";
    });
    const Attribute& a = model.cell(c).attribute(name);
    if (c == 0) materials_ = a.components();
    require(a.components() == materials_, [&] {
      return "slicer: attribute '" + name + "' has " + std::to_string(a.components()) +
             " components in cell " + std::to_string(c) + " but " + std::to_string(materials_) + " in cell 0";
    });
    material_[static_cast<std::size_t>(c)] = &a;
  }
  check_material_fractions(model, name);
  require(materials_ <= MaterialTable::max_materials, "slicer: more than 255 materials");
  require(model.materials().empty() || model.materials().size() == materials_, [&] {
    return "slicer: the model names " + std::to_string(model.materials().size()) + " materials but attribute '" +
           name + "' has " + std::to_string(materials_) + " components";
  });
}

SliceLayer LayerSlicer::slice(int k) const {
  SliceLayer L;
  slice(k, L);
  return L;
}

void LayerSlicer::slice(int k, SliceLayer& L) const {
  require(k >= 0 && k < grid_.layers,
          [&] { return "slicer: layer " + std::to_string(k) + " out of range 0.." + std::to_string(grid_.layers - 1); });
  const SliceGrid& g = grid_;
  const int n = static_cast<int>(sections_.size()), w = g.width, h = g.height;
  const auto uw = static_cast<std::size_t>(w), mats = static_cast<std::size_t>(materials_);
  if (L.width == w && L.height == h && L.cell.size() == uw * static_cast<std::size_t>(h) &&
      L.fractions.width() == w && L.fractions.height() == h && L.fractions.channels() == materials_ &&
      L.fractions.data().size() == uw * static_cast<std::size_t>(h) * mats &&
      L.row_extents.size() == static_cast<std::size_t>(h)) {
    for (int j = 0; j < h; ++j) {
      const auto [a, b] = L.row_extents[static_cast<std::size_t>(j)];
      std::fill(L.cell.data() + j * uw + a, L.cell.data() + j * uw + b, -1);
      std::fill(L.fractions.pixel(a, j), L.fractions.pixel(a, j) + mats * static_cast<std::size_t>(b - a), 0.0f);
    }
  } else {
    L.width = w;
    L.height = h;
    L.cell.assign(uw * static_cast<std::size_t>(h), -1);
    L.fractions = FractionImage(w, h, materials_, 0.0f);
  }
  L.row_extents.assign(static_cast<std::size_t>(h), {0, 0});
  L.index = k;
  L.z = g.z(k);
  L.stats = {};
  const double z = L.z;

  // Row crossings per cell and of the model boundary, sorted by (row, x).
  std::vector<std::vector<Hit>> hits(static_cast<std::size_t>(n));
  std::vector<Hit> model_hits;
  std::vector<OutlineSegment> segments;
  for (int c = 0; c < n; ++c) {
    segments.clear();
    sections_[static_cast<std::size_t>(c)].section(z, segments);
    for (const auto& s : segments) {
      add_hits(g, s, hits[static_cast<std::size_t>(c)]);
      if (model_face_[static_cast<std::size_t>(c)][static_cast<std::size_t>(s.face)]) add_hits(g, s, model_hits);
    }
    std::sort(hits[static_cast<std::size_t>(c)].begin(), hits[static_cast<std::size_t>(c)].end());
  }
  std::sort(model_hits.begin(), model_hits.end());

  // Calls paint(i_begin, i_end, entry crossing) for the even-odd spans of row j and advances `pos` past the row.
  auto spans = [&](const std::vector<Hit>& hs, std::size_t& pos, int j, auto&& paint) {
    while (pos < hs.size() && hs[pos].row < j) ++pos;
    std::size_t e = pos;
    while (e < hs.size() && hs[e].row == j) ++e;
    for (std::size_t q = pos; q + 1 < e; q += 2)
      paint(first_column_at_or_right(g, hs[q].x), first_column_at_or_right(g, hs[q + 1].x), hs[q]);
    pos = e;
  };

  const Tracing tracing = options_.tracing;
  const bool along_row = tracing == Tracing::previous_point || tracing == Tracing::full;
  const bool from_outline = tracing == Tracing::full;
  const bool from_below = tracing == Tracing::previous_line || tracing == Tracing::full;
  constexpr int kUnclaimed = -2;  // inside the part by the model fill, claimed by no cell
  std::vector<std::size_t> pos(static_cast<std::size_t>(n), 0);
  std::size_t model_pos = 0;
  std::vector<Param<3>> cur(static_cast<std::size_t>(w)), prev(static_cast<std::size_t>(w)), seed(static_cast<std::size_t>(w));
  std::vector<int> seed_cell(static_cast<std::size_t>(w), -1);
  // Pixel columns, parameters and model points of the pending run of pixels.
  std::array<int, kFractionRun> batch_i;
  std::array<Param<3>, kFractionRun> batch_u;
  std::array<double, 3 * kFractionRun> batch_x;
  std::vector<double> values(kFractionRun * mats);
  std::size_t batched = 0;
  int batch_cell = -1;
  auto flush = [&](int j) {
    if (batched == 0) return;
    const int c = batch_cell;
    const Attribute& a = *material_[static_cast<std::size_t>(c)];
    if (a.uses_model_point())
      a.eval_model_points(std::span<const double>(batch_x.data(), 3 * batched), values.data());
    else
      a.eval_many(model_.cell(c).geometry(), std::span<const Param<3>>(batch_u.data(), batched), nullptr, values.data());
    const std::span<const double> v(values.data(), mats * batched);
    const bool ok = mats == 2 ? normalise_fractions<2>(v, batch_i.data(), L.fractions.pixel(0, j))
                              : normalise_fractions<0>(v, batch_i.data(), L.fractions.pixel(0, j), mats);
    if (!ok)  // the message names the first bad pixel
      for (std::size_t q = 0; q < batched; ++q)
        material_fraction_sum(v.subspan(mats * q, mats), [&] { return cell_point(c, batch_u[q]); });
    batched = 0;
  };
  LayerStats& st = L.stats;
  for (int j = 0; j < h; ++j) {
    int* row = L.cell.data() + static_cast<std::size_t>(j) * static_cast<std::size_t>(w);
    // Later cells first, so the first claiming cell ends up on top. [first, last) covers every painted pixel
    // (and every seed): the solve loop skips the rest of the row, most of the tray.
    int first = w, last = 0;
    for (int c = n - 1; c >= 0; --c)
      spans(hits[static_cast<std::size_t>(c)], pos[static_cast<std::size_t>(c)], j, [&](int a, int b, const Hit& entry) {
        std::fill(row + a, row + b, c);
        if (a < b) {
          seed[static_cast<std::size_t>(a)] = entry.u;
          seed_cell[static_cast<std::size_t>(a)] = c;
          first = std::min(first, a);
          last = std::max(last, b);
        }
      });
    spans(model_hits, model_pos, j, [&](int a, int b, const Hit&) {
      for (int i = a; i < b; ++i)
        if (row[i] == -1) row[i] = kUnclaimed;
      if (a < b) {
        first = std::min(first, a);
        last = std::max(last, b);
      }
    });

    if (first < last) L.row_extents[static_cast<std::size_t>(j)] = {first, last};
    // Inverse Jacobian of the last pixel solved on this row, for chord steps in the same cell.
    Eigen::Matrix3d chord_inverse = Eigen::Matrix3d::Zero();
    int chord_cell = -1, chord_age = 0;
    // The cell of the pixels just left of i and how many of them (at most 5) are in it, after their solve.
    int streak_cell = -1, streak = 0;
    for (int i = first; i < last; ++i) {
      if (i > first) {
        streak = row[i - 1] == streak_cell ? std::min(streak + 1, kStreakMax) : 1;
        streak_cell = row[i - 1];
      }
      int c = row[i];
      const auto ui = static_cast<std::size_t>(i);
      const int seeded = std::exchange(seed_cell[ui], -1);
      if (c == -1) continue;
      const double x[3] = {g.x(i), g.y(j), z};
      InversionResult<3> r;
      bool ok = false, newton_used = false, next_set = false;  // next_set: solved by chord steps, point = s(r.param)
      Param<3> next;
      double point[3];
      if (c >= 0) {
        const PointInverter<3>& inv = inverters_[static_cast<std::size_t>(c)];
        const TensorSpline<3>& geo = inv.spline();
        const ElementPolynomials& poly = polynomials_[static_cast<std::size_t>(c)];
        auto newton_from = [&](const Param<3>& guess) {
          newton_used = true;
          if (poly.available() &&
              polynomial_newton(poly, domains_[static_cast<std::size_t>(c)], x, inv.absolute_tolerance(),
                                inv.options().max_newton, guess, r.param, r.residual))
            return r.converged = true;
          r = inv.newton(x, guess);
          return r.converged;
        };
        if (along_row && streak_cell == c) {
          // Polynomial extrapolation through up to five previous pixels of the cell (see kStreakMax).
          const Param<3>& a = cur[ui - 1];
          Param<3> guess = a;
          if (streak >= 2) {
            const Param<3>& b = cur[ui - 2];
            if (streak == 2)
              for (int d = 0; d < 3; ++d) guess[d] = 2 * a[d] - b[d];
            else if (streak == 3)
              for (int d = 0; d < 3; ++d) guess[d] = (3 * a[d] - 3 * b[d]) + cur[ui - 3][d];
            else if (streak == 4)
              for (int d = 0; d < 3; ++d) guess[d] = ((4 * a[d] - 6 * b[d]) + 4 * cur[ui - 3][d]) - cur[ui - 4][d];
            else
              for (int d = 0; d < 3; ++d)
                guess[d] = (((5 * a[d] - 10 * b[d]) + 10 * cur[ui - 3][d]) - 5 * cur[ui - 4][d]) + cur[ui - 5][d];
          }
          if (chord_cell == c) {
            r.param = guess;
            auto value = [&](const Param<3>& u, double* p) { poly.available() ? poly.eval(u, p) : geo.eval(u, p); };
            ok = chord_solve(value, domains_[static_cast<std::size_t>(c)], chord_inverse, x, inv.absolute_tolerance(),
                             r.param, r.residual, next, point);
          }
          next_set = ok;
          ok = ok || newton_from(guess);
        }
        if (!ok && from_outline && seeded == c) ok = newton_from(seed[ui]);
        if (!ok && from_below && j >= 1) {
          // The pixel below, else the nearest pixel of the cell on the previous row (where a row enters the
          // cell, its boundary has moved sideways since the previous row).
          const int* below = row - w;
          int near = -1;
          for (int d = 0; near < 0 && (i - d >= 0 || i + d < w); ++d) {
            if (i - d >= 0 && below[i - d] == c) near = i - d;
            else if (i + d < w && below[i + d] == c) near = i + d;
          }
          if (near >= 0) ok = newton_from(prev[static_cast<std::size_t>(near)]);
        }
        if (!ok) {
          r = inv.invert(x);
          ++st.full_solves;
          newton_used = true;
          ok = r.found && r.converged;
        }
      }
      if (!ok) {
        for (int c2 = 0; c2 < n && !ok; ++c2) {
          const PointInverter<3>& inv = inverters_[static_cast<std::size_t>(c2)];
          if (c2 == c || !boxes_[static_cast<std::size_t>(c2)].contains({x[0], x[1], x[2]}, inv.absolute_tolerance()))
            continue;
          r = inv.invert(x);
          ++st.full_solves;
          if (r.found && r.converged) {
            c = c2;
            ok = true;
            ++st.corrected_pixels;
          }
        }
      }
      if (!ok) {
        row[i] = -1;
        continue;
      }
      if (along_row && (newton_used || c != chord_cell || ++chord_age >= kChordRefresh)) {
        chord_cell = jacobian_inverse(inverters_[static_cast<std::size_t>(c)].spline(),
                                      polynomials_[static_cast<std::size_t>(c)], r.param, chord_inverse)
                         ? c
                         : -1;
        chord_age = 0;
      }
      row[i] = c;
      cur[static_cast<std::size_t>(i)] = next_set ? next : r.param;
      ++st.inside_pixels;
      st.max_residual = std::max(st.max_residual, r.residual);

      const Attribute* a = material_[static_cast<std::size_t>(c)];
      if (!a) {
        L.fractions.pixel(i, j)[0] = 1.0f;
        continue;
      }
      if (c != batch_cell || batched == kFractionRun) flush(j);
      batch_cell = c;
      batch_i[batched] = i;
      batch_u[batched] = r.param;
      if (a->uses_model_point()) {
        double* p = batch_x.data() + 3 * batched;
        if (next_set) {
          std::copy(point, point + 3, p);
        } else {
          // Newton and the robust search end with derivatives; the value kernel gives the point eval() would.
          const Box<3>& dom = domains_[static_cast<std::size_t>(c)];
          Param<3> t;
          for (int d = 0; d < 3; ++d) t[d] = std::clamp(r.param[d], dom.lo[d], dom.hi[d]);
          model_.cell(c).geometry().eval(t, p);
        }
      }
      ++batched;
    }
    flush(j);
    std::swap(cur, prev);
  }
}

}  // namespace trivar::am
