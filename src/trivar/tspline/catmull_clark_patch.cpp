#include "trivar/tspline/catmull_clark_patch.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

namespace {

// The faces around the star point and the five outer faces, as indices into the 2N + 8 layout; a new point of
// one Catmull-Clark step is a weight row over the layout.
class LocalMesh {
public:
  explicit LocalMesh(int n) : n_(n), k_(2 * n + 8) {
    for (int i = 0; i < n; ++i) faces_.push_back({0, e(i), d(i), e(i + 1)});
    faces_.push_back({e(0), x(1), x(2), d(0)});          // beyond the edge e_0 d_0
    faces_.push_back({d(0), x(2), x(3), x(4)});          // beyond d_0
    faces_.push_back({e(1), d(0), x(4), x(5)});          // beyond the edge d_0 e_1
    faces_.push_back({d(n - 1), x(0), x(1), e(0)});      // beyond the edge e_0 d_(N-1)
    faces_.push_back({d(1), e(1), x(5), x(6)});          // beyond the edge e_1 d_1
  }
  int e(int i) const { return 1 + 2 * (((i % n_) + n_) % n_); }
  int d(int i) const { return 2 + 2 * (((i % n_) + n_) % n_); }
  int x(int j) const { return 2 * n_ + 1 + j; }
  const std::array<int, 4>& outer(int j) const { return faces_[static_cast<std::size_t>(n_ + j)]; }
  int outer_face(int j) const { return n_ + j; }

  std::vector<double> face_point(int f) const {
    std::vector<double> w(static_cast<std::size_t>(k_), 0.0);
    for (int p : faces_[static_cast<std::size_t>(f)]) w[static_cast<std::size_t>(p)] += 0.25;
    return w;
  }
  std::vector<double> edge_point(int a, int b) const {
    std::vector<double> w(static_cast<std::size_t>(k_), 0.0);
    w[static_cast<std::size_t>(a)] += 0.25;
    w[static_cast<std::size_t>(b)] += 0.25;
    int found = 0;
    for (int f = 0; f < static_cast<int>(faces_.size()); ++f)
      if (has_edge(f, a, b)) {
        add(w, face_point(f), 0.25);
        ++found;
      }
    if (found != 2) throw Error("Catmull-Clark patch: edge without two faces");
    return w;
  }
  std::vector<double> vertex_point(int p) const {
    std::vector<double> faces(static_cast<std::size_t>(k_), 0.0), mids(static_cast<std::size_t>(k_), 0.0);
    std::vector<int> nbrs;
    int nf = 0;
    for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
      const auto& q = faces_[static_cast<std::size_t>(f)];
      const auto it = std::find(q.begin(), q.end(), p);
      if (it == q.end()) continue;
      ++nf;
      add(faces, face_point(f), 1.0);
      const std::size_t i = static_cast<std::size_t>(it - q.begin());
      for (int m : {q[(i + 1) % 4], q[(i + 3) % 4]})
        if (std::find(nbrs.begin(), nbrs.end(), m) == nbrs.end()) nbrs.push_back(m);
    }
    const int n = static_cast<int>(nbrs.size());
    if (n != nf) throw Error("Catmull-Clark patch: vertex without a full ring");
    for (int m : nbrs) {
      mids[static_cast<std::size_t>(p)] += 0.5;
      mids[static_cast<std::size_t>(m)] += 0.5;
    }
    // (F + 2 R + (n - 3) P) / n with F, R the averages of the face points and edge midpoints.
    std::vector<double> w(static_cast<std::size_t>(k_), 0.0);
    add(w, faces, 1.0 / (n * n));
    add(w, mids, 2.0 / (n * n));
    w[static_cast<std::size_t>(p)] += (n - 3.0) / n;
    return w;
  }

private:
  int n_, k_;
  std::vector<std::array<int, 4>> faces_;
  bool has_edge(int f, int a, int b) const {
    const auto& q = faces_[static_cast<std::size_t>(f)];
    for (std::size_t i = 0; i < 4; ++i)
      if ((q[i] == a && q[(i + 1) % 4] == b) || (q[i] == b && q[(i + 1) % 4] == a)) return true;
    return false;
  }
  static void add(std::vector<double>& w, const std::vector<double>& r, double s) {
    for (std::size_t i = 0; i < w.size(); ++i) w[i] += s * r[i];
  }
};

std::array<double, 4> cubic_bspline(double t) {
  const double s = 1 - t;
  return {s * s * s / 6, (3 * t * t * t - 6 * t * t + 4) / 6, (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, t * t * t / 6};
}
std::array<double, 4> cubic_bspline_derivative(double t) {
  const double s = 1 - t;
  return {-s * s / 2, (3 * t * t - 4 * t) / 2, (-3 * t * t + 2 * t + 1) / 2, t * t / 2};
}

}  // namespace

