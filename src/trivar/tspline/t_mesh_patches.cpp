#include "trivar/tspline/t_mesh_patches.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/bernstein_interpolation.hpp"

namespace trivar {

namespace t_mesh_patches_detail {

// Homogeneous points (w x, w y, w z, w): the Catmull-Clark pieces of a rational mesh are rational patches.
using P4 = std::array<double, 4>;
using Net = std::array<P4, 16>;  // bicubic Bezier net, index i + 4 j
// Value, d/du, d/dv of the homogeneous surface at (x, y) of the patch frame (12 values).
using HomogeneousEval = std::function<void(double, double, double*)>;

// The cubic Bezier coefficients of the cubic through f(0), f(1/3), f(2/3), f(1) (the inverse Bernstein
// Vandermonde matrix; its first and last rows are exact, so shared end values stay bit-identical).
std::array<P4, 4> interpolate(const std::array<P4, 4>& f) {
  std::array<P4, 4> b{};
  for (std::size_t c = 0; c < 4; ++c) {
    b[0][c] = f[0][c];
    b[1][c] = (-5 * f[0][c] + 18 * f[1][c] - 9 * f[2][c] + 2 * f[3][c]) / 6;
    b[2][c] = (2 * f[0][c] - 9 * f[1][c] + 18 * f[2][c] - 5 * f[3][c]) / 6;
    b[3][c] = f[3][c];
  }
  return b;
}

// A bicubic polynomial on [x0, x0 + w] x [y0, y0 + w] as its Bezier net.
Net interpolate_patch(const HomogeneousEval& f, double x0, double y0, double w) {
  Net vals{};
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      double o[12];
      f(x0 + w * i / 3.0, y0 + w * j / 3.0, o);
      vals[static_cast<std::size_t>(i + 4 * j)] = {o[0], o[1], o[2], o[3]};
    }
  Net rows{}, net{};
  for (std::size_t j = 0; j < 4; ++j) {
    const auto b = interpolate({vals[4 * j], vals[4 * j + 1], vals[4 * j + 2], vals[4 * j + 3]});
    for (std::size_t i = 0; i < 4; ++i) rows[i + 4 * j] = b[i];
  }
  for (std::size_t i = 0; i < 4; ++i) {
    const auto b = interpolate({rows[i], rows[i + 4], rows[i + 8], rows[i + 12]});
    for (std::size_t j = 0; j < 4; ++j) net[i + 4 * j] = b[j];
  }
  return net;
}

// The projected point of the net at (s, t).
std::array<double, 3> eval_net(const Net& n, double s, double t) {
  const auto bern = [](double x) {
    const double y = 1 - x;
    return std::array<double, 4>{y * y * y, 3 * x * y * y, 3 * x * x * y, x * x * x};
  };
  const auto bs = bern(s), bt = bern(t);
  P4 x{};
  for (std::size_t j = 0; j < 4; ++j)
    for (std::size_t i = 0; i < 4; ++i)
      for (std::size_t c = 0; c < 4; ++c) x[c] += bs[i] * bt[j] * n[i + 4 * j][c];
  return {x[0] / x[3], x[1] / x[3], x[2] / x[3]};
}

// A Bezier net of degree p given over the source rectangle [lo, hi], stride values per point, as a patch of
// the face, whose (u, v) = map(source point) for an axis-aligned similarity map: the piece is the image of the
// rectangle, the net reindexed so that its first index runs with u.
FacePatch to_face(int face, int p, const Box<2>& src, int stride, bool rational, const double* coefs,
                  const std::function<std::array<double, 2>(double, double)>& map, bool exact) {
  const int n = p + 1;
  std::vector<std::array<double, 2>> q(static_cast<std::size_t>(n * n));
  Box<2> piece = Box<2>::empty();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto x = map(src.lo[0] + (src.hi[0] - src.lo[0]) * i / p, src.lo[1] + (src.hi[1] - src.lo[1]) * j / p);
      q[static_cast<std::size_t>(i + n * j)] = x;
      piece.extend(x.data());
    }
  const int out_stride = rational ? 4 : 3;
  std::vector<double> out(static_cast<std::size_t>(n * n * out_stride));
  for (int k = 0; k < n * n; ++k) {
    const auto& x = q[static_cast<std::size_t>(k)];
    const int i = static_cast<int>(std::lround(p * (x[0] - piece.lo[0]) / (piece.hi[0] - piece.lo[0])));
    const int j = static_cast<int>(std::lround(p * (x[1] - piece.lo[1]) / (piece.hi[1] - piece.lo[1])));
    const double* c = coefs + static_cast<std::ptrdiff_t>(k) * stride;
    double* o = out.data() + static_cast<std::ptrdiff_t>(i + n * j) * out_stride;
    if (rational)
      std::copy(c, c + 4, o);
    else
      for (int d = 0; d < 3; ++d) o[d] = stride == 4 ? c[d] / c[3] : c[d];
  }
  std::array<KnotVector, 2> knots;
  for (int k = 0; k < 2; ++k) {
    std::vector<double> t(static_cast<std::size_t>(2 * n), piece.lo[k]);
    std::fill(t.begin() + n, t.end(), piece.hi[k]);
    knots[static_cast<std::size_t>(k)] = KnotVector(p, std::move(t));
  }
  return {face, piece, TensorSpline<2>(knots, 3, rational, std::move(out)), exact};
}

