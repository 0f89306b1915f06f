#include "trivar/am/cell_section.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "trivar/core/error.hpp"

namespace trivar::am {

namespace {

// A crossing of the plane on a grid edge: the parameter triple and the model point.
struct Crossing {
  Param<3> u{};
  double x = 0, y = 0;
};

}  // namespace

CellSection::CellSection(const TensorSpline<3>& geometry, const SectionOptions& options)
    : geometry_(geometry), options_(options) {
  require(geometry.dim() == 3, "cell section: the trivariate must have control dimension 3, got " +
                                   std::to_string(geometry.dim()));
  require(options.samples_per_span >= 1, "cell section: samples_per_span must be >= 1");
  require(std::isfinite(options.tolerance) && options.tolerance > 0, "cell section: tolerance must be positive");
  require(options.max_depth >= 0, "cell section: max_depth must be >= 0");
  for (int d = 0; d < 3; ++d) {
    const std::vector<double> b = geometry.knots(d).breakpoints();
    for (std::size_t e = 0; e + 1 < b.size(); ++e)
      for (int q = 0; q < options.samples_per_span; ++q)
        params_[d].push_back(b[e] + (b[e + 1] - b[e]) * q / options.samples_per_span);
    params_[d].push_back(b.back());
  }
  const Box<3> dom = geometry.domain();
  for (int f = 0; f < 6; ++f) {
    Face& face = faces_[f];
    face.fixed_dir = f / 2;
    face.fixed = f % 2 == 0 ? dom.lo[face.fixed_dir] : dom.hi[face.fixed_dir];
    face.dirs = face.fixed_dir == 0 ? std::array<int, 2>{1, 2}
                : face.fixed_dir == 1 ? std::array<int, 2>{0, 2}
                                      : std::array<int, 2>{0, 1};
    const auto& ps = params_[face.dirs[0]];
    const auto& pt = params_[face.dirs[1]];
    face.points.resize(3 * ps.size() * pt.size());
    Param<3> u{};
    u[face.fixed_dir] = face.fixed;
    double* p = face.points.data();
    for (double t : pt)
      for (double s : ps) {
        u[face.dirs[0]] = s;
        u[face.dirs[1]] = t;
        geometry.eval(u, p);
        p += 3;
      }
  }
  double lo[3], hi[3];
  geometry.control_bounds(lo, hi);
  z_lo_ = lo[2];
  z_hi_ = hi[2];
  double diag = 0;
  for (int k = 0; k < 3; ++k) diag += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  z_eps_ = 64 * std::numeric_limits<double>::epsilon() * std::max(std::sqrt(diag), std::abs(z_hi_) + std::abs(z_lo_));
}

void CellSection::section(double z, std::vector<OutlineSegment>& out) const {
  if (!(z >= z_lo_ && z <= z_hi_)) return;
  for (int f = 0; f < 6; ++f) section_face(faces_[f], z, out, f);
}

void CellSection::section_face(const Face& f, double z, std::vector<OutlineSegment>& out, int face) const {
  const auto& ps = params_[f.dirs[0]];
  const auto& pt = params_[f.dirs[1]];
  const int ns = static_cast<int>(ps.size()), nt = static_cast<int>(pt.size());
  auto height = [&](int a, int b) { return f.points[3 * (static_cast<std::size_t>(a) + static_cast<std::size_t>(ns) * b) + 2] - z; };
  bool any_above = false, any_below = false;
  for (int b = 0; b < nt; ++b)
    for (int a = 0; a < ns; ++a) (height(a, b) >= 0 ? any_above : any_below) = true;
  if (!any_above || !any_below) return;

  auto param = [&](int a, int b) {
    Param<3> u{};
    u[f.fixed_dir] = f.fixed;
    u[f.dirs[0]] = ps[a];
    u[f.dirs[1]] = pt[b];
    return u;
  };
  // Crossing on the grid edge from grid point (a0, b0) to (a1, b1), which differ in one index, increasing.
  auto refine = [&](int a0, int b0, int a1, int b1) {
    const int dir = a1 != a0 ? f.dirs[0] : f.dirs[1];
    const Param<3> ua = param(a0, b0), ub = param(a1, b1);
    double lo = ua[dir], hi = ub[dir], flo = height(a0, b0), fhi = height(a1, b1);
    const bool lo_above = flo >= 0;
    const double* plo = &f.points[3 * (static_cast<std::size_t>(a0) + static_cast<std::size_t>(ns) * b0)];
    const double* phi = &f.points[3 * (static_cast<std::size_t>(a1) + static_cast<std::size_t>(ns) * b1)];
    Crossing c;
    c.u = std::abs(flo) <= std::abs(fhi) ? ua : ub;
    c.x = std::abs(flo) <= std::abs(fhi) ? plo[0] : phi[0];
    c.y = std::abs(flo) <= std::abs(fhi) ? plo[1] : phi[1];
    double best = std::min(std::abs(flo), std::abs(fhi));
    int kept = 0;  // Illinois: which end stayed fixed last time (-1 lo, +1 hi)
    Param<3> u = ua;
    double p[3];
    for (int it = 0; it < 100 && best > z_eps_; ++it) {
      double t = (lo * fhi - hi * flo) / (fhi - flo);
      if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
      if (!(t > lo && t < hi)) break;  // bracket at rounding level
      u[dir] = t;
      geometry_.eval(u, p);
      const double ft = p[2] - z;
      if (std::abs(ft) < best) {
        best = std::abs(ft);
        c.u = u;
        c.x = p[0];
        c.y = p[1];
      }
      if ((ft >= 0) == lo_above) {
        lo = t;
        flo = ft;
        if (kept == 1) fhi *= 0.5;
        kept = 1;
      } else {
        hi = t;
        fhi = ft;
        if (kept == -1) flo *= 0.5;
        kept = -1;
      }
    }
    return c;
  };

  // Crossings per grid edge: s-edges (a, b)-(a+1, b) at a + (ns-1) b, t-edges (a, b)-(a, b+1) at a + ns b.
  std::vector<int> s_edge(static_cast<std::size_t>((ns - 1) * nt), -1), t_edge(static_cast<std::size_t>(ns * (nt - 1)), -1);
  std::vector<Crossing> crossings;
  for (int b = 0; b < nt; ++b)
    for (int a = 0; a + 1 < ns; ++a)
      if ((height(a, b) >= 0) != (height(a + 1, b) >= 0)) {
        s_edge[static_cast<std::size_t>(a + (ns - 1) * b)] = static_cast<int>(crossings.size());
        crossings.push_back(refine(a, b, a + 1, b));
      }
  for (int b = 0; b + 1 < nt; ++b)
    for (int a = 0; a < ns; ++a)
      if ((height(a, b) >= 0) != (height(a, b + 1) >= 0)) {
        t_edge[static_cast<std::size_t>(a + ns * b)] = static_cast<int>(crossings.size());
        crossings.push_back(refine(a, b, a, b + 1));
      }

  auto connect = [&](int i, int k) {
    const Crossing& c0 = crossings[static_cast<std::size_t>(i)];
    const Crossing& c1 = crossings[static_cast<std::size_t>(k)];
    const double a[2] = {c0.x, c0.y}, b[2] = {c1.x, c1.y};
    emit(f, c0.u, a, c1.u, b, z, 0, face, out);
  };
  for (int b = 0; b + 1 < nt; ++b)
    for (int a = 0; a + 1 < ns; ++a) {
      // Quad edges: 0 bottom (c0-c1), 1 right (c1-c2), 2 top (c3-c2), 3 left (c0-c3).
      const int e[4] = {s_edge[static_cast<std::size_t>(a + (ns - 1) * b)], t_edge[static_cast<std::size_t>(a + 1 + ns * b)],
                        s_edge[static_cast<std::size_t>(a + (ns - 1) * (b + 1))], t_edge[static_cast<std::size_t>(a + ns * b)]};
      int hit[4], n = 0;
      for (int k = 0; k < 4; ++k)
        if (e[k] >= 0) hit[n++] = e[k];
      if (n == 2) {
        connect(hit[0], hit[1]);
      } else if (n == 4) {
        const double mean = 0.25 * (height(a, b) + height(a + 1, b) + height(a + 1, b + 1) + height(a, b + 1));
        if ((mean >= 0) == (height(a, b) >= 0)) {  // c0 and c2 connected through the centre
          connect(e[0], e[1]);
          connect(e[2], e[3]);
        } else {
          connect(e[0], e[3]);
          connect(e[1], e[2]);
        }
      }
    }
}

void CellSection::emit(const Face& f, const Param<3>& pa, const double* a, const Param<3>& pb, const double* b,
                       double z, int depth, int face, std::vector<OutlineSegment>& out) const {
  auto chord = [&] { out.push_back({a[0], a[1], b[0], b[1], face, pa, pb}); };
  if (depth >= options_.max_depth) return chord();
  // The section curve's point between the ends: the parameter midpoint moved onto the plane by Newton along
  // the height gradient within the face.
  const int s = f.dirs[0], t = f.dirs[1];
  const Box<3> dom = geometry_.domain();
  Param<3> m = pa;
  m[s] = 0.5 * (pa[s] + pb[s]);
  m[t] = 0.5 * (pa[t] + pb[t]);
  double d[12];
  bool on_plane = false;
  for (int it = 0; it < 12; ++it) {
    geometry_.eval_derivs(m, 1, d);
    const double g = d[2] - z;
    if (std::abs(g) <= z_eps_) {
      on_plane = true;
      break;
    }
    const double gs = d[3 * (1 + s) + 2], gt = d[3 * (1 + t) + 2];
    const double n2 = gs * gs + gt * gt;
    if (!(n2 > 0)) break;
    m[s] = std::clamp(m[s] - g * gs / n2, dom.lo[s], dom.hi[s]);
    m[t] = std::clamp(m[t] - g * gt / n2, dom.lo[t], dom.hi[t]);
  }
  // Newton may have run to another branch of the section: only a point near the segment's parameter box counts.
  const double reach = std::max(std::abs(pb[s] - pa[s]), std::abs(pb[t] - pa[t]));
  for (int k : {s, t})
    if (m[k] < std::min(pa[k], pb[k]) - reach || m[k] > std::max(pa[k], pb[k]) + reach) on_plane = false;
  if (!on_plane) return chord();
  const double mx[2] = {d[0], d[1]};
  const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
  const double dev = len > 0 ? std::abs(ex * (mx[1] - a[1]) - ey * (mx[0] - a[0])) / len : std::hypot(mx[0] - a[0], mx[1] - a[1]);
  if (dev <= options_.tolerance) return chord();
  emit(f, pa, a, m, mx, z, depth + 1, face, out);
  emit(f, m, mx, pb, b, z, depth + 1, face, out);
}

}  // namespace trivar::am
