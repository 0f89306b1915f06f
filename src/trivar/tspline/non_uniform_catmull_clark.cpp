#include "trivar/tspline/non_uniform_catmull_clark.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

namespace {

using Comb = std::map<int, double>;  // a point of the next level as weights over the previous level

void add(Comb& a, const Comb& b, double s) {
  for (const auto& [i, w] : b) a[i] += s * w;
}

constexpr int kW = NonUniformStar::kWindow;

// The rules of one subdivision step (see the header) on a window whose points exist up to `valid` per sector.
class Rules {
public:
  Rules(int n, int valid, std::function<double(int, int)> w, std::function<double(int)> across)
      : n_(n), valid_(valid), w_(std::move(w)), across_(std::move(across)) {}

  int id(int k, int i, int j) const {
    k = ((k % n_) + n_) % n_;
    if (i == 0 && j == 0) return 0;
    if (j < 0) return id(k - 1, -j, i);  // (i, -r) is (r, i) of the sector before
    if (i < 0) return id(k + 1, j, -i);  // (-r, j) is (j, r) of the sector after
    if (i == 0) return id(k + 1, j, 0);
    if (i > valid_ || j > valid_) throw Error("non-uniform Catmull-Clark: point outside the subdivision window");
    return 1 + k * kW * (kW + 1) + (i - 1) * (kW + 1) + j;
  }
  double w(int k, int i) const { return w_(((k % n_) + n_) % n_, i); }
  // The interval between columns i and i + 1 on row j of sector k, and between rows j and j + 1 on column i.
  double ucol(int k, int i, int j) const {
    if (i >= 0) return w(k, i);
    if (j == 0) {
      if (i != -1) throw Error("non-uniform Catmull-Clark: interval two beyond the star point");
      return across_(((k % n_) + n_) % n_);
    }
    return w(k + 2, -1 - i);
  }
  double vrow(int k, int i, int j) const {
    if (j >= 0) return w(k + 1, j);
    if (i == 0) {
      if (j != -1) throw Error("non-uniform Catmull-Clark: interval two beyond the star point");
      return across_((((k + 1) % n_) + n_) % n_);
    }
    return w(k - 1, -1 - j);
  }
  Comb pt(int k, int i, int j) const { return {{id(k, i, j), 1.0}}; }
  static Comb curve(const Comb& p, const Comb& q, double before, double d, double after) {
    Comb c;
    const auto [wp, wq] = nurcc_curve_weights(before, d, after);
    add(c, p, wp);
    add(c, q, wq);
    return c;
  }
  Comb face(int k, int a, int b) const {
    if (b < 0) return face(k - 1, -b - 1, a);
    if (a < 0) return face(k + 1, b, -a - 1);
    const double du = w(k, a), nu = w(k, a + 1), pu = 0.5 * (ucol(k, a - 1, b) + ucol(k, a - 1, b + 1));
    const double dv = w(k + 1, b), nv = w(k + 1, b + 1), pv = 0.5 * (vrow(k, a, b - 1) + vrow(k, a + 1, b - 1));
    const std::array<double, 2> wu = nurcc_curve_weights(pu, du, nu), wv = nurcc_curve_weights(pv, dv, nv);
    Comb c;
    for (int t = 0; t < 2; ++t)
      for (int s = 0; s < 2; ++s) add(c, pt(k, a + s, b + t), wu[static_cast<std::size_t>(s)] * wv[static_cast<std::size_t>(t)]);
    return c;
  }
  Comb u_edge(int k, int a, int b) const {
    const double ep = w(k + 1, b), em = b >= 1 ? w(k + 1, b - 1) : w(k - 1, 0);
    Comb c;
    add(c, face(k, a, b - 1), ep / (2 * (em + ep)));
    add(c, face(k, a, b), em / (2 * (em + ep)));
    add(c, curve(pt(k, a, b), pt(k, a + 1, b), ucol(k, a - 1, b), w(k, a), w(k, a + 1)), 0.5);
    return c;
  }
  Comb v_edge(int k, int a, int b) const {
    const double em = w(k, a - 1), ep = w(k, a);
    Comb c;
    add(c, face(k, a - 1, b), ep / (2 * (em + ep)));
    add(c, face(k, a, b), em / (2 * (em + ep)));
    add(c, curve(pt(k, a, b), pt(k, a, b + 1), vrow(k, a, b - 1), w(k + 1, b), w(k + 1, b + 1)), 0.5);
    return c;
  }
  Comb vertex(int k, int a, int b) const {
    // Spokes +u, +v, -u, -v: interval, opposite interval, interval beyond the far end, far end.
    struct Spoke {
      double d, o, n;
      Comb q;
    };
    const std::array<Spoke, 4> s{{{w(k, a), ucol(k, a - 1, b), w(k, a + 1), pt(k, a + 1, b)},
                                  {w(k + 1, b), vrow(k, a, b - 1), w(k + 1, b + 1), pt(k, a, b + 1)},
                                  {ucol(k, a - 1, b), w(k, a), ucol(k, a - 2, b), pt(k, a - 1, b)},
                                  {vrow(k, a, b - 1), w(k + 1, b), vrow(k, a, b - 2), pt(k, a, b - 1)}}};
    const std::array<Comb, 4> f{face(k, a, b), face(k, a - 1, b), face(k, a - 1, b - 1), face(k, a, b - 1)};
    const Comb p = pt(k, a, b);
    const std::array<double, 4> spokes{s[0].d, s[1].d, s[2].d, s[3].d};  // each spoke's o is the opposite one's d
    const VertexWeights vw = nurcc_vertex_weights(spokes);
    Comb c;
    for (std::size_t m = 0; m < 4; ++m) {
      add(c, f[m], vw.faces[m]);
      add(c, curve(p, s[m].q, s[m].o, s[m].d, s[m].n), vw.curves[m]);
    }
    add(c, p, vw.self);
    return c;
  }
  // The vertex rule of the star point: the general one (nurcc_vertex_weights) with the first intervals of its
  // spokes.
  Comb star(std::span<const double> spokes) const {
    const VertexWeights vw = nurcc_vertex_weights(spokes);
    Comb c;
    for (int k = 0; k < n_; ++k) {
      add(c, face(k, 0, 0), vw.faces[static_cast<std::size_t>(k)]);
      add(c, curve(pt(k, 0, 0), pt(k, 1, 0), across_(k), w(k, 0), w(k, 1)), vw.curves[static_cast<std::size_t>(k)]);
    }
    c[0] += vw.self;
    return c;
  }

private:
  int n_, valid_;
  std::function<double(int, int)> w_;
  std::function<double(int)> across_;
};

}  // namespace