// A crease face's cells merged where they are one polynomial: a square [lo, lo + side]^2 of the face and the cell
// whose bicubic it is (on the cell's own square [cell_lo, cell_lo + cell_side]^2, extended beyond it).
struct CellSquare {
  const CreaseFace::Cell* cell;
  std::array<double, 2> cell_lo;
  double cell_side;
  std::array<double, 2> lo;
  double side;
  // Value, d/dx, d/dy (homogeneous) at (x, y) of the square.
  void eval(double x, double y, double* o) const {
    eval_cell(*cell, (lo[0] + x * side - cell_lo[0]) / cell_side, (lo[1] + y * side - cell_lo[1]) / cell_side, side / cell_side, o);
  }
};

// The cells (squares of dyadic sides) merged bottom up: four squares that fill their parent square and whose
// polynomials agree at the 16 points of each (two bicubics that agree there are one) become the parent, with the
// first one's polynomial; to 1e-11 of the points' size, rounding of the extension.
std::vector<CellSquare> merge_cells(std::vector<CellSquare> squares) {
  for (bool merged = true; merged;) {
    merged = false;
    // Parent square -> its quarters present, by quarter.
    std::map<std::array<long long, 3>, std::array<int, 4>> parents;
    for (int i = 0; i < static_cast<int>(squares.size()); ++i) {
      const CellSquare& q = squares[static_cast<std::size_t>(i)];
      const long long x = std::llround(q.lo[0] / q.side), y = std::llround(q.lo[1] / q.side);
      const auto it = parents.try_emplace({std::llround(1 / q.side), x / 2, y / 2}, std::array<int, 4>{-1, -1, -1, -1}).first;
      it->second[static_cast<std::size_t>((x % 2) + 2 * (y % 2))] = i;
    }
    std::vector<char> gone(squares.size(), 0);
    std::vector<CellSquare> out;
    for (const auto& [key, quarter] : parents) {
      if (std::find(quarter.begin(), quarter.end(), -1) != quarter.end()) continue;
      const CellSquare& first = squares[static_cast<std::size_t>(quarter[0])];
      double worst = 0, size = 0;
      for (int k : quarter)
        for (int j = 0; j <= 3; ++j)
          for (int i = 0; i <= 3; ++i) {
            const CellSquare& q = squares[static_cast<std::size_t>(k)];
            double a[12], b[12];
            q.eval(i / 3.0, j / 3.0, a);
            first.eval((q.lo[0] - first.lo[0]) / first.side + i / 3.0, (q.lo[1] - first.lo[1]) / first.side + j / 3.0, b);
            for (int c = 0; c < 4; ++c) {
              worst = std::max(worst, std::abs(a[c] - b[c]));
              size = std::max(size, std::abs(a[c]));
            }
          }
      if (worst > 1e-11 * size) continue;
      for (int k : quarter) gone[static_cast<std::size_t>(k)] = 1;
      out.push_back({first.cell, first.cell_lo, first.cell_side, first.lo, 2 * first.side});
      merged = true;
    }
    for (std::size_t i = 0; i < squares.size(); ++i)
      if (!gone[i]) out.push_back(squares[i]);
    squares = std::move(out);
  }
  return squares;
}

