#include "trivar/tspline/t_mesh_tessellation.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/clamped_count.hpp"
#include "trivar/core/error.hpp"

namespace trivar {

namespace {

constexpr double kSame = 1e-9;  // sample positions closer than this (in face or edge units) are one

struct SideLink {
  int link;
  double lo, hi;  // its range along the side, in [0, 1]
};

// The four sides of a face (from its first corner, counter-clockwise), each its links with their ranges.
std::array<std::vector<SideLink>, 4> face_sides(const TMesh& m, int f) {
  const auto& loop = m.faces[static_cast<std::size_t>(f)];
  const std::size_t start = static_cast<std::size_t>(std::find(loop.begin(), loop.end(), m.first_corner(f)) - loop.begin());
  std::array<std::vector<SideLink>, 4> sides;
  int k = -1;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const int l = loop[(start + i) % loop.size()];
    if (m.links[static_cast<std::size_t>(l)].flag == 0) ++k;
    sides[static_cast<std::size_t>(k)].push_back({l, 0, m.intervals[static_cast<std::size_t>(m.links[static_cast<std::size_t>(l)].edge)]});
  }
  for (auto& s : sides) {
    double total = 0;
    for (auto& x : s) total += x.hi;
    double at = 0;
    for (auto& x : s) {
      const double d = x.hi;
      x.lo = at / total;
      at += d;
      x.hi = at / total;
    }
    s.back().hi = 1;
  }
  return sides;
}

// The face coordinate (along axis side % 2) of side position sigma: sides 2 and 3 run backwards.
double face_coord(int side, double sigma) { return side >= 2 ? 1 - sigma : sigma; }

void insert_sorted(std::vector<double>& v, double x, bool& changed) {
  auto it = std::lower_bound(v.begin(), v.end(), x - kSame);
  if (it != v.end() && std::abs(*it - x) <= kSame) return;
  v.insert(it, x);
  changed = true;
}

}  // namespace