void eval_uniform_bicubic(std::span<const std::array<double, 3>> grid, double s, double t, double* out) {
  const auto bs = cubic_bspline(s), bt = cubic_bspline(t), ds = cubic_bspline_derivative(s), dt = cubic_bspline_derivative(t);
  std::fill(out, out + 9, 0.0);
  for (std::size_t j = 0; j < 4; ++j)
    for (std::size_t i = 0; i < 4; ++i) {
      const auto& p = grid[i + 4 * j];
      const double w0 = bs[i] * bt[j], w1 = ds[i] * bt[j], w2 = bs[i] * dt[j];
      for (std::size_t c = 0; c < 3; ++c) {
        out[c] += w0 * p[c];
        out[3 + c] += w1 * p[c];
        out[6 + c] += w2 * p[c];
      }
    }
}

void eval_bicubic_cell(std::span<const std::array<double, 3>> grid, const std::array<double, 6>& ku,
                       const std::array<double, 6>& kv, double s, double t, double* out) {
  double bu[8], bv[8];
  basis_derivatives(ku.data(), 3, 2, s, 1, bu);
  basis_derivatives(kv.data(), 3, 2, t, 1, bv);
  std::fill(out, out + 9, 0.0);
  for (std::size_t j = 0; j < 4; ++j)
    for (std::size_t i = 0; i < 4; ++i) {
      const auto& p = grid[i + 4 * j];
      const double w0 = bu[i] * bv[j], w1 = bu[4 + i] * bv[j], w2 = bu[i] * bv[4 + j];
      for (std::size_t c = 0; c < 3; ++c) {
        out[c] += w0 * p[c];
        out[3 + c] += w1 * p[c];
        out[6 + c] += w2 * p[c];
      }
    }
}

std::array<std::array<double, 3>, 16> regular_grid(std::span<const std::array<double, 3>> p) {
  const auto at = [](int a, int b) { return static_cast<std::size_t>((a + 1) + 4 * (b + 1)); };
  std::array<std::array<double, 3>, 16> g{};
  g[at(0, 0)] = p[0];
  g[at(1, 0)] = p[1];
  g[at(1, 1)] = p[2];
  g[at(0, 1)] = p[3];
  g[at(-1, 1)] = p[4];
  g[at(-1, 0)] = p[5];
  g[at(-1, -1)] = p[6];
  g[at(0, -1)] = p[7];
  g[at(1, -1)] = p[8];
  const std::array<std::array<int, 2>, 7> outer{{{2, -1}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {-1, 2}}};
  for (std::size_t j = 0; j < 7; ++j) g[at(outer[j][0], outer[j][1])] = p[9 + j];
  return g;
}

CatmullClarkPatch::CatmullClarkPatch(int valence) : n_(valence) {
  require(valence >= 3 && valence <= 64, "Catmull-Clark patch: valence " + std::to_string(valence) + " outside 3..64");
  const LocalMesh m(n_);
  const int k = size(), n = n_;
  std::vector<std::vector<double>> rows;
  rows.push_back(m.vertex_point(0));
  for (int i = 0; i < n; ++i) {
    rows.push_back(m.edge_point(0, m.e(i)));
    rows.push_back(m.face_point(i));
  }
  rows.push_back(m.edge_point(m.e(0), m.d(n - 1)));  // (2, -1)
  rows.push_back(m.vertex_point(m.e(0)));             // (2, 0)
  rows.push_back(m.edge_point(m.e(0), m.d(0)));       // (2, 1)
  rows.push_back(m.vertex_point(m.d(0)));             // (2, 2)
  rows.push_back(m.edge_point(m.e(1), m.d(0)));       // (1, 2)
  rows.push_back(m.vertex_point(m.e(1)));             // (0, 2)
  rows.push_back(m.edge_point(m.e(1), m.d(1)));       // (-1, 2)
  subdivide_.reserve(static_cast<std::size_t>(k * k));
  for (const auto& r : rows) subdivide_.insert(subdivide_.end(), r.begin(), r.end());
  // The next level's points on the grid of the regular sub-patches, (A, B) in -1..3 (half the old spacing).
  std::map<std::array<int, 2>, std::vector<double>> at;
  at[{0, 0}] = rows[0];
  at[{1, 0}] = rows[1];
  at[{1, 1}] = rows[2];
  at[{0, 1}] = rows[3];
  at[{-1, 1}] = rows[4];
  at[{-1, 0}] = m.edge_point(0, m.e(2));
  at[{0, -1}] = m.edge_point(0, m.e(n - 1));
  at[{1, -1}] = m.face_point(n - 1);
  at[{2, -1}] = rows[static_cast<std::size_t>(2 * n + 1)];
  at[{2, 0}] = rows[static_cast<std::size_t>(2 * n + 2)];
  at[{2, 1}] = rows[static_cast<std::size_t>(2 * n + 3)];
  at[{2, 2}] = rows[static_cast<std::size_t>(2 * n + 4)];
  at[{1, 2}] = rows[static_cast<std::size_t>(2 * n + 5)];
  at[{0, 2}] = rows[static_cast<std::size_t>(2 * n + 6)];
  at[{-1, 2}] = rows[static_cast<std::size_t>(2 * n + 7)];
  at[{3, -1}] = m.face_point(m.outer_face(3));
  at[{3, 0}] = m.edge_point(m.e(0), m.x(1));
  at[{3, 1}] = m.face_point(m.outer_face(0));
  at[{3, 2}] = m.edge_point(m.d(0), m.x(2));
  at[{3, 3}] = m.face_point(m.outer_face(1));
  at[{2, 3}] = m.edge_point(m.d(0), m.x(4));
  at[{1, 3}] = m.face_point(m.outer_face(2));
  at[{0, 3}] = m.edge_point(m.e(1), m.x(5));
  at[{-1, 3}] = m.face_point(m.outer_face(4));
  const std::array<std::array<int, 2>, 3> origin{{{0, -1}, {0, 0}, {-1, 0}}};
  for (std::size_t s = 0; s < 3; ++s)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const auto& r = at.at({origin[s][0] + i, origin[s][1] + j});
        picks_[s].insert(picks_[s].end(), r.begin(), r.end());
      }
}