std::array<double, 2> nurcc_curve_weights(double before, double d, double after) {
  const double s = 2 * (before + d + after);
  return {(d + 2 * after) / s, (2 * before + d) / s};
}

std::vector<double> nurcc_across_weights(int n, int k) {
  std::vector<double> w(static_cast<std::size_t>(n));
  double t = 0;
  for (int m = 0; m < n; ++m) {
    const double c = std::max(0.0, -std::cos(2 * std::numbers::pi * (m - k) / n));
    w[static_cast<std::size_t>(m)] = c < 1e-12 ? 0 : c;
    t += w[static_cast<std::size_t>(m)];
  }
  for (double& x : w) x /= t;
  return w;
}

double nurcc_across(std::span<const double> spokes, int k) {
  const std::vector<double> w = nurcc_across_weights(static_cast<int>(spokes.size()), k);
  double s = 0;
  for (std::size_t m = 0; m < w.size(); ++m) s += w[m] * spokes[m];
  return s;
}

// At a vertex of four faces the weights 16 / N^2 a_k a_(k+1) and 8 / N^2 a_k are the tensor product rule's
// a_s a_t and a_s / 2 (a_s + a_(s+2) = 1/2, so the vertex keeps 1/4): one formula for all valences.
VertexWeights nurcc_vertex_weights(std::span<const double> spokes) {
  const int n = static_cast<int>(spokes.size());
  const double nn = static_cast<double>(n) * n;
  std::vector<double> a(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double o = nurcc_across(spokes, k);
    a[static_cast<std::size_t>(k)] = o / (2 * (spokes[static_cast<std::size_t>(k)] + o));
  }
  VertexWeights vw;
  for (int k = 0; k < n; ++k) {
    vw.faces.push_back(16 / nn * a[static_cast<std::size_t>(k)] * a[static_cast<std::size_t>((k + 1) % n)]);
    vw.curves.push_back(8 / nn * a[static_cast<std::size_t>(k)]);
    vw.self -= vw.faces.back() + vw.curves.back();
  }
  return vw;
}