TSplineTriangulation tessellate(const TMeshSurface& s, double tolerance, int max_per_face) {
  require(tolerance > 0 && std::isfinite(tolerance), "tessellate: the chordal tolerance must be positive");
  require(max_per_face >= 1, "tessellate: max_per_face must be at least 1");
  // The topology as given: the mesh evaluated may be cut open along sharp creases (faces and their links keep
  // their numbers), and the two sides of a crease edge share its samples and vertices, so the triangles stay
  // one closed surface across it (both sides evaluate the same crease curve).
  const TMesh& m = s.face_mesh();
  const int nf = s.num_faces();
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  // Each edge's samples, as positions in (0, 1) from the start of its reference link (the smaller link id).
  std::vector<int> ref(m.intervals.size(), -1);
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l)
    if (L(l).vertex >= 0 && ref[static_cast<std::size_t>(L(l).edge)] < 0) ref[static_cast<std::size_t>(L(l).edge)] = l;
  const auto on_link = [&](int l, double t) { return ref[static_cast<std::size_t>(L(l).edge)] == l ? t : 1 - t; };
  std::vector<std::vector<double>> samples(m.intervals.size());
  std::vector<std::array<std::vector<SideLink>, 4>> sides(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    if (s.method(f) == FaceMethod::none) continue;
    sides[static_cast<std::size_t>(f)] = face_sides(m, f);
    // Second differences on a 9 x 9 grid.
    constexpr int g = 8;
    std::vector<std::array<double, 3>> x((g + 1) * (g + 1));
    for (int j = 0; j <= g; ++j)
      for (int i = 0; i <= g; ++i) {
        double o[9];
        s.eval(f, double(i) / g, double(j) / g, o);
        x[static_cast<std::size_t>(i + (g + 1) * j)] = {o[0], o[1], o[2]};
      }
    double d = 0;
    const auto at = [&](int i, int j) -> const std::array<double, 3>& { return x[static_cast<std::size_t>(i + (g + 1) * j)]; };
    for (int j = 0; j <= g; ++j)
      for (int i = 1; i < g; ++i)
        for (int c = 0; c < 3; ++c) {
          d = std::max(d, std::abs(at(i - 1, j)[c] - 2 * at(i, j)[c] + at(i + 1, j)[c]));
          d = std::max(d, std::abs(at(j, i - 1)[c] - 2 * at(j, i)[c] + at(j, i + 1)[c]));
        }
    d *= g * g;  // per unit face size
    const int n = clamped_count(std::sqrt(d / (8 * tolerance)), 1, max_per_face);
    for (const auto& side : sides[static_cast<std::size_t>(f)])
      for (const SideLink& x1 : side) {
        const int k = std::max(1, static_cast<int>(std::ceil(n * (x1.hi - x1.lo) - 1e-9)));
        auto& e = samples[static_cast<std::size_t>(L(x1.link).edge)];
        bool changed = false;
        if (static_cast<int>(e.size()) + 1 < k) {
          e.clear();
          for (int i = 1; i < k; ++i) insert_sorted(e, double(i) / k, changed);
        }
      }
  }
  // Carry samples across faces until every face's opposite sides agree.
  const auto axis_positions = [&](int f, int axis) {
    std::vector<double> u{0.0, 1.0};
    bool unused = false;
    for (int side : {axis, axis + 2})
      for (const SideLink& x : sides[static_cast<std::size_t>(f)][static_cast<std::size_t>(side)]) {
        insert_sorted(u, face_coord(side, x.lo), unused);
        insert_sorted(u, face_coord(side, x.hi), unused);
        for (double t : samples[static_cast<std::size_t>(L(x.link).edge)])
          insert_sorted(u, face_coord(side, x.lo + on_link(x.link, t) * (x.hi - x.lo)), unused);
      }
    return u;
  };
  std::size_t total = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (int f = 0; f < nf; ++f) {
      if (s.method(f) == FaceMethod::none) continue;
      for (int axis = 0; axis < 2; ++axis) {
        const std::vector<double> u = axis_positions(f, axis);
        for (int side : {axis, axis + 2})
          for (const SideLink& x : sides[static_cast<std::size_t>(f)][static_cast<std::size_t>(side)])
            for (double c : u) {
              const double sigma = face_coord(side, c);
              if (sigma <= x.lo + kSame || sigma >= x.hi - kSame) continue;
              auto& e = samples[static_cast<std::size_t>(L(x.link).edge)];
              const std::size_t before = e.size();
              insert_sorted(e, on_link(x.link, (sigma - x.lo) / (x.hi - x.lo)), changed);
              total += e.size() - before;
            }
      }
    }
    require(total < 4000000, "tessellate: the samples carried across T-junction faces exceed 4e6 points");
  }
  // Points: vertices and edge samples once, then each face's interior grid and its triangles.
  TSplineTriangulation out;
  std::vector<int> vertex_id(m.vertices.size(), -1);
  std::vector<std::vector<int>> edge_ids(m.intervals.size());
  for (std::size_t e = 0; e < samples.size(); ++e) edge_ids[e].assign(samples[e].size(), -1);
  const auto add_point = [&](int f, double u, double v) {
    double o[9];
    s.eval(f, u, v, o);
    out.points.push_back({o[0], o[1], o[2]});
    out.params.push_back({u, v});
    return static_cast<int>(out.points.size()) - 1;
  };
  for (int f = 0; f < nf; ++f) {
    if (s.method(f) == FaceMethod::none) continue;
    const std::vector<double> us = axis_positions(f, 0), vs = axis_positions(f, 1);
    const std::size_t nu = us.size(), nv = vs.size();
    std::vector<int> id(nu * nv, -1);
    const auto boundary_id = [&](int side, double c, double u, double v) {
      const double sigma = face_coord(side, c);
      for (const SideLink& x : sides[static_cast<std::size_t>(f)][static_cast<std::size_t>(side)]) {
        if (sigma < x.lo - kSame || sigma > x.hi + kSame) continue;
        int vtx = -1;
        if (std::abs(sigma - x.lo) <= kSame) vtx = L(x.link).vertex;
        if (std::abs(sigma - x.hi) <= kSame) vtx = L(L(x.link).opp).vertex;
        if (vtx >= 0) {
          int& i = vertex_id[static_cast<std::size_t>(vtx)];
          if (i < 0) i = add_point(f, u, v);
          return i;
        }
        const int e = L(x.link).edge;
        const double t = on_link(x.link, (sigma - x.lo) / (x.hi - x.lo));
        const auto& smp = samples[static_cast<std::size_t>(e)];
        const std::size_t k = static_cast<std::size_t>(std::lower_bound(smp.begin(), smp.end(), t - kSame) - smp.begin());
        require(k < smp.size() && std::abs(smp[k] - t) <= kSame, "tessellate: a face's grid misses its side's samples");
        int& i = edge_ids[static_cast<std::size_t>(e)][k];
        if (i < 0) i = add_point(f, u, v);
        return i;
      }
      throw Error("tessellate: a boundary sample outside its face's sides");
    };
    for (std::size_t j = 0; j < nv; ++j)
      for (std::size_t i = 0; i < nu; ++i) {
        const double u = us[i], v = vs[j];
        int& x = id[i + nu * j];
        if (j == 0) x = boundary_id(0, u, u, v);
        else if (j == nv - 1) x = boundary_id(2, u, u, v);
        else if (i == 0) x = boundary_id(3, v, u, v);
        else if (i == nu - 1) x = boundary_id(1, v, u, v);
        else x = add_point(f, u, v);
      }
    for (std::size_t j = 0; j + 1 < nv; ++j)
      for (std::size_t i = 0; i + 1 < nu; ++i) {
        const int a = id[i + nu * j], b = id[i + 1 + nu * j], c = id[i + 1 + nu * (j + 1)], d = id[i + nu * (j + 1)];
        out.triangles.push_back({a, b, c});
        out.triangles.push_back({a, c, d});
      }
  }
  return out;
}

}  // namespace trivar