FacePatch net_to_face(int face, const Net& net, const Box<2>& src, const CornerFrame& fr, bool exact) {
  const auto map = [&](double x, double y) {
    return std::array<double, 2>{fr.origin[0] + x * fr.a[0] + y * fr.b[0], fr.origin[1] + x * fr.a[1] + y * fr.b[1]};
  };
  const bool rational = std::any_of(net.begin(), net.end(), [](const P4& x) { return std::abs(x[3] - 1) > 1e-14; });
  return to_face(face, 3, src, 4, rational, net[0].data(), map, exact);
}

// The exact faces: the chart's Bezier elements inside the face.
void exact_face(const TMeshSurface& s, int face, std::vector<FacePatch>& out) {
  const TMeshSurface::ChartFrame f = s.chart_frame(face);
  const TSplineSurface& chart = *f.chart;
  const auto& o = f.origin;
  const auto& au = f.axis_u;
  const auto& av = f.axis_v;
  const double lu = au[0] * au[0] + au[1] * au[1], lv = av[0] * av[0] + av[1] * av[1];
  const auto map = [&](double x, double y) {
    const double dx = x - o[0], dy = y - o[1];
    return std::array<double, 2>{(dx * au[0] + dy * au[1]) / lu, (dx * av[0] + dy * av[1]) / lv};
  };
  double area = 0;
  for (std::size_t e = 0; e < chart.elements().size(); ++e) {
    const Box<2>& b = chart.elements()[e];
    const auto c = map(0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]));
    if (c[0] <= 0 || c[0] >= 1 || c[1] <= 0 || c[1] >= 1) continue;
    const BezierElement<2>& z = chart.bezier_elements()[e];
    require(z.degrees[0] == z.degrees[1], [&] { return "T-mesh patches: face " + std::to_string(face) + ": unequal degrees"; });
    const int st = z.stride();
    bool unit = true;
    for (std::size_t k = static_cast<std::size_t>(st - 1); k < z.coefs.size(); k += static_cast<std::size_t>(st))
      unit = unit && std::abs(z.coefs[k] - 1) <= 1e-14;
    out.push_back(to_face(face, z.degrees[0], b, st, !unit, z.coefs.data(), map, true));
    area += out.back().piece.extent(0) * out.back().piece.extent(1);
  }
  require(std::abs(area - 1) <= 1e-9, [&] {
    return "T-mesh patches: the Bezier elements of face " + std::to_string(face) + " cover " + std::to_string(area) +
           " of it, not all";
  });
}