std::array<double, 3> nurcc_curve_vertex_weights(double before, double after) {
  const double s = 2 * (before + after);
  return {after / s, before / s, 0.5};
}

std::array<double, 2> natural_end_weights(double d1, double d2) { return {(d1 + d2) / (2 * d1 + d2), d1 / (2 * d1 + d2)}; }

NonUniformStar::NonUniformStar(int valence, std::vector<std::array<double, 4>> intervals)
    : n_(valence), u_(std::move(intervals)) {
  require(valence >= 3 && valence <= 64, "non-uniform Catmull-Clark: valence " + std::to_string(valence) + " outside 3..64");
  require(static_cast<int>(u_.size()) == valence, "non-uniform Catmull-Clark: one interval row per spoke");
  for (const auto& r : u_)
    for (double d : r)
      require(std::isfinite(d) && d > 0, "non-uniform Catmull-Clark: knot interval " + std::to_string(d) + " is not positive");
  for (int l = 0; l < 4; ++l) build_step(l, steps_[static_cast<std::size_t>(l)]);
  build_eigen();
}

double NonUniformStar::interval(int level, int spoke, int i) const {
  return u_[static_cast<std::size_t>(spoke)][static_cast<std::size_t>(std::min(i >> std::min(level, 3), 3))];
}

double NonUniformStar::across(int spoke) const { return nurcc_across(first_intervals(), spoke); }

std::vector<double> NonUniformStar::first_intervals() const {
  std::vector<double> d;
  for (const auto& r : u_) d.push_back(r[0]);
  return d;
}

void NonUniformStar::build_step(int level, std::vector<Row>& rows) const {
  const Rules r(n_, level == 0 ? kRings : kW, [this, level](int k, int i) { return interval(level, k, i); },
                [this](int k) { return across(k); });
  rows.assign(static_cast<std::size_t>(window_size()), {});
  const auto put = [&](int at, const Comb& c) {
    Row& row = rows[static_cast<std::size_t>(at)];
    for (const auto& [i, w] : c)
      if (w != 0) row.emplace_back(i, w);
  };
  put(0, r.star(first_intervals()));
  for (int k = 0; k < n_; ++k)
    for (int i = 1; i <= kW; ++i)
      for (int j = 0; j <= kW; ++j) {
        const int at = 1 + k * kW * (kW + 1) + (i - 1) * (kW + 1) + j;
        const int a = i / 2, b = j / 2;
        if (i % 2 == 0 && j % 2 == 0)
          put(at, r.vertex(k, a, b));
        else if (j % 2 == 0)
          put(at, r.u_edge(k, a, b));
        else if (i % 2 == 0)
          put(at, r.v_edge(k, a, b));
        else
          put(at, r.face(k, a, b));
      }
}

