#include "trivar/model/boundary_tessellation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "trivar/core/error.hpp"

namespace trivar {

namespace {

using Vec = std::array<double, 3>;

Vec at(const TensorSpline<2>& s, const Param<2>& u) {
  Vec x;
  s.eval(u, x.data());
  return x;
}

double distance(const Vec& a, const Vec& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

Vec lerp(const Vec& a, const Vec& b, double t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

// Breakpoints of direction k mapped to [0, 1]: the places where the geometry may bend abruptly.
std::vector<double> unit_breaks(const TensorSpline<2>& s, int k) {
  std::vector<double> b = s.knots(k).breakpoints();
  const double lo = b.front(), len = b.back() - b.front();
  for (double& x : b) x = (x - lo) / len;
  b.front() = 0.0;
  b.back() = 1.0;
  return b;
}

std::vector<double> merged(std::vector<double> a, const std::vector<double>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
  return a;
}

// Splits every interval [t_i, t_{i+1}] of `samples` flagged by too_coarse(a, b) at its midpoint, repeatedly,
// until none is flagged or `max_samples` is reached.
template <class TooCoarse>
std::vector<double> refine_samples(std::vector<double> samples, int max_samples, const TooCoarse& too_coarse) {
  for (bool changed = true; changed && static_cast<int>(samples.size()) < max_samples;) {
    changed = false;
    std::vector<double> next{samples.front()};
    for (std::size_t i = 0; i + 1 < samples.size(); ++i) {
      if (static_cast<int>(next.size() + samples.size() - i) < max_samples && too_coarse(samples[i], samples[i + 1])) {
        next.push_back(0.5 * (samples[i] + samples[i + 1]));
        changed = true;
      }
      next.push_back(samples[i + 1]);
    }
    samples = std::move(next);
  }
  return samples;
}

// Distance of the curve points at the quarter points of [a, b] from the chord between its ends.
template <class Point>
double chord_error(const Point& point, double a, double b) {
  const Vec pa = point(a), pb = point(b);
  double e = 0;
  for (double f : {0.25, 0.5, 0.75}) e = std::max(e, distance(point(a + f * (b - a)), lerp(pa, pb, f)));
  return e;
}

struct Use {
  int face, side;
  bool reversed;
};

class Tessellator {
public:
  Tessellator(const Brep& brep, const TessellationOptions& opts) : brep_(brep), opts_(opts) {
    require(opts.chordal_tolerance > 0, "tessellate: the chordal tolerance must be positive");
    uses_.resize(brep.curves.size());
    for (std::size_t f = 0; f < brep.faces.size(); ++f) {
      const BrepFace& face = brep.faces[f];
      require(face.surface.dim() == 3, [&] { return "tessellate: face " + std::to_string(f) + " is not in 3-D"; });
      for (int s = 0; s < 4; ++s) {
        const int c = face.sides[s].curve;
        require(c >= 0 && c < static_cast<int>(brep.curves.size()), [&] {
          return "tessellate: face " + std::to_string(f) + " side " + std::to_string(s) + " names curve " +
                 std::to_string(c) + " of " + std::to_string(brep.curves.size());
        });
        uses_[c].push_back({static_cast<int>(f), s, face.sides[s].reversed});
      }
    }
    for (std::size_t c = 0; c < brep.curves.size(); ++c)
      for (int v : brep.curves[c].vertices)
        require(v >= 0 && v < brep.num_vertices,
                [&] { return "tessellate: curve " + std::to_string(c) + " names vertex " + std::to_string(v); });
  }

  BrepTessellation run() {
    out_.mesh.vertices.assign(static_cast<std::size_t>(brep_.num_vertices), Vec{});
    out_.origins.assign(static_cast<std::size_t>(brep_.num_vertices), VertexOrigin{});
    sample_curves();
    for (std::size_t f = 0; f < brep_.faces.size(); ++f) tessellate_face(static_cast<int>(f));
    return std::move(out_);
  }

private:
  Vec use_point(const Use& u, double t) const {
    const TensorSpline<2>& s = brep_.faces[u.face].surface;
    return at(s, side_parameters(s, u.side, u.reversed ? 1.0 - t : t));
  }

  int add_vertex(const Vec& x, int face, const Param<2>& uv) {
    out_.mesh.vertices.push_back(x);
    out_.origins.push_back({face, uv});
    return static_cast<int>(out_.mesh.vertices.size()) - 1;
  }

  // Every curve: samples in [0, 1] fine enough on all faces that use it, and the mesh vertex of each sample.
  void sample_curves() {
    const double tol = opts_.chordal_tolerance;
    samples_.resize(brep_.curves.size());
    ids_.resize(brep_.curves.size());
    for (std::size_t c = 0; c < brep_.curves.size(); ++c) {
      const std::vector<Use>& uses = uses_[c];
      if (uses.empty()) continue;
      std::vector<double> t{0.0, 1.0};
      for (const Use& u : uses) {
        std::vector<double> b = unit_breaks(brep_.faces[u.face].surface, 1 - u.side / 2);
        if (u.reversed)
          for (double& x : b) x = 1.0 - x;
        t = merged(std::move(t), b);
      }
      const bool closed = brep_.curves[c].vertices[0] == brep_.curves[c].vertices[1];
      bool collapsed = closed;
      for (double x : {0.25, 0.5, 0.75}) collapsed = collapsed && distance(use_point(uses[0], x), use_point(uses[0], 0)) <= tol;
      // A collapsed side (a pole) is one vertex; a closed curve would otherwise be a single chord.
      if (collapsed) t = {0.0, 1.0};
      if (closed && !collapsed && t.size() == 2) t = {0.0, 0.5, 1.0};
      if (!collapsed) t = refine_samples(std::move(t), opts_.max_samples, [&](double a, double b) {
        return std::any_of(uses.begin(), uses.end(), [&](const Use& u) {
          return chord_error([&](double x) { return use_point(u, x); }, a, b) > tol;
        });
      });
      const Use& first = uses.front();
      const TensorSpline<2>& s = brep_.faces[first.face].surface;
      for (const Use& u : uses)
        for (double x : t)
          require(distance(use_point(u, x), use_point(first, x)) <= 100 * tol, [&] {
            return "tessellate: faces " + std::to_string(first.face) + " and " + std::to_string(u.face) +
                   " do not meet along curve " + std::to_string(c);
          });
      std::vector<int>& ids = ids_[c];
      ids.resize(t.size());
      for (std::size_t i = 0; i < t.size(); ++i) {
        const Param<2> uv = side_parameters(s, first.side, first.reversed ? 1.0 - t[i] : t[i]);
        const bool end = i == 0 || i + 1 == t.size();
        if (end) {
          const int v = brep_.curves[c].vertices[i == 0 ? 0 : 1];
          if (out_.origins[v].face < 0) {
            out_.mesh.vertices[v] = at(s, uv);
            out_.origins[v] = {first.face, uv};
          }
          ids[i] = v;
        } else {
          ids[i] = add_vertex(at(s, uv), first.face, uv);
        }
      }
      samples_[c] = std::move(t);
    }
  }

  // The vertices and unit positions along one face side, in the side's increasing parameter.
  void side_samples(int face, int side, std::vector<int>& ids, std::vector<double>& pos) const {
    const FaceSide& fs = brep_.faces[face].sides[side];
    const std::vector<double>& t = samples_[fs.curve];
    const std::vector<int>& v = ids_[fs.curve];
    ids.clear();
    pos.clear();
    for (std::size_t i = 0; i < t.size(); ++i) {
      const std::size_t j = fs.reversed ? t.size() - 1 - i : i;
      ids.push_back(v[j]);
      pos.push_back(fs.reversed ? 1.0 - t[j] : t[j]);
    }
  }

  // Interior grid lines of direction k (unit positions, including 0 and 1), at least three so that an
  // interior ring exists.
  std::vector<double> grid_lines(const TensorSpline<2>& s, int k, std::vector<double> lines,
                                 const std::vector<double>& across) const {
    const Box<2> d = s.domain();
    const auto param = [&](double a, double b) {
      Param<2> p;
      p[k] = d.lo[k] + a * (d.hi[k] - d.lo[k]);
      p[1 - k] = d.lo[1 - k] + b * (d.hi[1 - k] - d.lo[1 - k]);
      return p;
    };
    if (lines.size() == 2) lines = {0.0, 0.5, 1.0};
    const double tol = opts_.chordal_tolerance;
    return refine_samples(std::move(lines), opts_.max_samples, [&](double a, double b) {
      for (std::size_t j = 0; j < across.size(); ++j) {
        if (chord_error([&](double x) { return at(s, param(x, across[j])); }, a, b) > tol) return true;
        // The quad centre against the mean of its corners catches twist that no grid line shows.
        if (j + 1 < across.size()) {
          const double c = 0.5 * (across[j] + across[j + 1]);
          const Vec m = lerp(lerp(at(s, param(a, across[j])), at(s, param(b, across[j])), 0.5),
                             lerp(at(s, param(a, across[j + 1])), at(s, param(b, across[j + 1])), 0.5), 0.5);
          if (distance(at(s, param(0.5 * (a + b), c)), m) > tol) return true;
        }
      }
      return false;
    });
  }

  void tessellate_face(int f) {
    const BrepFace& face = brep_.faces[f];
    const TensorSpline<2>& s = face.surface;
    const Box<2> d = s.domain();
    // Grid lines start from the knots and the samples of the sides along them, so the strip between the
    // boundary and the first interior ring is made of triangles no wider than the grid cells. Lines in u are
    // checked along v lines and vice versa; two rounds let each see the other's refinement.
    std::vector<int> ids;
    std::vector<double> pos;
    std::array<std::vector<double>, 2> start{unit_breaks(s, 0), unit_breaks(s, 1)};
    for (int side = 0; side < 4; ++side) {
      side_samples(f, side, ids, pos);
      start[1 - side / 2] = merged(std::move(start[1 - side / 2]), pos);
    }
    std::vector<double> gu = start[0], gv = start[1];
    for (int round = 0; round < 2; ++round) {
      gu = grid_lines(s, 0, merged(gu, start[0]), merged(gv, {0.5}));
      gv = grid_lines(s, 1, merged(gv, start[1]), merged(gu, {0.5}));
    }
    const int nu = static_cast<int>(gu.size()), nv = static_cast<int>(gv.size());
    const auto uv = [&](double a, double b) {
      return Param<2>{d.lo[0] + a * (d.hi[0] - d.lo[0]), d.lo[1] + b * (d.hi[1] - d.lo[1])};
    };
    // Interior vertices (i, j) for 1 <= i <= nu-2, 1 <= j <= nv-2.
    std::vector<int> grid(static_cast<std::size_t>(nu * nv), -1);
    for (int j = 1; j + 1 < nv; ++j)
      for (int i = 1; i + 1 < nu; ++i) {
        const Param<2> p = uv(gu[i], gv[j]);
        grid[i + nu * j] = add_vertex(at(s, p), f, p);
      }
    const auto tri = [&](int a, int b, int c) {
      if (face.flip) std::swap(b, c);
      out_.mesh.triangles.push_back({a, b, c});
    };
    for (int j = 1; j + 2 < nv; ++j)
      for (int i = 1; i + 2 < nu; ++i) {
        const int a = grid[i + nu * j], b = grid[i + 1 + nu * j], c = grid[i + 1 + nu * (j + 1)],
                  e = grid[i + nu * (j + 1)];
        tri(a, b, c);
        tri(a, c, e);
      }

    // Outer and inner loops, counter-clockwise in (u, v), each vertex with a perimeter coordinate in [0, 4):
    // side v = lo on [0, 1), u = hi on [1, 2), v = hi on [2, 3), u = lo on [3, 4).
    struct LoopVertex {
      int id;
      double s;
    };
    std::vector<LoopVertex> outer, inner;
    const std::array<int, 4> order{2, 1, 3, 0};  // face sides in loop order
    for (int q = 0; q < 4; ++q) {
      side_samples(f, order[q], ids, pos);
      const bool backwards = q >= 2;  // v = hi and u = lo run against their parameter
      for (std::size_t i = 0; i + 1 < ids.size(); ++i) {
        const std::size_t j = backwards ? ids.size() - 1 - i : i;
        outer.push_back({ids[j], q + (backwards ? 1.0 - pos[j] : pos[j])});
      }
    }
    // The inner loop starts at corner (1, 1); every side then lists its interior vertices and its end corner.
    // Positions use the outer loop's coordinates (unit parameters), so each inner vertex meets the boundary
    // samples facing it; a corner takes the position of the side it ends, which makes the outer corner
    // region fan to it.
    inner.push_back({grid[1 + nu], -gv[1]});
    for (int i = 2; i <= nu - 2; ++i) inner.push_back({grid[i + nu], gu[i]});
    for (int j = 2; j <= nv - 2; ++j) inner.push_back({grid[nu - 2 + nu * j], 1 + gv[j]});
    for (int i = nu - 3; i >= 1; --i) inner.push_back({grid[i + nu * (nv - 2)], 3 - gu[i]});
    for (int j = nv - 3; j >= 2; --j) inner.push_back({grid[1 + nu * j], 4 - gv[j]});

    // Steps between two entries of one vertex (a degenerate side) add no triangle.
    const std::size_t no = outer.size(), ni = inner.size();
    std::size_t io = 0, ii = 0;
    while (io < no || ii < ni) {
      const double so = io < no ? (io + 1 < no ? outer[io + 1].s : 4.0 + outer[0].s) : 6.0;
      const double si = ii < ni ? (ii + 1 < ni ? inner[ii + 1].s : 4.0 + inner[0].s) : 6.0;
      const int o = outer[io % no].id, in = inner[ii % ni].id;
      if (so <= si) {
        if (const int next = outer[(io + 1) % no].id; next != o) tri(o, next, in);
        ++io;
      } else {
        if (const int next = inner[(ii + 1) % ni].id; next != in) tri(o, next, in);
        ++ii;
      }
    }
  }

  const Brep& brep_;
  const TessellationOptions& opts_;
  std::vector<std::vector<Use>> uses_;
  std::vector<std::vector<double>> samples_;
  std::vector<std::vector<int>> ids_;
  BrepTessellation out_;
};

}  // namespace

BrepTessellation tessellate(const Brep& brep, const TessellationOptions& opts) {
  return Tessellator(brep, opts).run();
}

}  // namespace trivar
