#include "trivar/model/brep_from_surfaces.hpp"

#include <array>
#include <cmath>
#include <queue>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/core/vec3.hpp"

namespace trivar {

namespace {

using Vec = Vec3;

constexpr std::array<double, 3> kProbes{0.25, 0.5, 0.75};

// Direction in which the counter-clockwise loop of a face (normal S_u x S_v) runs along a side: sides v = lo
// and u = hi forwards, v = hi and u = lo backwards.
int loop_direction(int side) { return side == 1 || side == 2 ? 1 : -1; }

// Signed volume contribution (1/3) * integral of x . (S_u x S_v) over the face, by Gauss quadrature per
// element; only its sign per component is used, so moderate accuracy suffices.
double volume_term(const TensorSpline<2>& s) {
  const QuadratureRule q = gauss_legendre(6);
  const std::vector<double> bu = s.knots(0).breakpoints(), bv = s.knots(1).breakpoints();
  double sum = 0;
  double d[9];
  for (std::size_t i = 0; i + 1 < bu.size(); ++i)
    for (std::size_t j = 0; j + 1 < bv.size(); ++j)
      for (std::size_t a = 0; a < q.nodes.size(); ++a)
        for (std::size_t b = 0; b < q.nodes.size(); ++b) {
          const double du = bu[i + 1] - bu[i], dv = bv[j + 1] - bv[j];
          s.eval_derivs({bu[i] + q.nodes[a] * du, bv[j] + q.nodes[b] * dv}, 1, d);
          const double* x = d;
          const double* su = d + 3;
          const double* sv = d + 6;
          const double n[3] = {su[1] * sv[2] - su[2] * sv[1], su[2] * sv[0] - su[0] * sv[2],
                               su[0] * sv[1] - su[1] * sv[0]};
          sum += q.weights[a] * q.weights[b] * du * dv * (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]);
        }
  return sum / 3.0;
}

struct CurveRecord {
  int face, side;        // the first use, which defines the curve's direction
  bool collapsed;        // a side shrunk to a point: never shared
  std::vector<std::pair<int, int>> uses;  // (face, side)
};

}  // namespace

Brep brep_from_surfaces(std::vector<TensorSpline<2>> surfaces, const BrepOptions& opts) {
  const double tol = opts.tolerance;
  require(tol > 0, "brep_from_surfaces: the tolerance must be positive");
  Brep brep;
  std::vector<Vec> vertex_pos;
  const auto vertex_of = [&](const Vec& x) {
    for (std::size_t v = 0; v < vertex_pos.size(); ++v)
      if (distance(vertex_pos[v], x) <= tol) return static_cast<int>(v);
    vertex_pos.push_back(x);
    return static_cast<int>(vertex_pos.size()) - 1;
  };
  std::vector<CurveRecord> records;
  for (std::size_t f = 0; f < surfaces.size(); ++f) {
    const TensorSpline<2>& s = surfaces[f];
    require(s.dim() == 3, [&] { return "brep_from_surfaces: surface " + std::to_string(f) + " is not in 3-D"; });
    BrepFace face;
    face.surface = s;
    for (int side = 0; side < 4; ++side) {
      const std::array<int, 2> ends{vertex_of(side_point(s, side, 0.0)), vertex_of(side_point(s, side, 1.0))};
      bool collapsed = ends[0] == ends[1];
      for (double t : kProbes) collapsed = collapsed && distance(side_point(s, side, t), vertex_pos[ends[0]]) <= tol;
      int found = -1;
      bool reversed = false;
      for (std::size_t c = 0; c < records.size() && found < 0 && !collapsed; ++c) {
        const CurveRecord& r = records[c];
        const std::array<int, 2>& ce = brep.curves[c].vertices;
        if (r.collapsed) continue;
        for (bool rev : {false, true}) {
          if (ends[rev ? 1 : 0] != ce[0] || ends[rev ? 0 : 1] != ce[1]) continue;
          bool same = true;
          for (double t : kProbes)
            same = same && distance(side_point(s, side, rev ? 1.0 - t : t),
                                    side_point(surfaces[r.face], r.side, t)) <= tol;
          if (same) {
            found = static_cast<int>(c);
            reversed = rev;
            break;
          }
        }
      }
      if (found < 0) {
        found = static_cast<int>(records.size());
        records.push_back({static_cast<int>(f), side, collapsed, {}});
        brep.curves.push_back({ends});
      }
      require(records[found].uses.size() < 2, [&] {
        return "brep_from_surfaces: face " + std::to_string(f) + " side " + std::to_string(side) +
               " is the third side on one curve (faces " + std::to_string(records[found].uses[0].first) + " and " +
               std::to_string(records[found].uses[1].first) + ")";
      });
      records[found].uses.emplace_back(static_cast<int>(f), side);
      face.sides[side] = {found, reversed};
    }
    brep.faces.push_back(std::move(face));
  }
  brep.num_vertices = static_cast<int>(vertex_pos.size());
  if (opts.require_closed)
    for (const CurveRecord& r : records)
      require(r.collapsed || r.uses.size() == 2, [&] {
        return "brep_from_surfaces: face " + std::to_string(r.face) + " side " + std::to_string(r.side) +
               " meets no other face (the surfaces do not close up)";
      });

  // Orientation by breadth-first propagation: across a shared curve the two loops must run oppositely.
  const int nf = static_cast<int>(brep.faces.size());
  std::vector<int> component(static_cast<std::size_t>(nf), -1);
  std::vector<double> component_volume;
  for (int seed = 0; seed < nf; ++seed) {
    if (component[seed] >= 0) continue;
    const int comp = static_cast<int>(component_volume.size());
    component_volume.push_back(0.0);
    component[seed] = comp;
    std::queue<int> todo;
    todo.push(seed);
    while (!todo.empty()) {
      const int f = todo.front();
      todo.pop();
      const BrepFace& face = brep.faces[f];
      component_volume[comp] += (face.flip ? -1 : 1) * volume_term(face.surface);
      for (int side = 0; side < 4; ++side) {
        const CurveRecord& r = records[face.sides[side].curve];
        if (r.collapsed) continue;
        for (const auto& [g, gside] : r.uses) {
          if (g == f && gside == side) continue;
          const auto run = [&](int h, int hside) {
            const BrepFace& hf = brep.faces[h];
            return loop_direction(hside) * (hf.sides[hside].reversed ? -1 : 1) * (hf.flip ? -1 : 1);
          };
          if (component[g] < 0) {
            component[g] = comp;
            brep.faces[g].flip = run(f, side) == run(g, gside) ? !brep.faces[g].flip : brep.faces[g].flip;
            todo.push(g);
          } else {
            require(run(f, side) != run(g, gside), [&] {
              return "brep_from_surfaces: faces " + std::to_string(f) + " and " + std::to_string(g) +
                     " cannot be oriented consistently (a one-sided surface)";
            });
          }
        }
      }
    }
  }
  for (int f = 0; f < nf; ++f)
    if (component_volume[component[f]] < 0) brep.faces[f].flip = !brep.faces[f].flip;
  return brep;
}

}  // namespace trivar