void NonUniformStar::build_eigen() {
  // The one-ring (star, (k, 1, 0), (k, 1, 1)) is invariant under the stationary step.
  const int m = 2 * n_ + 1;
  std::vector<int> ring{0};
  for (int k = 0; k < n_; ++k) {
    ring.push_back(1 + k * kW * (kW + 1));
    ring.push_back(1 + k * kW * (kW + 1) + 1);
  }
  std::vector<int> pos(static_cast<std::size_t>(window_size()), -1);
  for (int i = 0; i < m; ++i) pos[static_cast<std::size_t>(ring[static_cast<std::size_t>(i)])] = i;
  std::vector<double> s(static_cast<std::size_t>(m * m), 0.0);
  for (int i = 0; i < m; ++i)
    for (const auto& [j, w] : steps_[3][static_cast<std::size_t>(ring[static_cast<std::size_t>(i)])]) {
      const int c = pos[static_cast<std::size_t>(j)];
      require(c >= 0, "non-uniform Catmull-Clark: the one-ring is not invariant");
      s[static_cast<std::size_t>(i * m + c)] += w;
    }
  const auto at = [&](int i, int j) { return s[static_cast<std::size_t>(i * m + j)]; };
  const auto dot = [&](const std::vector<double>& a, const std::vector<double>& b) {
    double t = 0;
    for (int i = 0; i < m; ++i) t += a[static_cast<std::size_t>(i)] * b[static_cast<std::size_t>(i)];
    return t;
  };
  // Left eigenvector of eigenvalue 1 (rows sum to 1) by power iteration on S^T.
  std::vector<double> l(static_cast<std::size_t>(m), 1.0 / m), t(static_cast<std::size_t>(m));
  for (int it = 0; it < 2000; ++it) {
    std::fill(t.begin(), t.end(), 0.0);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) t[static_cast<std::size_t>(j)] += at(i, j) * l[static_cast<std::size_t>(i)];
    double sum = 0;
    for (double x : t) sum += x;
    for (int i = 0; i < m; ++i) t[static_cast<std::size_t>(i)] /= sum;
    double change = 0;
    for (int i = 0; i < m; ++i) change = std::max(change, std::abs(t[static_cast<std::size_t>(i)] - l[static_cast<std::size_t>(i)]));
    l.swap(t);
    if (change < 1e-17) break;
  }
  limit_ = l;
  // The dominant two-dimensional invariant subspaces of S^T (tangent functionals, orthogonal to the constants'
  // complement: x . 1 = 0 is kept by projecting out l) and of S (characteristic map: l . x = 0), by orthogonal
  // iteration; then the pair is made biorthonormal so that chart . tangent reproduces the one-ring's tangent part.
  const auto iterate = [&](bool transpose, std::array<std::vector<double>, 2>& q, std::array<double, 2>& lambda) {
    for (int c = 0; c < 2; ++c) {
      q[static_cast<std::size_t>(c)].assign(static_cast<std::size_t>(m), 0.0);
      for (int i = 0; i < m; ++i) q[static_cast<std::size_t>(c)][static_cast<std::size_t>(i)] = std::sin(1.0 + i * (c + 1.3) + c);
    }
    for (int it = 0; it < 3000; ++it) {
      std::array<std::vector<double>, 2> y{std::vector<double>(static_cast<std::size_t>(m), 0.0), std::vector<double>(static_cast<std::size_t>(m), 0.0)};
      for (std::size_t c = 0; c < 2; ++c) {
        for (int i = 0; i < m; ++i)
          for (int j = 0; j < m; ++j) {
            if (transpose)
              y[c][static_cast<std::size_t>(j)] += at(i, j) * q[c][static_cast<std::size_t>(i)];
            else
              y[c][static_cast<std::size_t>(i)] += at(i, j) * q[c][static_cast<std::size_t>(j)];
          }
        // Out of the eigenvalue-1 space: left vectors lose their l component along 1, right ones their
        // constant along l.
        double proj = 0;
        for (int i = 0; i < m; ++i) proj += transpose ? y[c][static_cast<std::size_t>(i)] : l[static_cast<std::size_t>(i)] * y[c][static_cast<std::size_t>(i)];
        for (int i = 0; i < m; ++i) y[c][static_cast<std::size_t>(i)] -= proj * (transpose ? l[static_cast<std::size_t>(i)] : 1.0);
      }
      if (it == 2999) lambda = {std::sqrt(dot(y[0], y[0])), 0};
      // Gram-Schmidt.
      const double n0 = std::sqrt(dot(y[0], y[0]));
      for (double& x : y[0]) x /= n0;
      const double p = dot(y[0], y[1]);
      for (int i = 0; i < m; ++i) y[1][static_cast<std::size_t>(i)] -= p * y[0][static_cast<std::size_t>(i)];
      const double n1 = std::sqrt(dot(y[1], y[1]));
      for (double& x : y[1]) x /= n1;
      if (it == 2999) lambda = {n0, n1};
      q = std::move(y);
    }
  };
  std::array<std::vector<double>, 2> left, right;
  iterate(true, left, lambda_);
  std::array<double, 2> lr{};
  iterate(false, right, lr);
  // C = (L^T R)^-1 so that R C L^T is the projector onto the subdominant part.
  const double a = dot(left[0], right[0]), b = dot(left[0], right[1]), c = dot(left[1], right[0]), d = dot(left[1], right[1]);
  const double det = a * d - b * c;
  require(std::abs(det) > 1e-12, "non-uniform Catmull-Clark: no tangent plane at the star point (degenerate subdominant eigenvectors)");
  // tangent_m = sum_n Cinv... : chart (R rows) times C gives the chart coordinates to pair with L.
  chart_.assign(static_cast<std::size_t>(m), {});
  for (int i = 0; i < m; ++i) {
    const double r0 = right[0][static_cast<std::size_t>(i)], r1 = right[1][static_cast<std::size_t>(i)];
    chart_[static_cast<std::size_t>(i)] = {(r0 * d - r1 * c) / det, (-r0 * b + r1 * a) / det};
  }
  tangent_ = left;
  // The same functionals on the level-0 points: back through the first three steps.
  std::array<std::vector<double>, 3> g;
  for (std::size_t e = 0; e < 3; ++e) {
    std::vector<double> x(static_cast<std::size_t>(window_size()), 0.0);
    const std::vector<double>& src = e == 0 ? limit_ : tangent_[e - 1];
    for (int i = 0; i < m; ++i) x[static_cast<std::size_t>(ring[static_cast<std::size_t>(i)])] = src[static_cast<std::size_t>(i)];
    for (int level = 2; level >= 0; --level) {
      std::vector<double> y(x.size(), 0.0);
      const auto& rows = steps_[static_cast<std::size_t>(level)];
      for (std::size_t r = 0; r < rows.size(); ++r)
        for (const auto& [j, w] : rows[r]) y[static_cast<std::size_t>(j)] += w * x[r];
      x.swap(y);
    }
    g[e].assign(static_cast<std::size_t>(size()), 0.0);
    g[e][0] = x[0];
    for (int k = 0; k < n_; ++k)
      for (int i = 1; i <= kRings; ++i)
        for (int j = 0; j <= kRings; ++j)
          g[e][static_cast<std::size_t>(index(k, i, j))] = x[static_cast<std::size_t>(1 + k * kW * (kW + 1) + (i - 1) * (kW + 1) + j)];
  }
  limit0_ = std::move(g[0]);
  tangent0_ = {std::move(g[1]), std::move(g[2])};
}

