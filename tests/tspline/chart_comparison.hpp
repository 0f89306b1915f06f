#pragma once
// The faces of a T-mesh surface against the T-spline of the chart of their two face rings (an independent
// evaluation: Bezier extraction of sum w P B / sum w B on the chart's local knot vectors), where that chart
// exists (no star point inside the rings).
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar::test {

// The faces within `depth` rings (faces sharing a vertex with the previous ring) of face f.
inline std::vector<int> face_rings(const TMesh& m, int f, int depth) {
  std::vector<std::vector<int>> at(m.vertices.size());
  for (const TMeshLink& k : m.links)
    if (k.vertex >= 0 && k.face >= 0) at[static_cast<std::size_t>(k.vertex)].push_back(k.face);
  std::vector<int> dist(m.faces.size(), INT_MAX), all{f}, front{f};
  dist[static_cast<std::size_t>(f)] = 0;
  for (int r = 1; r <= depth; ++r) {
    std::vector<int> next;
    for (int g : front)
      for (int l : m.faces[static_cast<std::size_t>(g)])
        for (int h : at[static_cast<std::size_t>(m.links[static_cast<std::size_t>(l)].vertex)])
          if (dist[static_cast<std::size_t>(h)] > r) {
            dist[static_cast<std::size_t>(h)] = r;
            next.push_back(h);
            all.push_back(h);
          }
    front = std::move(next);
  }
  return all;
}

struct ChartComparison {
  int compared = 0;
  double position = 0, derivative = 0;  // largest differences (derivatives in the face's (u, v))
};

// Every face of `method` whose two rings hold no star point.
inline ChartComparison compare_with_charts(const TMesh& mesh, const TMeshSurface& s, FaceMethod method) {
  ChartComparison r;
  for (int f = 0; f < s.num_faces(); ++f) {
    if (s.method(f) != method) continue;
    const std::vector<int> hood = face_rings(mesh, f, 2);
    // A star point inside the rings: no chart (one on the boundary lays out without an error, overlapping).
    const auto has_star = [&](int g) {
      return std::any_of(mesh.faces[static_cast<std::size_t>(g)].begin(), mesh.faces[static_cast<std::size_t>(g)].end(), [&](int l) {
        const int v = mesh.links[static_cast<std::size_t>(l)].vertex;
        return std::find(s.stars().begin(), s.stars().end(), v) != s.stars().end();
      });
    };
    if (std::any_of(hood.begin(), hood.end(), has_star)) continue;
    TChart chart;
    try {
      chart = t_spline_chart(mesh, hood, f, false);
    } catch (const Error&) {
      continue;  // a star point inside the rings
    }
    const TSplineSurface ts(chart.spline, 1);
    const auto c = s.corners(f);
    const auto st = [&](int v) {
      const TVertex& x = chart.spline.image.vertices[static_cast<std::size_t>(chart.vertex[static_cast<std::size_t>(v)])];
      return std::array<double, 2>{x.s, x.t};
    };
    const auto p0 = st(c[0]), p1 = st(c[1]), p3 = st(c[3]);
    ++r.compared;
    for (double u : {0.0, 0.23, 0.5, 0.91})
      for (double v : {0.07, 0.5, 1.0}) {
        double a[9], b[9];
        s.eval(f, u, v, a);
        const Param<2> x{p0[0] + u * (p1[0] - p0[0]) + v * (p3[0] - p0[0]), p0[1] + u * (p1[1] - p0[1]) + v * (p3[1] - p0[1])};
        ts.eval_first_derivatives(x, b);
        for (int k = 0; k < 3; ++k) {
          r.position = std::max(r.position, std::abs(a[k] - b[k]));
          const double du = (p1[0] - p0[0]) * b[3 + k] + (p1[1] - p0[1]) * b[6 + k];
          const double dv = (p3[0] - p0[0]) * b[3 + k] + (p3[1] - p0[1]) * b[6 + k];
          r.derivative = std::max({r.derivative, std::abs(a[3 + k] - du), std::abs(a[6 + k] - dv)});
        }
      }
  }
  return r;
}

}  // namespace trivar::test