// The corner patch [0, h]^2 (patch frame) of a star face; see the header. Built on the homogeneous surface: the
// construction is affine in the data, and a tangent direction of (w x, w) at the star point projects to the
// limit tangent, so the projected patches keep the tangent plane there.
Net corner_patch(const HomogeneousEval& f, double h) {
  double o[12];
  f(0, 0, o);
  const P4 b00{o[0], o[1], o[2], o[3]};
  const auto norm = [](const P4& d) { return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + d[3] * d[3]); };
  const auto unit = [&](const double* d) {
    const P4 x{d[0], d[1], d[2], d[3]};
    const double l = norm(x);
    return P4{d[0] / l, d[1] / l, d[2] / l, d[3] / l};
  };
  const P4 tu = unit(o + 4), tv = unit(o + 8);
  Net b{};
  const auto at = [&](int i, int j) -> P4& { return b[static_cast<std::size_t>(i + 4 * j)]; };
  // The sides away from the star point and their cross-derivatives, sampled at the thirds.
  std::array<P4, 4> side_u{}, side_v{}, du{}, dv{};
  for (std::size_t k = 0; k < 4; ++k) {
    f(h, h * static_cast<double>(k) / 3.0, o);
    side_u[k] = {o[0], o[1], o[2], o[3]};
    du[k] = {o[4], o[5], o[6], o[7]};
    f(h * static_cast<double>(k) / 3.0, h, o);
    side_v[k] = {o[0], o[1], o[2], o[3]};
    dv[k] = {o[8], o[9], o[10], o[11]};
  }
  const auto su = interpolate(side_u), sv = interpolate(side_v), cu = interpolate(du), cv = interpolate(dv);
  for (int k = 0; k < 4; ++k) {
    at(3, k) = su[static_cast<std::size_t>(k)];
    at(k, 3) = sv[static_cast<std::size_t>(k)];
  }
  at(3, 3) = su[3];
  // The edges out of the star point: from the limit point along the limit tangent to the exact end.
  at(0, 0) = b00;
  const auto edge = [&](const P4& end, const P4& t, const P4& d_end, P4& b1, P4& b2) {
    const double chord = norm({end[0] - b00[0], end[1] - b00[1], end[2] - b00[2], end[3] - b00[3]});
    for (std::size_t c = 0; c < 4; ++c) {
      b1[c] = b00[c] + chord / 3 * t[c];
      b2[c] = end[c] - h / 3 * d_end[c];
    }
  };
  // d/du at (h, 0) is the first coefficient's value of the sampled cross-derivative (its end values are exact).
  edge(at(3, 0), tu, du[0], at(1, 0), at(2, 0));
  edge(at(0, 3), tv, dv[0], at(0, 1), at(0, 2));
  for (std::size_t c = 0; c < 4; ++c) {
    at(1, 1)[c] = at(1, 0)[c] + at(0, 1)[c] - b00[c];
    at(2, 1)[c] = at(3, 1)[c] - h / 3 * cu[1][c];
    at(1, 2)[c] = at(1, 3)[c] - h / 3 * cv[1][c];
    at(2, 2)[c] = 0.5 * (at(3, 2)[c] - h / 3 * cu[2][c] + at(2, 3)[c] - h / 3 * cv[2][c]);
  }
  return b;
}

double corner_deviation(const HomogeneousEval& f, const Net& net, double h) {
  double worst = 0;
  for (int j = 0; j <= 8; ++j)
    for (int i = 0; i <= 8; ++i) {
      double o[12];
      f(h * i / 8.0, h * j / 8.0, o);
      const auto x = eval_net(net, i / 8.0, j / 8.0);
      worst = std::max(worst, std::hypot(x[0] - o[0] / o[3], x[1] - o[1] / o[3], x[2] - o[2] / o[3]));
    }
  return worst;
}

// The polynomial of degree p through the homogeneous surface at the (p + 1)^2 nodes of the square [lo, lo + side]^2
// of the face's (u, v), as its Bezier coefficients (4 per node, first index along u): the surface itself where it is
// one polynomial of degree p there. A polynomial face's weights are 1 exactly (its basis sums to 1 only to rounding,
// which the interpolation would amplify into weights that are not 1).
std::vector<double> interpolate_square(const HomogeneousEval& f, int p, bool rational, const std::array<double, 2>& lo, double side) {
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(4 * (p + 1) * (p + 1)));
  for (int j = 0; j <= p; ++j)
    for (int i = 0; i <= p; ++i) {
      double o[12];
      f(lo[0] + side * i / p, lo[1] + side * j / p, o);
      if (!rational) {
        for (int c = 0; c < 3; ++c) o[c] /= o[3];
        o[3] = 1;
      }
      values.insert(values.end(), o, o + 4);
    }
  BernsteinInterpolation<2>({p, p}).apply(values, 4, {});
  return values;
}