void NonUniformStar::apply(int level, int radius, int sector, const std::vector<std::array<double, 4>>& p,
                           std::vector<std::array<double, 4>>& q) const {
  const auto& rows = steps_[static_cast<std::size_t>(std::min(level, 3))];
  const std::size_t per = static_cast<std::size_t>(kW * (kW + 1));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (r == 0 && sector >= 0) continue;
    if (r > 0) {
      const std::size_t local = (r - 1) % per;
      if (static_cast<int>(local) / (kW + 1) + 1 > radius || static_cast<int>(local) % (kW + 1) > radius) continue;
      const int m = static_cast<int>((r - 1) / per), dist = ((m - sector) % n_ + n_) % n_;
      if (sector >= 0 && dist > 1 && dist < n_ - 1) continue;
    }
    std::array<double, 4> s{};
    for (const auto& [j, w] : rows[r])
      for (std::size_t c = 0; c < 4; ++c) s[c] += w * p[static_cast<std::size_t>(j)][c];
    q[r] = s;
  }
}

void NonUniformStar::eval(std::span<const std::array<double, 4>> points, int sector, double x, double y, double* out,
                          std::optional<std::array<int, 2>> face) const {
  require(static_cast<int>(points.size()) == size(), "non-uniform Catmull-Clark: wrong number of control points");
  require(sector >= 0 && sector < n_ && x >= 0 && y >= 0 && std::max(x, y) <= 2,
          "non-uniform Catmull-Clark: (x, y) outside the star point's faces");
  // The limit point and the tangent functionals straight from the level-0 points.
  std::array<double, 4> origin{};
  std::array<std::array<double, 4>, 2> tangent{};
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t c = 0; c < 4; ++c) {
      origin[c] += limit0_[i] * points[i][c];
      for (std::size_t e = 0; e < 2; ++e) tangent[e][c] += tangent0_[e][i] * points[i][c];
    }
  const double mx = std::max(x, y);
  if (mx == 0) {
    // The characteristic map's directions from the star point to the spokes k and k + 1.
    for (int e = 0; e < 2; ++e) {
      const auto& ch = chart_[static_cast<std::size_t>(1 + 2 * ((sector + e) % n_))];
      const auto& c0 = chart_[0];
      for (std::size_t c = 0; c < 4; ++c) out[4 + 4 * e + c] = (ch[0] - c0[0]) * tangent[0][c] + (ch[1] - c0[1]) * tangent[1][c];
    }
    for (std::size_t c = 0; c < 4; ++c) out[c] = origin[c];
    return;
  }
  // Relative to the limit point (the rules are affine): the points of level j then have the size of the
  // neighbourhood, and their rounding, scaled by 2^j in the derivatives, stays small.
  const std::size_t ws = static_cast<std::size_t>(window_size());
  std::vector<std::array<double, 4>> p(ws), q(ws);
  const auto rel = [&](const std::array<double, 4>& a) {
    return std::array<double, 4>{a[0] - origin[0], a[1] - origin[1], a[2] - origin[2], a[3] - origin[3]};
  };
  p[0] = rel(points[0]);
  for (int k = 0; k < n_; ++k)
    for (int i = 1; i <= kRings; ++i)
      for (int j = 0; j <= kRings; ++j)
        p[static_cast<std::size_t>(1 + k * kW * (kW + 1) + (i - 1) * (kW + 1) + j)] = rel(points[static_cast<std::size_t>(index(k, i, j))]);
  // Level of the exact cell: max(x, y) 2^level in [2, 4); x = y = 0 (or beyond double range): the star point. In
  // the face (0, 0) the cells of its outer sides are those below them: max(x, y) 2^level in (2, 4].
  const bool closed = face && (*face)[0] == 0 && (*face)[1] == 0;
  const auto below = [closed](double t) { return closed ? t <= 2 : t < 2; };
  int level = 0, levels = 1;
  for (double t = 2 * mx; below(t) && levels < 1100; t *= 2) ++levels;
  double sx = x, sy = y;
  while ((level == 0 || below(std::max(sx, sy))) && level < 1100) {  // level 0 holds points up to 3 only
    // The last step makes the cell's points (up to 5 per direction) from points up to 3; the steps before
    // need only those (points up to 3 from points up to 2).
    // The cell's points lie in the sectors k - 1 .. k + 1 and off the star point.
    apply(level, level + 1 == levels ? kW : 3, level + 1 == levels ? sector : -1, p, q);
    p.swap(q);
    sx *= 2;
    sy *= 2;
    ++level;
  }
  const Rules r(n_, kW, [this, level](int k, int i) { return interval(level, k, i); }, [this](int k) { return across(k); });
  if (std::max(sx, sy) < 2) {
    // Below the double range of the levels: the star point.
    for (std::size_t c = 0; c < 4; ++c) out[c] = origin[c];
    std::fill(out + 4, out + 12, 0.0);
    return;
  }
  // The cell, inside the face when given (its cells of this level end at (face + 1) 2^level).
  const auto cell = [&](double t, int d) {
    const int c = std::min(static_cast<int>(t), 3);
    return face && level < 30 ? std::min(c, (((*face)[static_cast<std::size_t>(d)] + 1) << level) - 1) : c;
  };
  const int a = cell(sx, 0), b = cell(sy, 1);
  // The cell's knots in its own units, 6 per direction around [a, a + 1] and [b, b + 1].
  double ku[6], kv[6];
  const double cu = r.ucol(sector, a, b < 1 ? 1 : b), cv = r.vrow(sector, a < 1 ? 1 : a, b);
  ku[2] = 0;
  kv[2] = 0;
  for (int s = 1; s <= 3; ++s) {
    ku[2 + s] = ku[1 + s] + r.ucol(sector, a + s - 1, std::max(b, 1)) / cu;
    kv[2 + s] = kv[1 + s] + r.vrow(sector, std::max(a, 1), b + s - 1) / cv;
  }
  for (int s = 1; s <= 2; ++s) {
    ku[2 - s] = ku[3 - s] - r.ucol(sector, a - s, std::max(b, 1)) / cu;
    kv[2 - s] = kv[3 - s] - r.vrow(sector, std::max(a, 1), b - s) / cv;
  }
  double bu[8], bv[8];
  basis_derivatives(ku, 3, 2, sx - a, 1, bu);
  basis_derivatives(kv, 3, 2, sy - b, 1, bv);
  const double scale = std::ldexp(1.0, level);
  std::fill(out, out + 12, 0.0);
  for (int t = 0; t < 4; ++t)
    for (int s = 0; s < 4; ++s) {
      const auto& pt = p[static_cast<std::size_t>(r.id(sector, a - 1 + s, b - 1 + t))];
      const double w0 = bu[s] * bv[t], w1 = bu[4 + s] * bv[t] * scale, w2 = bu[s] * bv[4 + t] * scale;
      for (std::size_t c = 0; c < 4; ++c) {
        out[c] += w0 * pt[c] + (s == 0 && t == 0 ? origin[c] : 0.0);
        out[4 + c] += w1 * pt[c];
        out[8 + c] += w2 * pt[c];
      }
    }
}

}  // namespace trivar