std::array<double, 3> CatmullClarkPatch::limit_point(std::span<const std::array<double, 3>> p) const {
  // (N^2 v + 4 sum e_i + sum d_i) / (N (N + 5)).
  const double n = n_;
  std::array<double, 3> x{};
  for (std::size_t c = 0; c < 3; ++c) {
    double s = n * n * p[0][c];
    for (int i = 0; i < n_; ++i) s += 4 * p[static_cast<std::size_t>(1 + 2 * i)][c] + p[static_cast<std::size_t>(2 + 2 * i)][c];
    x[c] = s / (n * (n + 5));
  }
  return x;
}

void CatmullClarkPatch::eval(std::span<const std::array<double, 3>> points, double u, double v, double* out) const {
  const std::size_t k = static_cast<std::size_t>(size());
  // Relative to the star point's limit (the rules are affine): the points of level j then have the size of the
  // neighbourhood, about lambda^j, and their rounding, scaled by 2^j in the derivatives, stays small.
  const std::array<double, 3> origin = limit_point(points);
  std::vector<std::array<double, 3>> p(k), q(k);
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t c = 0; c < 3; ++c) p[i][c] = points[i][c] - origin[c];
  int level = 0;
  while (u < 0.5 && v < 0.5 && !(u == 0 && v == 0) && level < 1100) {
    for (std::size_t r = 0; r < k; ++r) {
      std::array<double, 3> s{};
      const double* w = subdivide_.data() + r * k;
      for (std::size_t j = 0; j < k; ++j)
        if (w[j] != 0)
          for (std::size_t c = 0; c < 3; ++c) s[c] += w[j] * p[j][c];
      q[r] = s;
    }
    p.swap(q);
    u *= 2;
    v *= 2;
    ++level;
  }
  if (u < 0.5 && v < 0.5) {
    // The star point: its limit position and the limit tangents towards e_0 and e_1.
    const double n = n_, a = 1 + std::cos(2 * std::numbers::pi / n) +
                             std::cos(std::numbers::pi / n) * std::sqrt(2 * (9 + std::cos(2 * std::numbers::pi / n)));
    for (std::size_t c = 0; c < 3; ++c) {
      out[c] = origin[c];
      for (int t = 0; t < 2; ++t) {
        double s = 0;
        for (int i = 0; i < n_; ++i) {
          const double ci = std::cos(2 * std::numbers::pi * (i - t) / n), cj = std::cos(2 * std::numbers::pi * (i + 1 - t) / n);
          s += a * ci * p[static_cast<std::size_t>(1 + 2 * i)][c] + (ci + cj) * p[static_cast<std::size_t>(2 + 2 * i)][c];
        }
        out[3 + 3 * t + c] = s / (n * (n + 5));  // scaled as the limit point's weights; a direction
      }
    }
    return;
  }
  const std::size_t s = u >= 0.5 ? (v >= 0.5 ? 1 : 0) : 2;
  std::array<std::array<double, 3>, 16> g{};
  for (std::size_t r = 0; r < 16; ++r) {
    const double* w = picks_[s].data() + r * k;
    for (std::size_t j = 0; j < k; ++j)
      if (w[j] != 0)
        for (std::size_t c = 0; c < 3; ++c) g[r][c] += w[j] * p[j][c];
  }
  const double su = s == 2 ? 2 * u : 2 * u - 1, sv = s == 0 ? 2 * v : 2 * v - 1;
  eval_uniform_bicubic(g, su, sv, out);
  for (std::size_t c = 0; c < 3; ++c) out[c] += origin[c];
  const double scale = std::ldexp(2.0, level);
  for (int c = 3; c < 9; ++c) out[c] *= scale;
}

const CatmullClarkPatch& catmull_clark_patch(int valence) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<CatmullClarkPatch>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& p = cache[valence];
  if (!p) p = std::make_unique<CatmullClarkPatch>(valence);
  return *p;
}

}  // namespace trivar