FacePatch square_to_face(int face, int p, const std::vector<double>& coefs, const std::array<double, 2>& lo, double side, bool exact) {
  bool rational = false;
  for (std::size_t k = 3; k < coefs.size(); k += 4) rational = rational || std::abs(coefs[k] - 1) > 1e-14;
  return to_face(face, p, {{lo[0], lo[1]}, {lo[0] + side, lo[1] + side}}, 4, rational, coefs.data(),
                 [](double x, double y) { return std::array<double, 2>{x, y}; }, exact);
}

// The largest distance between the projected patch and the surface at 9 x 9 points of the square.
double square_deviation(const HomogeneousEval& f, int p, const std::vector<double>& coefs, const std::array<double, 2>& lo, double side) {
  double worst = 0;
  std::vector<double> bu(static_cast<std::size_t>(p + 1)), bv(static_cast<std::size_t>(p + 1));
  for (int j = 0; j <= 8; ++j)
    for (int i = 0; i <= 8; ++i) {
      bernstein_values<-1>(p, i / 8.0, 1, bu.data(), nullptr);
      bernstein_values<-1>(p, j / 8.0, 1, bv.data(), nullptr);
      P4 x{};
      for (int b = 0; b <= p; ++b)
        for (int a = 0; a <= p; ++a)
          for (std::size_t c = 0; c < 4; ++c)
            x[c] += bu[static_cast<std::size_t>(a)] * bv[static_cast<std::size_t>(b)] * coefs[static_cast<std::size_t>(4 * (a + (p + 1) * b)) + c];
      double o[12];
      f(lo[0] + side * i / 8.0, lo[1] + side * j / 8.0, o);
      worst = std::max(worst, std::hypot(x[0] / x[3] - o[0] / o[3], x[1] / x[3] - o[1] / o[3], x[2] / x[3] - o[2] / o[3]));
    }
  return worst;
}

}  // namespace t_mesh_patches_detail

TMeshPatches t_mesh_patches(const TMeshSurface& s, const TMeshPatchOptions& options) {
  using namespace t_mesh_patches_detail;
  require(options.max_levels >= 0 && options.max_levels <= 60 && options.levels <= 60,
          "T-mesh patches: levels above 60 (2^-60 of a face) are refused");
  TMeshPatches r;
  r.tolerance = options.tolerance;
  if (r.tolerance <= 0) {
    Box<3> b = Box<3>::empty();
    for (const RationalPoint& p : s.mesh().points) b.extend(p.xyz.data());
    r.tolerance = 1e-6 * b.diagonal();
  }
  // Star faces: the corner patches for a growing number of levels until they meet the tolerance.
  struct Star {
    int face;
    HomogeneousEval eval;
    Net corner;
  };
  const auto patch_eval = [&s](int f) -> HomogeneousEval {
    return [&s, f](double x, double y, double* o) { s.eval_patch_homogeneous(f, x, y, o); };
  };
  // A subdivided face's quarter in its own patch frame.
  const auto quarter_eval = [&s](int f, int q) -> HomogeneousEval {
    const SubdividedFace& z = s.subdivided(f);
    return [&z, q](double x, double y, double* o) { z.eval_quarter(q, x, y, o); };
  };
  // A crease face's quarter at corner q in the quarter's frame (corner_frame(q) at half scale).
  const auto crease_quarter_eval = [&s](int f, int q) -> HomogeneousEval {
    return [&z = s.crease_face(f), fr = corner_frame(q)](double x, double y, double* o) {
      double h[12];
      z.eval(fr.origin[0] + (x * fr.a[0] + y * fr.b[0]) / 2, fr.origin[1] + (x * fr.a[1] + y * fr.b[1]) / 2, h);
      for (int c = 0; c < 4; ++c) {
        o[c] = h[c];
        o[4 + c] = (fr.a[0] * h[4 + c] + fr.a[1] * h[8 + c]) / 2;
        o[8 + c] = (fr.b[0] * h[4 + c] + fr.b[1] * h[8 + c]) / 2;
      }
    };
  };
  std::vector<Star> stars;
  for (int f = 0; f < s.num_faces(); ++f) {
    if (s.method(f) == FaceMethod::star || (s.method(f) == FaceMethod::non_uniform && s.star_corner(f)))
      stars.push_back({f, patch_eval(f), {}});
    if (s.method(f) == FaceMethod::subdivided)
      for (int q = 0; q < 4; ++q)
        if (s.subdivided(f).valence(q) != 4) stars.push_back({f, quarter_eval(f, q), {}});
    if (s.method(f) == FaceMethod::crease)
      for (int q = 0; q < 4; ++q)
        if (s.crease_face(f).irregular(q)) stars.push_back({f, crease_quarter_eval(f, q), {}});
  }
  // Averaging faces (degree p above 3): their homogeneous surface, and their irregular corners.
  const auto face_eval = [&s](int f) -> HomogeneousEval { return [&s, f](double x, double y, double* o) { s.eval_patch_homogeneous(f, x, y, o); }; };
  const auto corner_lo = [](int c, double h) { return std::array<double, 2>{c == 1 || c == 2 ? 1 - h : 0, c >= 2 ? 1 - h : 0}; };
  std::vector<std::array<int, 2>> averaging_corners;
  for (int f = 0; f < s.num_faces(); ++f)
    if (s.method(f) == FaceMethod::averaging)
      for (int c = 0; c < 4; ++c)
        if (s.averaging_face(f).irregular(c)) averaging_corners.push_back({f, c});
  for (int k = options.levels >= 0 ? options.levels : 0;; ++k) {
    const double h = std::ldexp(1.0, -k);
    double dev = 0;
    for (Star& st : stars) {
      st.corner = corner_patch(st.eval, h);
      dev = std::max(dev, corner_deviation(st.eval, st.corner, h));
    }
    for (const auto& [f, c] : averaging_corners) {
      const int p = s.mesh().degree;
      dev = std::max(dev, square_deviation(face_eval(f), p, interpolate_square(face_eval(f), p, s.rational_patch(f), corner_lo(c, h), h),
                                           corner_lo(c, h), h));
    }
    r.levels = k;
    r.deviation = dev;
    if (options.levels >= 0 || dev <= r.tolerance) break;
    require(k < options.max_levels, [&] {
      return "T-mesh patches: corner patches at star points deviate " + std::to_string(dev) + " from the limit surface after " +
             std::to_string(k) + " levels, above the tolerance " + std::to_string(r.tolerance);
    });
  }
  std::size_t next_star = 0;
  const auto next_corner_patch = [&](int f, const CornerFrame& fr) {
    const double h = std::ldexp(1.0, -r.levels);
    r.patches.push_back(net_to_face(f, stars[next_star++].corner, {{0, 0}, {h, h}}, fr, false));
  };
  // The next star's rings of exact patches (split x split B-spline cells per square) and its corner patch.
  const auto star_patches = [&](int f, const CornerFrame& fr, int split) {
    const Star& st = stars[next_star];
    for (int j = 1; j <= r.levels; ++j) {
      const double h = std::ldexp(1.0, -j), c = h / split;
      for (const auto& lo : {std::array<double, 2>{h, 0}, std::array<double, 2>{h, h}, std::array<double, 2>{0, h}})
        for (int b = 0; b < split; ++b)
          for (int a = 0; a < split; ++a) {
            const double x = lo[0] + a * c, y = lo[1] + b * c;
            r.patches.push_back(net_to_face(f, interpolate_patch(st.eval, x, y, c), {{x, y}, {x + c, y + c}}, fr, true));
          }
    }
    next_corner_patch(f, fr);
  };
  // The frame of quarter q of a face: corner q's, at half scale.
  const auto quarter_frame = [](int q) {
    const CornerFrame c = corner_frame(q);
    return CornerFrame{c.origin, {c.a[0] / 2, c.a[1] / 2}, {c.b[0] / 2, c.b[1] / 2}};
  };
  for (int f = 0; f < s.num_faces(); ++f) {
    switch (s.method(f)) {
      case FaceMethod::none: break;
      case FaceMethod::averaging:
        // Each regular sub-face one exact patch of degree p; each irregular corner's square [0, 2^-levels]^2 the
        // polynomial through the surface at its nodes.
        s.averaging_face(f).for_each_square(r.levels, [&](const std::array<double, 2>& lo, double side, int corner) {
          const int p = s.mesh().degree;
          r.patches.push_back(square_to_face(f, p, interpolate_square(face_eval(f), p, s.rational_patch(f), lo, side), lo, side, corner < 0));
        });
        break;
      case FaceMethod::exact: exact_face(s, f, r.patches); break;
      case FaceMethod::bicubic:
        r.patches.push_back(net_to_face(f, interpolate_patch(patch_eval(f), 0, 0, 1), {{0, 0}, {1, 1}},
                                        corner_frame(s.patch_corner(f)), true));
        break;
      case FaceMethod::non_uniform:
        if (!s.star_corner(f)) {
          // A face of the second ring: four bicubic B-spline cells.
          const CornerFrame fr = corner_frame(s.patch_corner(f));
          for (const auto& lo : {std::array<double, 2>{0, 0}, std::array<double, 2>{0.5, 0}, std::array<double, 2>{0.5, 0.5}, std::array<double, 2>{0, 0.5}})
            r.patches.push_back(net_to_face(f, interpolate_patch(patch_eval(f), lo[0], lo[1], 0.5),
                                            {{lo[0], lo[1]}, {lo[0] + 0.5, lo[1] + 0.5}}, fr, true));
          break;
        }
        [[fallthrough]];
      case FaceMethod::star:
        // Stam's rings are one bicubic piece per square; the non-uniform scheme's are 2 x 2 B-spline cells.
        star_patches(f, corner_frame(s.patch_corner(f)), s.method(f) == FaceMethod::star ? 1 : 2);
        break;
      case FaceMethod::subdivided:
      case FaceMethod::crease:
        if (s.method(f) == FaceMethod::crease && s.crease_face(f).has_cells()) {
          // Unequal intervals: a quarter is several B-spline cells (knot lines where the rules inserted them), each
          // one bicubic piece, so each cell is one exact patch; at an irregular corner the star's corner patch
          // covers the square of side 2^-levels of the quarter, which no cell reaches.
          // Cells that are one polynomial (the rules' midpoint insertions past the star point's ring) are one patch.
          const CreaseFace& z = s.crease_face(f);
          // The cells are kept (a std::deque does not move them) for the squares that point at them.
          std::deque<CreaseFace::Cell> cells;
          std::vector<CellSquare> squares;
          z.for_each_cell(r.levels + 1, [&](const CreaseFace::Cell& cell, const std::array<double, 2>& lo, double side) {
            squares.push_back({&cells.emplace_back(cell), lo, side, lo, side});
          });
          for (const CellSquare& q : merge_cells(std::move(squares))) {
            const HomogeneousEval e = [&q](double x, double y, double* o) { q.eval(x, y, o); };
            r.patches.push_back(net_to_face(f, interpolate_patch(e, 0, 0, 1), {{0, 0}, {1, 1}}, {q.lo, {q.side, 0}, {0, q.side}}, true));
          }
          for (int q = 0; q < 4; ++q)
            if (z.irregular(q)) next_corner_patch(f, quarter_frame(q));
          break;
        }
        for (int q = 0; q < 4; ++q) {
          // A crease face's quarters away from its irregular corners are bicubic B-splines (their corners are
          // regular after one step).
          const CornerFrame fr = quarter_frame(q);
          const bool subdivided = s.method(f) == FaceMethod::subdivided;
          if (subdivided ? s.subdivided(f).valence(q) != 4 : s.crease_face(f).irregular(q))
            star_patches(f, fr, 1);
          else
            r.patches.push_back(net_to_face(f, interpolate_patch(subdivided ? quarter_eval(f, q) : crease_quarter_eval(f, q), 0, 0, 1),
                                            {{0, 0}, {1, 1}}, fr, true));
        }
        break;
    }
  }
  for (const FacePatch& p : r.patches) ++(p.exact ? r.exact_patches : r.corner_patches);
  return r;
}

}  // namespace trivar
