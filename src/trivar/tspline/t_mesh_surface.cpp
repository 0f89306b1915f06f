#include "trivar/tspline/t_mesh_surface.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <span>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/tspline/boundary_ghosts.hpp"
#include "trivar/tspline/catmull_clark_patch.hpp"
#include "trivar/tspline/crease_ends.hpp"
#include "trivar/tspline/exact_chart.hpp"
#include "trivar/tspline/non_uniform_catmull_clark.hpp"
#include "trivar/tspline/non_uniform_subdivision.hpp"
#include "trivar/tspline/sharp_creases.hpp"

namespace trivar {

const char* face_method_name(FaceMethod m) {
  switch (m) {
    case FaceMethod::none: return "none";
    case FaceMethod::exact: return "exact";
    case FaceMethod::bicubic: return "bicubic";
    case FaceMethod::star: return "star";
    case FaceMethod::non_uniform: return "non-uniform";
    case FaceMethod::subdivided: return "subdivided";
    case FaceMethod::crease: return "crease";
    case FaceMethod::averaging: return "averaging";
  }
  return "?";
}

CornerFrame corner_frame(int corner) {
  static constexpr std::array<CornerFrame, 4> frames{{{{0, 0}, {1, 0}, {0, 1}},
                                                      {{1, 0}, {0, 1}, {-1, 0}},
                                                      {{1, 1}, {-1, 0}, {0, -1}},
                                                      {{0, 1}, {0, -1}, {1, 0}}}};
  return frames[static_cast<std::size_t>(corner)];
}

namespace {

struct Gather {
  std::vector<int> points;  // mesh vertices in the catmull_clark_patch layout
  std::string error;        // why the face's neighbourhood is not a Catmull-Clark patch
};

// The 2N + 8 vertices around the corner that link l0 (in its face) leaves, in the catmull_clark_patch layout.
Gather gather(const TMesh& m, int l0) {
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const auto nxt = [&](int l, int k) {
    for (int i = 0; i < k; ++i) l = L(l).next;
    return l;
  };
  const auto quad = [&](int l) {
    return L(l).face >= 0 && m.faces[static_cast<std::size_t>(L(l).face)].size() == 4;
  };
  Gather g;
  const int v = L(l0).vertex;
  std::vector<int> ring;  // links leaving v, one per face counter-clockwise
  int l = l0;
  do {
    if (!quad(l)) {
      g.error = "a face at vertex " + std::to_string(v) + " is not a quadrilateral without T-junctions, or it is on the boundary";
      return g;
    }
    ring.push_back(l);
    l = L(L(l).prev).opp;
  } while (l != l0 && ring.size() <= 64);
  if (l != l0 || ring.size() < 3) {
    g.error = "vertex " + std::to_string(v) + " has no closed ring of 3 to 64 faces";
    return g;
  }
  const int n = static_cast<int>(ring.size());
  g.points.push_back(v);
  for (int i = 0; i < n; ++i) {
    g.points.push_back(L(nxt(ring[static_cast<std::size_t>(i)], 1)).vertex);
    g.points.push_back(L(nxt(ring[static_cast<std::size_t>(i)], 2)).vertex);
  }
  // The outer faces: beyond e_0 d_0 (o1), beyond d_0 (o2), beyond d_0 e_1 (o3), beyond e_0 d_(N-1) (o4),
  // beyond e_1 d_1 (o5); each must be a quadrilateral and the rings at e_0, d_0, e_1 must close with four faces.
  const int o1 = L(nxt(l0, 1)).opp, o3 = L(nxt(l0, 2)).opp;
  const int o2 = quad(o1) ? L(nxt(o1, 3)).opp : -1;
  const int o4 = L(nxt(ring.back(), 2)).opp, o5 = L(nxt(ring[1], 1)).opp;
  for (int o : {o1, o2, o3, o4, o5})
    if (o < 0 || !quad(o)) {
      g.error = "the faces around vertex " + std::to_string(v) + " are not surrounded by quadrilaterals";
      return g;
    }
  const int x20 = L(nxt(o1, 2)).vertex, x21 = L(nxt(o1, 3)).vertex, x22 = L(nxt(o2, 2)).vertex,
            x12 = L(nxt(o2, 3)).vertex, x02 = L(nxt(o3, 3)).vertex, x2m = L(nxt(o4, 2)).vertex,
            xm2 = L(nxt(o5, 3)).vertex;
  if (L(nxt(o3, 2)).vertex != x12 || L(nxt(o4, 3)).vertex != x20 || L(nxt(o5, 2)).vertex != x02) {
    g.error = "a vertex next to vertex " + std::to_string(v) + " is a second star point or a T-junction";
    return g;
  }
  for (int x : {x2m, x20, x21, x22, x12, x02, xm2}) g.points.push_back(x);
  return g;
}

// The sectors around star point v for non-uniform Catmull-Clark: the level-0 points (NonUniformStar layout),
// the knot intervals U_k[0..3] along the spokes, and per sector the faces of the cells (0, 0), (1, 0), (1, 1),
// (0, 1) with the link leaving each cell's corner (a, b) towards (a + 1, b).
struct Sectors {
  std::vector<int> points;
  std::vector<std::array<double, 4>> intervals;
  std::vector<std::array<std::array<int, 2>, 4>> cells;  // (face, link) per sector and cell
  std::string error;
};

Sectors gather_sectors(const TMesh& m, int v) {
  const auto L = [&](int x) -> const TMeshLink& { return m.links[static_cast<std::size_t>(x)]; };
  const auto target = [&](int x) { return L(L(x).next).vertex; };
  const auto interval = [&](int x) { return m.intervals[static_cast<std::size_t>(L(x).edge)]; };
  Sectors s;
  std::vector<int> spokes;
  int l0 = -1;
  for (int l = 0; l < static_cast<int>(m.links.size()) && l0 < 0; ++l)
    if (L(l).vertex == v && L(l).face >= 0) l0 = l;
  int l = l0;
  do {
    if (L(l).face < 0 || L(l).prev < 0) break;
    spokes.push_back(l);
    l = L(L(l).prev).opp;
  } while (l >= 0 && l != l0 && spokes.size() <= 64);
  if (l != l0 || spokes.size() < 3) {
    s.error = "star point " + std::to_string(v) + " has no closed ring of 3 to 64 faces";
    return s;
  }
  const int n = static_cast<int>(spokes.size());
  s.points.assign(static_cast<std::size_t>(1 + 12 * n), -1);
  s.points[0] = v;
  s.intervals.resize(static_cast<std::size_t>(n));
  s.cells.resize(static_cast<std::size_t>(n));
  // v-direction edges of each sector, checked against the next spoke's intervals once all are known.
  std::vector<std::array<std::array<double, 3>, 3>> up(static_cast<std::size_t>(n));
  const auto fail = [&](const std::string& what) {
    s.error = "the faces within 3 rings of star point " + std::to_string(v) + " " + what +
              "; non-uniform Catmull-Clark needs quadrilaterals without T-junctions, vertices of 4 faces and no boundary there";
  };
  for (int k = 0; k < n; ++k) {
    int spoke = spokes[static_cast<std::size_t>(k)];
    for (int i = 1; i <= 3; ++i) {
      if (i > 1) spoke = straight_link(m, spoke);
      if (spoke < 0) {
        fail("are not a regular grid along spoke " + std::to_string(k));
        return s;
      }
      s.intervals[static_cast<std::size_t>(k)][static_cast<std::size_t>(i - 1)] = interval(spoke);
      s.points[static_cast<std::size_t>(NonUniformStar::index(k, i, 0))] = target(spoke);
      int col = L(spoke).next;  // (i, 0) -> (i, 1)
      for (int j = 1; j <= 3; ++j) {
        if (j > 1) col = straight_link(m, col);
        if (col < 0 || L(col).face < 0 || m.faces[static_cast<std::size_t>(L(col).face)].size() != 4) {
          fail("are not a regular grid in sector " + std::to_string(k));
          return s;
        }
        s.points[static_cast<std::size_t>(NonUniformStar::index(k, i, j))] = target(col);
        up[static_cast<std::size_t>(k)][static_cast<std::size_t>(i - 1)][static_cast<std::size_t>(j - 1)] = interval(col);
        // The cell (i - 1, j - 1) left of the column: its sides along u have the spoke's interval i - 1.
        const int across = L(col).next;
        if (std::abs(interval(across) - s.intervals[static_cast<std::size_t>(k)][static_cast<std::size_t>(i - 1)]) >
            1e-12 * interval(across)) {
          fail("have knot intervals that differ on opposite sides of face " + std::to_string(L(col).face));
          return s;
        }
        if (i <= 2 && j <= 2) {
          static constexpr std::array<std::array<int, 2>, 2> slot{{{0, 3}, {1, 2}}};  // cell (a, b) -> 0..3
          s.cells[static_cast<std::size_t>(k)][static_cast<std::size_t>(slot[static_cast<std::size_t>(i - 1)][static_cast<std::size_t>(j - 1)])] =
              {L(col).face, L(col).prev};
        }
      }
    }
    const int beyond = straight_link(m, spoke);
    if (beyond < 0) {
      fail("are not a regular grid along spoke " + std::to_string(k));
      return s;
    }
    s.intervals[static_cast<std::size_t>(k)][3] = interval(beyond);
  }
  for (int k = 0; k < n; ++k)
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j) {
        const double a = up[static_cast<std::size_t>(k)][i][j], b = s.intervals[static_cast<std::size_t>((k + 1) % n)][j];
        if (std::abs(a - b) > 1e-12 * b) {
          fail("have knot intervals that differ along a strip of spoke " + std::to_string((k + 1) % n));
          return s;
        }
      }
  std::vector<int> sorted = s.points;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) fail("close on themselves");

  return s;
}

// Faces of mesh m (vertex_faces: the faces at each vertex) in `ring_count` rings around `front`: each ring the faces
// sharing a vertex with the previous one; dist holds each face's ring (faces already nearer are not revisited).
std::vector<int> face_rings(const TMesh& m, const std::vector<std::vector<int>>& vertex_faces, std::vector<int> front, int ring_count,
                            std::vector<int>& dist) {
  std::vector<int> all = front;
  for (int r = 1; r <= ring_count && !front.empty(); ++r) {
    std::vector<int> next;
    for (int f : front)
      for (int l : m.faces[static_cast<std::size_t>(f)])
        for (int g : vertex_faces[static_cast<std::size_t>(m.links[static_cast<std::size_t>(l)].vertex)])
          if (dist[static_cast<std::size_t>(g)] > r) {
            dist[static_cast<std::size_t>(g)] = r;
            next.push_back(g);
            all.push_back(g);
          }
    front = std::move(next);
  }
  return all;
}

std::vector<std::vector<int>> faces_at_vertices(const TMesh& m) {
  std::vector<std::vector<int>> out(m.vertices.size());
  for (const TMeshLink& k : m.links)
    if (k.vertex >= 0 && k.face >= 0) out[static_cast<std::size_t>(k.vertex)].push_back(k.face);
  return out;
}

// The knots of the bicubic cell of the quad whose corner link is l0 (from (0, 0) to (1, 0)), six per direction in
// units of the cell's side: two intervals before it, its own, two after, read along the lines through (0, 0). A
// line that ends at a vertex of a ghost layer (ids from first_ghost on, on the extended mesh's boundary) goes on
// with its last interval: the ghost rows are placed for that (boundary_ghosts).
std::optional<std::array<std::array<double, 6>, 2>> cell_knots(const TMesh& m, int l0, int first_ghost) {
  const auto L = [&](int x) -> const TMeshLink& { return m.links[static_cast<std::size_t>(x)]; };
  const auto interval = [&](int x) { return m.intervals[static_cast<std::size_t>(L(x).edge)]; };
  // The intervals of the links straight on after link l, into out[0], out[1], ... (a ghost vertex repeats the last).
  const auto read_on = [&](int l, std::span<double> out) {
    double last = interval(l);
    for (double& o : out) {
      if (l >= 0) {
        const int n = straight_link(m, l);
        if (n < 0 && L(L(l).next).vertex < first_ghost) return false;
        if (n >= 0) last = interval(n);
        l = n;
      }
      o = last;
    }
    return true;
  };
  std::array<std::array<double, 6>, 2> k{};
  const std::array<int, 2> axis{l0, L(L(l0).prev).opp};
  for (std::size_t d = 0; d < 2; ++d) {
    std::array<double, 5> h{};  // intervals -2 .. 2
    h[2] = interval(axis[d]);
    std::array<double, 2> before{};
    if (!read_on(axis[d], std::span<double>(h).subspan(3, 2)) || !read_on(L(axis[d]).opp, before)) return std::nullopt;
    h[1] = before[0];
    h[0] = before[1];
    k[d][2] = 0;
    for (std::size_t i = 3; i < 6; ++i) k[d][i] = k[d][i - 1] + h[i - 1] / h[2];
    for (std::size_t i = 2; i-- > 0;) k[d][i] = k[d][i + 1] - h[i] / h[2];
  }
  return k;
}

// The crease net of face f of the mesh cut open along its creases (`m`, with the points of `given`): its two face
// rings `hood` (f first), `rules` its boundary_rules; `where` begins the errors. Refused in one line: T-junctions,
// knot intervals that differ on opposite sides of a face, vertices without one control point.
CreaseNet crease_net(const TMesh& m, const TMesh& given, const std::vector<CreaseRule>& rules, int f, const std::vector<int>& hood,
                     const std::string& where) {
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const auto name = [&](int v) {
    const int from = m.vertices[static_cast<std::size_t>(v)].split_from;  // a side of a sharp crease: the file's vertex
    return std::to_string(from >= 0 ? from : v);
  };
  CreaseNet net;
  std::vector<int> id(m.vertices.size(), -1);
  for (int g : hood) {
    const auto& loop = m.faces[static_cast<std::size_t>(g)];
    require(loop.size() == 4, [&] { return where + "face " + std::to_string(g) + " nearby has a T-junction; local subdivision takes quadrilaterals"; });
    int start = 0;
    if (g == f)
      while (loop[static_cast<std::size_t>(start)] != m.first_corner(f)) ++start;
    std::array<int, 4> quad{};
    std::array<bool, 4> sharp{};
    std::array<double, 4> intervals{};
    for (std::size_t k = 0; k < 4; ++k) {
      const int l = loop[(static_cast<std::size_t>(start) + k) % 4], v = L(l).vertex;
      intervals[k] = m.intervals[static_cast<std::size_t>(L(l).edge)];
      require(intervals[k] > 0, [&] {
        return where + "edge " + std::to_string(L(l).edge) + " nearby has knot interval " + std::to_string(intervals[k]) +
               "; local subdivision takes positive intervals";
      });
      const int o = L(l).opp;
      sharp[k] = L(o).face < 0 || !m.live_face(L(o).face);
      if (id[static_cast<std::size_t>(v)] < 0) {
        const TMeshVertex& gv = given.vertices[static_cast<std::size_t>(v)];
        require(gv.primary >= 0 && gv.block.empty(), [&] {
          return where + "vertex " + name(v) + " has no control point or repeated-knot nodes; local subdivision needs one point per vertex";
        });
        const RationalPoint& p = given.points[static_cast<std::size_t>(gv.primary)];
        id[static_cast<std::size_t>(v)] = static_cast<int>(net.points.size());
        net.points.push_back({p.w * p.xyz[0], p.w * p.xyz[1], p.w * p.xyz[2], p.w});
        // In CreaseRule's order: none (inside the mesh), crease, corner, dart.
        static constexpr std::array<VertexRule, 4> rule_of{VertexRule::smooth, VertexRule::crease, VertexRule::corner, VertexRule::dart};
        net.rules.push_back(rule_of[static_cast<std::size_t>(rules[static_cast<std::size_t>(v)])]);
      }
      quad[k] = id[static_cast<std::size_t>(v)];
    }
    for (std::size_t k = 0; k < 2; ++k)
      require(std::abs(intervals[k] - intervals[k + 2]) <= 1e-12 * intervals[k], [&] {
        return where + "face " + std::to_string(g) + " nearby has knot intervals " + std::to_string(intervals[k]) + " and " +
               std::to_string(intervals[k + 2]) + " on opposite sides; local subdivision takes one interval per strip";
      });
    net.quads.push_back(quad);
    net.sharp.push_back(sharp);
    net.intervals.push_back(intervals);
  }
  return net;
}

// The mesh after `steps` global non-uniform Catmull-Clark steps.
TMesh refined(const TMesh& m, int steps) {
  TMesh r = nurcc_step(m);
  for (int i = 1; i < steps; ++i) r = nurcc_step(r);
  return r;
}

}  // namespace

struct TMeshSurface::Nurcc {
  NonUniformStar star;
  std::vector<std::array<double, 4>> points;  // homogeneous (w x, w y, w z, w) in the NonUniformStar layout
};

TMeshSurface::~TMeshSurface() = default;
TMeshSurface::TMeshSurface(TMeshSurface&&) noexcept = default;

TMeshSurface::TMeshSurface(const TMesh& mesh, int threads, int global_steps)
    : TMeshSurface(mesh, has_creases(mesh) ? std::make_unique<TMesh>(split_creases(mesh)) : nullptr, threads, global_steps) {}

// A crease boundary, or Bezier end conditions without block points, is evaluated as the Bezier end conditions
// of the same surface with its block points (crease_ends); the mesh as given is kept for writing it back.
TMeshSurface::TMeshSurface(const TMesh& mesh, std::unique_ptr<TMesh> cut, int threads, int global_steps)
    : lines_(mesh.degree == 1 ? std::nullopt : complete_t_junction_lines(cut ? *cut : mesh, mesh.degree + 2)),
      steps_(global_steps >= 0 ? global_steps : nurcc_steps_needed(lines_ ? lines_->mesh : mesh, kStarsApart)),
      mesh_(steps_ > 0 ? refined(lines_ ? lines_->mesh : mesh, steps_)
                       : bezier_equivalent_of_cut(lines_ ? lines_->mesh : cut ? *cut : mesh)),
      source_(steps_ == 0 && !lines_ && mesh.end_conditions == EndConditions::bezier && mesh_.points.size() == mesh.points.size()
                  ? nullptr
                  : std::make_unique<TMesh>(mesh)),
      stars_(star_points(mesh_)) {
  // A crease boundary's irregular vertices (crease vertices of other than two faces, corners of other than one):
  // their faces are evaluated by local subdivision of the mesh cut open along its creases (the vertices, faces and
  // links of mesh_, the points as given: after the lines or the global steps, their points), as are the faces near
  // star points that are too close to a crease boundary for Stam's patches.
  std::unique_ptr<TMesh> split;
  if (mesh.end_conditions == EndConditions::subd_creases)
    split = steps_ > 0 ? std::make_unique<TMesh>(mesh_)
            : lines_   ? std::make_unique<TMesh>(std::move(lines_->mesh))
            : cut      ? std::move(cut)
                       : std::make_unique<TMesh>(mesh);
  if (lines_) {
    lines_->mesh = TMesh{};
    pieces_of_.resize(mesh.faces.size());
    for (std::size_t f = 0; f < lines_->pieces.size(); ++f)
      pieces_of_[static_cast<std::size_t>(lines_->pieces[f].source)].push_back(static_cast<int>(f));
  }
  const TMesh& m = mesh_;
  const int nf = static_cast<int>(m.faces.size()), nv = static_cast<int>(m.vertices.size());
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  faces_.resize(static_cast<std::size_t>(nf));
  {
    // A concave corner's end-condition nodes form a ring all round it (Rhino writes 8 at degree 3): with some
    // directions only, the blending functions of those nodes, clamped across one side, reach over the corner's
    // interior edges, where they jump.
    const VertexAngles angles = vertex_angles(m);
    for (int v = 0; v < nv; ++v) {
      const TMeshVertex& mv = m.vertices[static_cast<std::size_t>(v)];
      const auto& d = mv.block_dims;
      require(!angles.boundary[static_cast<std::size_t>(v)] || angles.degrees[static_cast<std::size_t>(v)] != 270 || mv.block.empty() ||
                  (d[0] > 0 && d[1] == d[0] && d[2] == d[0] && d[3] == d[0]),
              [&] {
                return "T-mesh: concave corner vertex " + std::to_string(v) + " has end-condition nodes in block dims " + std::to_string(d[0]) + " " +
                       std::to_string(d[1]) + " " + std::to_string(d[2]) + " " + std::to_string(d[3]) +
                       "; a concave corner needs them all round (one ring, 8 nodes at degree 3), else the blending functions clamped "
                       "across one side jump across its interior edges";
              });
    }
  }
  if (m.degree == 1 && !split) {
    // Degree 1: a blending function restricted to a face is its hat on that face's own knots (the face's corners and
    // the vertices on its sides, where the stems of those T-junctions, in the faces across, end the rays along the
    // sides; the knots beyond bound its supports elsewhere), star point or not. So each face is the T-spline of the
    // chart of itself and the faces across its T-junctions: bilinear pieces, continuous across every edge.
    for (int f = 0; f < nf; ++f) {
      if (!m.live_face(f)) continue;
      const std::array<int, 1> self{f};
      std::vector<int> chart{f};
      const auto& loop = m.faces[static_cast<std::size_t>(f)];
      for (std::size_t i = 0; i < loop.size(); ++i)
        if (L(loop[i]).flag == 1)
          for (int l : {loop[i], loop[(i + loop.size() - 1) % loop.size()]})
            if (const int g = L(L(l).opp).face; g >= 0 && std::find(chart.begin(), chart.end(), g) == chart.end()) chart.push_back(g);
      ExactChart c = exact_chart(m, chart, f, self, 1);
      Face& face = faces_[static_cast<std::size_t>(f)];
      face.method = FaceMethod::exact;
      face.origin = c.frames[0].origin;
      face.axis_u = c.frames[0].axis_u;
      face.axis_v = c.frames[0].axis_v;
      face.chart = static_cast<int>(charts_.size());
      charts_.push_back(std::move(c.surface));
    }
    return;
  }
  std::vector<int> irregular;
  std::vector<CreaseRule> rules;  // of the boundary vertices of local subdivision's mesh, once needed
  std::vector<CreaseRule> smooth;  // the averaging faces' nets: no crease rule anywhere, once needed
  if (split) irregular = irregular_crease_vertices(*split);
  std::vector<char> is_irregular(static_cast<std::size_t>(nv), 0);
  for (int v : irregular) is_irregular[static_cast<std::size_t>(v)] = 1;
  const std::vector<std::vector<int>> vertex_faces = faces_at_vertices(m);
  std::vector<char> boundary(static_cast<std::size_t>(nv), 0);
  for (const TMeshLink& k : m.links)
    if (k.vertex >= 0 && k.face < 0) boundary[static_cast<std::size_t>(k.vertex)] = 1;
  const int depth = m.degree + 1;
  // Star points on or near a Bezier boundary: interior ones of the control mesh with a ghost layer (boundary_ghosts)
  // over the boundary vertices of every face within (p + 1) / 2 rings of a Catmull-Clark face (depth + 2 rings of
  // the star points' faces, whose vertices lie depth + 3 steps across faces from the star points). A crease
  // boundary's rules are local subdivision's instead.
  std::vector<char> ghosted(static_cast<std::size_t>(nv), 0);
  double ghost_interval = 0;
  if (!split && m.degree == 3 && !stars_.empty() && std::find(boundary.begin(), boundary.end(), 1) != boundary.end()) {
    GhostedMesh gm = ghost_boundary(m, stars_, depth + 3);
    for (int v = 0; v < nv; ++v) ghosted[static_cast<std::size_t>(v)] = gm.ghost[static_cast<std::size_t>(v)] >= 0;
    ghost_interval = gm.interval;
    if (std::find(ghosted.begin(), ghosted.end(), 1) != ghosted.end()) ghosted_ = std::make_unique<TMesh>(std::move(gm.mesh));
  }
  const TMesh& cm = cc_mesh();
  // Face rings: faces sharing a vertex with the previous ring.
  const auto rings = [&](std::vector<int> front, int ring_count, std::vector<int>& dist) {
    return face_rings(m, vertex_faces, std::move(front), ring_count, dist);
  };
  // The face rings the supports of the blending functions on a face span on a uniform quad mesh: their anchors
  // lie (p - 1) / 2 rings out and their supports (p + 1) / 2 further.
  const int reach = m.degree;
  // Face distances from the star points and irregular crease-boundary vertices (charts keep away from both), and
  // from the latter alone.
  const auto distances = [&](const std::vector<int>& from) {
    std::vector<int> dist(static_cast<std::size_t>(nf), INT_MAX), front;
    for (int s : from)
      for (int f : vertex_faces[static_cast<std::size_t>(s)])
        if (dist[static_cast<std::size_t>(f)] != 0) {
          dist[static_cast<std::size_t>(f)] = 0;
          front.push_back(f);
        }
    rings(front, depth + 5, dist);  // far enough to size the clusters below
    return dist;
  };
  std::vector<int> singular = stars_;
  for (int v : irregular)
    if (std::find(stars_.begin(), stars_.end(), v) == stars_.end()) singular.push_back(v);
  const std::vector<int> star_dist = distances(singular), crease_dist = distances(irregular);
  // Star points with unequal knot intervals on their three rings of faces: non-uniform Catmull-Clark on the
  // faces of the cells (0, 0), (1, 0), (1, 1), (0, 1) of every sector (the faces whose 4 x 4 points hold the star
  // point). With equal intervals the uniform evaluation below applies (the same surface, Stam's exact method).
  struct NurccFace {
    int star = -1, sector = 0, cell = 0, link = -1;
  };
  static constexpr int kSharedCell = -2;  // NurccFace::star of a face in the cells of two star points
  std::vector<NurccFace> nurcc_of(static_cast<std::size_t>(nf));
  std::vector<std::string> nurcc_why(static_cast<std::size_t>(nv));  // a star point whose sectors could not be gathered
  for (int v : stars_) {
    if (m.degree != 3 || is_irregular[static_cast<std::size_t>(v)]) continue;
    Sectors sec = gather_sectors(m, v);
    if (!sec.error.empty()) {
      nurcc_why[static_cast<std::size_t>(v)] = sec.error;
      continue;
    }
    const double d0 = sec.intervals[0][0];
    bool equal = true;
    for (const auto& r : sec.intervals)
      for (double d : r) equal = equal && std::abs(d - d0) <= 1e-12 * d0;
    if (equal) continue;
    for (const auto& r : sec.intervals)
      for (double d : r)
        require(d > 0, [&] {
          return "T-mesh: knot interval " + std::to_string(d) + " within three rings of star point " + std::to_string(v) +
                 ": repeated knots near a star point are not evaluated";
        });
    // A vertex without one point of its own (repeated-knot nodes: a side of a sharp crease in its Bezier form, or
    // a boundary vertex) leaves the star point to the rules below (local subdivision in a creased mesh).
    const auto own_point = [&](int x) {
      const TMeshVertex& mv = m.vertices[static_cast<std::size_t>(x)];
      return mv.primary >= 0 && mv.block.empty();
    };
    if (const auto x = std::find_if_not(sec.points.begin(), sec.points.end(), own_point); x != sec.points.end()) {
      nurcc_why[static_cast<std::size_t>(v)] = "vertex " + std::to_string(*x) + " has no control point or repeated-knot nodes";
      continue;
    }
    auto z = std::make_unique<Nurcc>(Nurcc{NonUniformStar(static_cast<int>(sec.intervals.size()), sec.intervals), {}});
    for (int x : sec.points) {
      const TMeshVertex& mv = m.vertices[static_cast<std::size_t>(x)];
      const RationalPoint& pt = m.points[static_cast<std::size_t>(mv.primary)];
      z->points.push_back({pt.w * pt.xyz[0], pt.w * pt.xyz[1], pt.w * pt.xyz[2], pt.w});
    }
    for (std::size_t k = 0; k < sec.cells.size(); ++k)
      for (int c = 0; c < 4; ++c) {
        const auto [face, link] = sec.cells[k][static_cast<std::size_t>(c)];
        // A face in the cells of two star points (each on the other's third ring) is neither's alone: local
        // subdivision takes it below (its two face rings lie within the two stars' regular rings).
        NurccFace& nf_ = nurcc_of[static_cast<std::size_t>(face)];
        nf_ = nf_.star == -1 ? NurccFace{static_cast<int>(nurcc_.size()), static_cast<int>(k), c, link} : NurccFace{kSharedCell};
      }
    nurcc_.push_back(std::move(z));
  }
  std::vector<int> exact;
  struct NearExact {
    int face;
    std::string why;  // why it is not a Catmull-Clark face
  };
  std::vector<NearExact> near_exact;
  std::vector<char> is_star(cm.vertices.size(), 0);
  for (int s : stars_) is_star[static_cast<std::size_t>(s)] = 1;
  // The Catmull-Clark region's conditions on a face's neighbourhood (near a star point, or round a closed strip
  // too short for charts). A face's uniform bicubic patch is the T-spline there when the (p + 1) / 2 rings around
  // it are uniform quadrilaterals inside the mesh: its 16 nodes are the corners of the first ring and their rays
  // cross (p + 1) / 2 lines. Empty when they hold; `unequal` names unequal knot intervals there.
  const int cc_depth = (m.degree + 1) / 2;
  // " at vertex V": the first T-junction (a straight corner, flag 1) of face g.
  const auto t_junction_at = [&](int g) -> std::string {
    for (int l : m.faces[static_cast<std::size_t>(g)])
      if (L(l).flag == 1) return " at vertex " + std::to_string(L(l).vertex);
    return {};
  };
  const auto regular = [&](int f, std::string& unequal) -> std::string {
    if (m.degree != 3) return "the Catmull-Clark evaluation is for degree 3, not " + std::to_string(m.degree);
    std::vector<int> dist(static_cast<std::size_t>(nf), INT_MAX);
    dist[static_cast<std::size_t>(f)] = 0;
    const std::vector<int> hood = rings({f}, cc_depth, dist);
    const double d0 = m.intervals[static_cast<std::size_t>(L(m.faces[static_cast<std::size_t>(f)].front()).edge)];
    for (int g : hood)
      for (int l : m.faces[static_cast<std::size_t>(g)]) {
        if (m.faces[static_cast<std::size_t>(g)].size() != 4)
          return "face " + std::to_string(g) + " nearby has a T-junction" + t_junction_at(g) +
                 "; the Catmull-Clark evaluation around star points needs none within " + std::to_string(cc_depth) + " rings";
        if (boundary[static_cast<std::size_t>(L(l).vertex)] && !ghosted[static_cast<std::size_t>(L(l).vertex)]) {
          // A side of a sharp crease: named by the file's vertex.
          const int v = L(l).vertex, from = m.vertices[static_cast<std::size_t>(v)].split_from;
          return "boundary vertex " + (from >= 0 ? std::to_string(from) + " (a side of its sharp crease)" : std::to_string(v)) + " is within " +
                 std::to_string(cc_depth) + " rings; the Catmull-Clark evaluation around star points needs none";
        }
        const double d = m.intervals[static_cast<std::size_t>(L(l).edge)];
        if (std::abs(d - d0) > 1e-12 * d0 && unequal.empty())
          unequal = "edge " + std::to_string(L(l).edge) + " nearby has knot interval " + std::to_string(d) + ", not " + std::to_string(d0);
        if (ghosted[static_cast<std::size_t>(L(l).vertex)] && std::abs(ghost_interval - d0) > 1e-12 * d0 && unequal.empty())
          unequal = "the ghost layer at boundary vertex " + std::to_string(L(l).vertex) + " nearby has knot interval " + std::to_string(ghost_interval) +
                    ", not " + std::to_string(d0);
      }
    return {};
  };
  // The bicubic or star patch of a face whose neighbourhood is regular, its star point (if any) at `corner`.
  const auto set_patch = [&](int f, int corner, int star_corners, const std::string& unequal, const std::string& where, Gather gth) {
    Face& face = faces_[static_cast<std::size_t>(f)];
    const auto& loop = m.faces[static_cast<std::size_t>(f)];
    require(gth.error.empty(), [&] { return where + gth.error; });
    if (!unequal.empty()) {
      // Unequal intervals: a face whose 16 points avoid the star points is the bicubic B-spline on its knots;
      // one whose points hold a star point needs its star's non-uniform Catmull-Clark sectors.
      for (int x : gth.points)
        require(!is_star[static_cast<std::size_t>(x)], [&] {
          const std::string& sw = nurcc_why[static_cast<std::size_t>(x)];
          return where + unequal + "; non-uniform Catmull-Clark at star point " + std::to_string(x) + " needs its three rings of faces: " +
                 (sw.empty() ? std::string("degree 3") : sw);
        });
      face.knots = cell_knots(cm, loop[static_cast<std::size_t>(corner)], static_cast<int>(m.vertices.size()));
      require(face.knots.has_value(), [&] { return where + unequal + "; its knot lines are not straight through vertices of four faces"; });
    }
    for (int x : gth.points) {
      const TMeshVertex& mv = cm.vertices[static_cast<std::size_t>(x)];
      require(mv.primary >= 0 && mv.block.empty(), [&] {
        return where + "vertex " + std::to_string(x) + " has no control point or repeated-knot nodes; the Catmull-Clark evaluation around star points needs one point per vertex";
      });
      const RationalPoint& pt = cm.points[static_cast<std::size_t>(mv.primary)];
      face.wx.push_back({pt.w * pt.xyz[0], pt.w * pt.xyz[1], pt.w * pt.xyz[2]});
      face.w.push_back({pt.w, 0, 0});
      face.rational = face.rational || pt.w != 1.0;
    }
    face.method = star_corners ? FaceMethod::star : FaceMethod::bicubic;
    face.boundary_star = star_corners && boundary[static_cast<std::size_t>(L(loop[static_cast<std::size_t>(corner)]).vertex)];
    face.corner = corner;
    face.points = std::move(gth.points);
  };
  // A T-junction within `reach` rings of a star point's faces leaves the faces round it without a rule (neither
  // the T-spline's, whose blending functions there would reach the star point, nor Catmull-Clark's, Stam's or the
  // non-uniform one, which are for quadrilateral meshes without T-junctions): the mesh is refused, naming it and
  // the nearest star point, before any other reason of the faces around it.
  for (int f = 0; f < nf; ++f) {
    if (!m.live_face(f) || m.faces[static_cast<std::size_t>(f)].size() == 4 || star_dist[static_cast<std::size_t>(f)] > reach) continue;
    int star = -1;
    for (int k = 0; star < 0; ++k) {
      std::vector<int> dist(static_cast<std::size_t>(nf), INT_MAX);
      dist[static_cast<std::size_t>(f)] = 0;
      for (int g : rings({f}, k, dist))
        for (int l : m.faces[static_cast<std::size_t>(g)])
          if (star < 0 && is_star[static_cast<std::size_t>(L(l).vertex)]) star = L(l).vertex;
    }
    const int d = star_dist[static_cast<std::size_t>(f)];
    throw Error("T-mesh: face " + std::to_string(f) + " has a T-junction" + t_junction_at(f) + " within " + std::to_string(d) +
                (d == 1 ? " face ring" : " face rings") + " of star point " + std::to_string(star) +
                "'s faces; no evaluation rule covers T-junctions within " + std::to_string(reach) +
                " rings of a star point (the T-spline's blending functions there reach the star point, the Catmull-Clark rules take "
                "quadrilaterals without T-junctions)");
  }
  // Local subdivision of the face's two face rings (crease_face): with the crease rules of the mesh cut open along
  // its creases, or in a mesh without creases on the mesh with the ghost layers of its boundary near star points
  // (the smooth rule at every vertex of the mesh; the layer's outer boundary takes the crease rules, its natural
  // end, for which the ghost rows are placed; its nets are kept off the rest of the boundary,
  // boundary_within_two_rings).
  std::vector<std::vector<int>> cc_vertex_faces;
  const auto local_subdivision = [&](int f, const std::string& why) {
    const TMesh& topology = split ? m : cm;
    if (rules.empty()) {
      rules = boundary_rules(split ? *split : cm);
      cc_vertex_faces = faces_at_vertices(topology);
    }
    std::vector<int> dist(topology.faces.size(), INT_MAX);
    dist[static_cast<std::size_t>(f)] = 0;
    const std::string where = "T-mesh: face " + std::to_string(f) + " (" + why + ", evaluated by local subdivision): ";
    crease_faces_.emplace_back(crease_net(topology, split ? *split : cm, rules, f, face_rings(topology, cc_vertex_faces, {f}, 2, dist), where));
    Face& face = faces_[static_cast<std::size_t>(f)];
    face.method = FaceMethod::crease;
    face.crease = static_cast<int>(crease_faces_.size()) - 1;
    face.rational = crease_faces_.back().rational();
  };
  // The first boundary vertex of face f's two face rings outside the ghost layers (-1: none). Without a crease
  // boundary the smooth rule has no rule for it (a Bezier boundary is no subdivision rule).
  const auto boundary_within_two_rings = [&](int f) {
    std::vector<int> dist(static_cast<std::size_t>(nf), INT_MAX);
    dist[static_cast<std::size_t>(f)] = 0;
    for (int g : rings({f}, 2, dist))
      for (int l : m.faces[static_cast<std::size_t>(g)])
        if (const int v = L(l).vertex; boundary[static_cast<std::size_t>(v)] && !ghosted[static_cast<std::size_t>(v)]) return v;
    return -1;
  };
  for (int f = 0; f < nf; ++f) {
    if (!m.live_face(f)) continue;
    Face& face = faces_[static_cast<std::size_t>(f)];
    if (crease_dist[static_cast<std::size_t>(f)] <= depth) {
      local_subdivision(f, "within " + std::to_string(depth + 1) + " face rings of an irregular vertex of a crease boundary");
      continue;
    }
    if (star_dist[static_cast<std::size_t>(f)] > depth && steps_ > 0) {
      // A mesh refined by global steps is closed and has no T-junction: away from star points the T-spline of
      // a face is the bicubic B-spline cell of its 16 points on its knots, without a chart.
      std::string unequal;
      const std::string why = regular(f, unequal);
      require(why.empty(), [&] { return "T-mesh: face " + std::to_string(f) + " after the global steps: " + why; });
      set_patch(f, 0, 0, unequal, "T-mesh: face " + std::to_string(f) + " after the global steps: ",
                gather(cm, m.faces[static_cast<std::size_t>(f)][0]));
      continue;
    }
    if (star_dist[static_cast<std::size_t>(f)] > depth) {
      face.method = FaceMethod::exact;
      exact.push_back(f);
      continue;
    }
    if (m.degree > 3) {
      // Odd degrees above 3: the averaging subdivision of that degree (averaging_face), the uniform B-spline of the
      // mesh = the T-spline wherever the neighbourhood is a regular grid of equal intervals. It reads the face's
      // m + 1 face rings: quadrilaterals inside the mesh, one interval, one point per vertex.
      const std::string where = "T-mesh: face " + std::to_string(f) + " (within " + std::to_string(depth + 1) +
                                " face rings of a star point, degree " + std::to_string(m.degree) + "): ";
      std::vector<int> dist(static_cast<std::size_t>(nf), INT_MAX);
      dist[static_cast<std::size_t>(f)] = 0;
      const std::vector<int> hood = rings({f}, (m.degree - 1) / 2 + 1, dist);
      const double d0 = m.intervals[static_cast<std::size_t>(L(m.faces[static_cast<std::size_t>(f)].front()).edge)];
      std::string why;
      for (int g : hood)
        for (int l : m.faces[static_cast<std::size_t>(g)])
          if (!why.empty()) {
            break;
          } else if (m.faces[static_cast<std::size_t>(g)].size() != 4) {
            why = "face " + std::to_string(g) + " nearby has a T-junction" + t_junction_at(g);
          } else if (boundary[static_cast<std::size_t>(L(l).vertex)]) {
            why = "boundary vertex " + std::to_string(L(l).vertex) + " is nearby";
          } else if (const double d = m.intervals[static_cast<std::size_t>(L(l).edge)]; std::abs(d - d0) > 1e-12 * d0) {
            why = "edge " + std::to_string(L(l).edge) + " nearby has knot interval " + std::to_string(d) + ", not " + std::to_string(d0);
          }
      if (!why.empty()) {
        why += "; the averaging subdivision at star points takes " + std::to_string((m.degree - 1) / 2 + 1) +
               " face rings of quadrilaterals inside the mesh with equal knot intervals";
        require(star_dist[static_cast<std::size_t>(f)] > reach, [&] { return where + why; });
        face.method = FaceMethod::exact;
        near_exact.push_back({f, where + why});
        continue;
      }
      if (smooth.empty()) smooth.assign(static_cast<std::size_t>(nv), CreaseRule::none);
      CreaseNet net = crease_net(m, m, smooth, f, hood, where);
      averaging_faces_.emplace_back(QuadNet{std::move(net.points), std::move(net.quads), {}}, m.degree);
      face.method = FaceMethod::averaging;
      face.averaging = static_cast<int>(averaging_faces_.size()) - 1;
      face.rational = averaging_faces_.back().rational();
      continue;
    }
    if (const NurccFace& z = nurcc_of[static_cast<std::size_t>(f)]; z.star >= 0) {
      static constexpr std::array<std::array<int, 2>, 4> cells{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
      face.method = FaceMethod::non_uniform;
      face.nurcc = z.star;
      face.sector = z.sector;
      face.cell = cells[static_cast<std::size_t>(z.cell)];
      const auto c = corners(f);
      face.corner = static_cast<int>(std::find(c.begin(), c.end(), L(z.link).vertex) - c.begin());
      for (const auto& p : nurcc_[static_cast<std::size_t>(z.star)]->points) face.rational = face.rational || p[3] != 1.0;
      continue;
    }
    std::string unequal;  // unequal knot intervals within cc_depth rings: exact as a non-uniform bicubic face
    const std::string why = regular(f, unequal);
    const auto where = [&] { return "T-mesh: face " + std::to_string(f) + " (within " + std::to_string(depth + 1) + " face rings of a star point): "; };
    const auto& loop = m.faces[static_cast<std::size_t>(f)];
    int corner = 0, star_corners = 0;
    for (int c = 0; c < static_cast<int>(loop.size()) && c < 4; ++c)
      if (is_star[static_cast<std::size_t>(L(loop[static_cast<std::size_t>(c)]).vertex)]) {
        corner = c;
        ++star_corners;
      }
    if (!why.empty() && split && star_dist[static_cast<std::size_t>(f)] <= reach) {
      // A star point near a crease boundary: local subdivision handles both.
      local_subdivision(f, "near a star point and a crease boundary: " + why);
      continue;
    }
    if (!unequal.empty() && why.empty() && star_dist[static_cast<std::size_t>(f)] <= 1 && (split || boundary_within_two_rings(f) < 0)) {
      // Unequal intervals round a star point whose three rings are no regular grid for NonUniformStar (another star
      // point or a crease boundary there; its own faces are taken above), or at a face with several star corners
      // or next to star points joined by an edge (no Stam patch): the face's 4 x 4 points hold the star point, and
      // local subdivision's rules there are NonUniformStar's on two face rings (the global steps' too). At a star
      // point on or near a Bezier boundary the same on the mesh with the boundary's ghost layer.
      local_subdivision(f, "near a star point with unequal knot intervals: " + unequal);
      for (int l : loop)
        face.boundary_star = face.boundary_star || (is_star[static_cast<std::size_t>(L(l).vertex)] && boundary[static_cast<std::size_t>(L(l).vertex)]);
      continue;
    }
    if (!why.empty()) {
      // A face beyond the reach of its blending functions' supports from the star points' faces may still be
      // the T-spline of a chart that holds no star point (a boundary, a T-junction or unequal intervals nearby):
      // tried below, else this reason.
      require(star_dist[static_cast<std::size_t>(f)] > reach, [&] { return where() + why; });
      face.method = FaceMethod::exact;
      near_exact.push_back({f, where() + why});
      continue;
    }
    Gather gth = star_corners <= 1 ? gather(cm, loop[static_cast<std::size_t>(corner)]) : Gather{};
    if (star_corners > 1 || !gth.error.empty()) {
      // Several star corners, or star points joined by an edge: one local Catmull-Clark step (subdivided_face).
      const std::string what = star_corners > 1 ? "it has " + std::to_string(star_corners) + " star corners" : gth.error;
      require(unequal.empty(), [&] {
        return where() + what + " and " + unequal + "; with unequal intervals such faces take local non-uniform subdivision, which needs their two face rings inside the mesh (boundary vertex " +
               std::to_string(boundary_within_two_rings(f)) + " is within them)";
      });
      try {
        subdivided_.emplace_back(cm, f);
      } catch (const Error& e) {
        throw Error(where() + what + "; its local Catmull-Clark step: " + e.what());
      }
      face.method = FaceMethod::subdivided;
      face.subdivided = static_cast<int>(subdivided_.size()) - 1;
      face.rational = subdivided_.back().rational();
      continue;
    }
    set_patch(f, corner, star_corners, unequal, where(), std::move(gth));
  }
  // Exact faces: the T-spline in a chart of their neighbourhood. Near star points or irregular crease vertices, first
  // in charts as large as the faces allow (embedded_faces: grown from an exact face over every face not at one of those
  // vertices, as long as the layout neither closes round one of them nor overlaps or touches itself), each serving the
  // exact faces whose depth face rings it holds (their neighbourhoods lie inside, as in the charts below); the faces
  // left over (a blending function on them cut by the chart's border, a face that is not one element of the chart, or a
  // chart that does not lay out) are grouped as follows. A chart of depth + k rings around a face serves every face
  // within k rings of it, so faces are grouped greedily: a cluster around the first face not yet served, k as large as
  // the star points allow (up to 4; without star points all it reaches). A mesh without star points but with a closed
  // strip (a torus, a tube) has no chart of all its faces, and a chart must not wrap round the strip: clusters of one
  // ring in charts of reach + 1 rings, split into single faces in charts of reach rings where those wrap (degree 3:
  // strips of 8 faces and more), and on shorter strips the bicubic B-spline cells of regular neighbourhoods.
  const bool periodic = singular.empty() && has_closed_strip(m);
  std::vector<char> served(static_cast<std::size_t>(nf), 0);
  const auto take = [&](int f, const ExactChart::Frame& fr, int chart) {
    Face& face = faces_[static_cast<std::size_t>(f)];
    face.origin = fr.origin;
    face.axis_u = fr.axis_u;
    face.axis_v = fr.axis_v;
    face.chart = chart;
  };
  // Regions: charts grown from a face over the faces not at a star point (embedded_faces). Pending: 1 an exact face,
  // 2 a face near a star point that the Catmull-Clark rules do not take (a T-junction nearby), whose blending
  // functions reach `reach` rings.
  std::vector<char> allowed(static_cast<std::size_t>(nf), 0), pending(static_cast<std::size_t>(nf), 0);
  for (int f = 0; f < nf; ++f) allowed[static_cast<std::size_t>(f)] = m.live_face(f) && star_dist[static_cast<std::size_t>(f)] > 0;
  struct Region {
    int seed;
    std::vector<int> faces, members;
  };
  // The region grown from face f, its members the pending faces without a face outside it within depth rings
  // (reach for the faces near star points), which are pending no more.
  const auto region = [&](int f) {
    Region g{f, embedded_faces(m, f, allowed), {}};
    std::vector<int> dist(static_cast<std::size_t>(nf), INT_MAX), outside;
    for (int h : g.faces) dist[static_cast<std::size_t>(h)] = INT_MAX - 1;
    for (int h = 0; h < nf; ++h)
      if (m.live_face(h) && dist[static_cast<std::size_t>(h)] == INT_MAX) {
        dist[static_cast<std::size_t>(h)] = 0;
        outside.push_back(h);
      }
    rings(outside, depth, dist);
    for (int h : g.faces)
      if (pending[static_cast<std::size_t>(h)] && dist[static_cast<std::size_t>(h)] > (pending[static_cast<std::size_t>(h)] == 2 ? reach : depth)) {
        pending[static_cast<std::size_t>(h)] = 0;
        g.members.push_back(h);
      }
    return g;
  };
  // Its chart, for the members whose knot vectors it holds (with `whole`, only those that are one of its elements:
  // the knot lines of faces far away cross a large chart, which splits a face's patches without changing it).
  const auto serve_region = [&](const Region& g, bool whole) {
    ExactChart c;
    try {
      c = exact_chart(m, g.faces, g.seed, g.members, threads);
    } catch (const Error&) {
      return;  // the clusters below take its members (and name the reason if theirs fail too)
    }
    bool used = false;
    for (std::size_t j = 0; j < g.members.size(); ++j) {
      if (c.cut[j] || (whole && !c.whole[j])) continue;
      take(g.members[j], c.frames[j], static_cast<int>(charts_.size()));
      served[static_cast<std::size_t>(g.members[j])] = 1;
      used = true;
    }
    if (used) charts_.push_back(std::move(c.surface));
  };
  if (!singular.empty()) {
    for (int f : exact) pending[static_cast<std::size_t>(f)] = 1;
    std::vector<Region> regions;
    for (int f : exact) {
      if (!pending[static_cast<std::size_t>(f)]) continue;
      Region g = region(f);
      pending[static_cast<std::size_t>(f)] = 0;  // a seed its chart does not serve goes to the clusters below
      if (!g.members.empty()) regions.push_back(std::move(g));
    }
    for (const Region& g : regions) serve_region(g, true);
  }
  const std::size_t region_charts = charts_.size();
  struct Cluster {
    int centre, rings;
    std::vector<int> members;
    std::string why;  // a face near a star point: why it is not a Catmull-Clark face
  };
  std::vector<Cluster> clusters;
  // Faces near star points alone, from `reach` rings up to the ring before the star points' faces.
  for (NearExact& n : near_exact) clusters.push_back({n.face, reach, {n.face}, std::move(n.why)});
  for (int f : exact) {
    if (served[static_cast<std::size_t>(f)]) continue;
    // Without star points the chart of all the faces it reaches (the global T-spline: small charts of a
    // model whose end-condition blocks or slits end inside them can have blending functions the chart's border
    // collapses).
    const int k = periodic ? 1 : singular.empty() ? nf : std::min(4, star_dist[static_cast<std::size_t>(f)] == INT_MAX ? 4 : star_dist[static_cast<std::size_t>(f)] - depth - 1);
    std::vector<int> dist(static_cast<std::size_t>(nf), INT_MAX);
    dist[static_cast<std::size_t>(f)] = 0;
    Cluster c{f, (periodic ? reach : depth) + k, {}, {}};
    for (int g : rings({f}, k, dist))
      if (faces_[static_cast<std::size_t>(g)].method == FaceMethod::exact && !served[static_cast<std::size_t>(g)]) {
        served[static_cast<std::size_t>(g)] = 1;
        c.members.push_back(g);
      }
    clusters.push_back(std::move(c));
  }
  std::vector<std::string> errors;
  // A chart is exact for its members when no blending function that is nonzero on a member has a knot vector
  // cut by the chart's border inside the mesh. Otherwise the chart grows by a ring, as long as it holds no star
  // point.
  const auto serve = [&](std::size_t first) {
    charts_.resize(region_charts + clusters.size());
    errors.resize(clusters.size());
    parallel_for(static_cast<std::ptrdiff_t>(clusters.size() - first), threads, [&](std::ptrdiff_t n) {
      const std::ptrdiff_t i = static_cast<std::ptrdiff_t>(first) + n;
      const Cluster& cl = clusters[static_cast<std::size_t>(i)];
      const int centre_dist = star_dist[static_cast<std::size_t>(cl.centre)];
      try {
        for (int r = cl.rings;; ++r) {
          require(r < centre_dist && r <= cl.rings + 8, [&] {
            return "the T-spline's knot vectors on face " + std::to_string(cl.centre) + " reach beyond " + std::to_string(r - 1) +
                   " face rings" + (r >= centre_dist ? " (to a star point)" : "");
          });
          std::vector<int> dist(static_cast<std::size_t>(nf), INT_MAX);
          dist[static_cast<std::size_t>(cl.centre)] = 0;
          ExactChart c = exact_chart(m, rings({cl.centre}, r, dist), cl.centre, cl.members, 1);
          if (std::find(c.cut.begin(), c.cut.end(), 1) != c.cut.end()) continue;
          for (std::size_t j = 0; j < cl.members.size(); ++j) take(cl.members[j], c.frames[j], static_cast<int>(region_charts) + static_cast<int>(i));
          charts_[region_charts + static_cast<std::size_t>(i)] = std::move(c.surface);
          break;
        }
      } catch (const Error& e) {
        errors[static_cast<std::size_t>(i)] =
            cl.why.empty() ? "T-mesh: face " + std::to_string(cl.centre) + ": its chart: " + e.what() +
                                 (periodic ? " (the mesh has a closed strip of faces, too short for a chart of the face's knot vectors)" : "")
                           : cl.why + " (nor is it the T-spline of a chart without star points: " + e.what() + ")";
      }
    });
  };
  serve(0);
  // A face near a star point whose chart of whole rings cuts its knot vectors before it reaches the star point (a
  // T-junction nearby lengthens them): a region grown from it, which holds its rings on every side it can, split into
  // several elements if need be.
  for (std::size_t i = 0; i < clusters.size(); ++i)
    if (!errors[i].empty() && !clusters[i].why.empty()) pending[static_cast<std::size_t>(clusters[i].centre)] = 2;
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    const int f = clusters[i].centre;
    if (errors[i].empty() || clusters[i].why.empty()) continue;
    if (!served[static_cast<std::size_t>(f)]) {
      pending[static_cast<std::size_t>(f)] = 2;
      const Region g = region(f);
      if (!g.members.empty()) serve_region(g, false);
    }
    if (served[static_cast<std::size_t>(f)]) errors[i].clear();
  }
  if (periodic) {
    const std::size_t first = clusters.size();
    for (std::size_t i = 0; i < first; ++i)
      if (!errors[i].empty() && clusters[i].rings > reach) {
        errors[i].clear();
        const std::vector<int> members = clusters[i].members;  // the clusters grow below
        for (int g : members) clusters.push_back({g, reach, {g}, {}});
      }
    if (clusters.size() > first) serve(first);
    // Where a strip is too short even for those, a face whose neighbourhood is regular is the bicubic B-spline
    // cell of its 16 points on its knots, the T-spline there (no chart needed).
    for (std::size_t i = first; i < clusters.size(); ++i) {
      if (errors[i].empty()) continue;
      const int f = clusters[i].centre;
      std::string unequal;
      const std::string why = regular(f, unequal);
      if (!why.empty()) {
        errors[i] += " (nor is it a regular bicubic patch: " + why + ")";
        continue;
      }
      set_patch(f, 0, 0, unequal, "T-mesh: face " + std::to_string(f) + " (round a short closed strip): ",
                gather(cm, m.faces[static_cast<std::size_t>(f)][0]));
      errors[i].clear();
    }
  }
  for (const std::string& e : errors) require(e.empty(), e);
}

int TMeshSurface::count(FaceMethod m) const {
  return static_cast<int>(std::count_if(faces_.begin(), faces_.end(), [m](const Face& f) { return f.method == m; }));
}

int TMeshSurface::boundary_star_faces() const {
  return static_cast<int>(std::count_if(faces_.begin(), faces_.end(), [](const Face& f) { return f.boundary_star; }));
}

int TMeshSurface::valence(int star) const {
  int n = 0;
  for (const TMeshLink& k : mesh_.links) n += k.vertex == star && k.face >= 0;
  return n;
}

std::array<int, 4> TMeshSurface::corners(int face) const {
  std::array<int, 4> c{};
  int i = 0;
  for (int l : mesh_.faces[static_cast<std::size_t>(face)])
    if (mesh_.links[static_cast<std::size_t>(l)].flag == 0 && i < 4) c[static_cast<std::size_t>(i++)] = mesh_.links[static_cast<std::size_t>(l)].vertex;
  // Start at the first corner link's vertex.
  const int first = mesh_.links[static_cast<std::size_t>(mesh_.first_corner(face))].vertex;
  std::rotate(c.begin(), std::find(c.begin(), c.end(), first), c.end());
  return c;
}

TMeshSurface::FacePoint TMeshSurface::refined_point(int source_face, double u, double v) const {
  require(source_face >= 0 && static_cast<std::size_t>(source_face) < source_mesh().faces.size(),
          [&] { return "T-mesh: no face " + std::to_string(source_face); });
  require(u >= 0 && u <= 1 && v >= 0 && v <= 1, [&] { return "T-mesh: (u, v) = (" + std::to_string(u) + ", " + std::to_string(v) + ") outside [0, 1]^2"; });
  FacePoint p{source_face, u, v, {1, 1}};
  if (lines_) {
    // The piece holding (u, v); on a side between two, the one above it.
    const auto& pieces = pieces_of_[static_cast<std::size_t>(source_face)];
    require(!pieces.empty(), [&] { return "T-mesh: face " + std::to_string(source_face) + " is deleted"; });
    const auto holds = [&](const FacePiece& q, bool strict) {
      for (std::size_t a = 0; a < 2; ++a) {
        const double x = a == 0 ? u : v, hi = q.lo[a] + q.size[a];
        if (x < q.lo[a] - 1e-14 || x > hi + 1e-14 || (strict && x >= hi - 1e-14 && hi < 1 - 1e-14)) return false;
      }
      return true;
    };
    int at = pieces.front();
    for (bool strict : {false, true})
      for (int q : pieces)
        if (holds(lines_->pieces[static_cast<std::size_t>(q)], strict)) at = q;
    const FacePiece& q = lines_->pieces[static_cast<std::size_t>(at)];
    p.face = at;
    p.u = std::clamp((u - q.lo[0]) / q.size[0], 0.0, 1.0);
    p.v = std::clamp((v - q.lo[1]) / q.size[1], 0.0, 1.0);
    p.scale = {1 / q.size[0], 1 / q.size[1]};
  }
  // nurcc_step's numbering: quarter 0, 1, 2, 3 at (u, v) in [0, 1/2]^2, [1/2, 1] x [0, 1/2], [1/2, 1]^2, [0, 1/2] x
  // [1/2, 1].
  for (int k = 0; k < steps_; ++k) {
    const int i = p.u >= 0.5 ? 1 : 0, j = p.v >= 0.5 ? 1 : 0;
    p.face = 4 * p.face + (j == 0 ? i : 3 - i);
    p.u = 2 * p.u - i;
    p.v = 2 * p.v - j;
    p.scale[0] *= 2;
    p.scale[1] *= 2;
  }
  return p;
}

void TMeshSurface::eval_source(int source_face, double u, double v, double* out) const {
  const FacePoint p = refined_point(source_face, u, v);
  eval(p.face, p.u, p.v, out);
  for (int k = 3; k < 9; ++k) out[k] *= p.scale[k < 6 ? 0 : 1];
}

void TMeshSurface::eval(int face, double u, double v, double* out) const {
  require(face >= 0 && face < num_faces() && faces_[static_cast<std::size_t>(face)].method != FaceMethod::none,
          [&] { return "T-mesh: no face " + std::to_string(face); });
  require(u >= 0 && u <= 1 && v >= 0 && v <= 1, [&] { return "T-mesh: (u, v) = (" + std::to_string(u) + ", " + std::to_string(v) + ") outside [0, 1]^2"; });
  const Face& f = faces_[static_cast<std::size_t>(face)];
  if (f.method == FaceMethod::exact) {
    const TSplineSurface& s = *charts_[static_cast<std::size_t>(f.chart)];
    const auto at = [&](double x, double y) {
      return Param<2>{f.origin[0] + x * f.axis_u[0] + y * f.axis_v[0], f.origin[1] + x * f.axis_u[1] + y * f.axis_v[1]};
    };
    // The element of this face that holds the point (cells are half-open; the face's sides belong to it here).
    const int e = s.locate(at(std::clamp(u, 1e-9, 1 - 1e-9), std::clamp(v, 1e-9, 1 - 1e-9)));
    double q[9];
    s.eval_first_derivatives_on_element(e, at(u, v), q);
    for (int c = 0; c < 3; ++c) {
      out[c] = q[c];
      out[3 + c] = f.axis_u[0] * q[3 + c] + f.axis_u[1] * q[6 + c];
      out[6 + c] = f.axis_v[0] * q[3 + c] + f.axis_v[1] * q[6 + c];
    }
    return;
  }
  // The patch's frame: (u', v') from the corner along the next and the previous corner.
  const CornerFrame fr = corner_frame(f.corner);
  const auto& o = fr.origin;
  const auto& a = fr.a;
  const auto& b = fr.b;
  const double up = a[0] * (u - o[0]) + a[1] * (v - o[1]), vp = b[0] * (u - o[0]) + b[1] * (v - o[1]);
  double h[12], q[9];
  eval_patch_homogeneous(face, std::clamp(up, 0.0, 1.0), std::clamp(vp, 0.0, 1.0), h);
  // The quotient rule: x = X / W, x' = (X' - x W') / W.
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) {
      const double x = h[c] / h[3];
      q[3 * k + c] = k == 0 ? x : (h[4 * k + c] - x * h[4 * k + 3]) / h[3];
    }
  for (int c = 0; c < 3; ++c) {
    out[c] = q[c];
    out[3 + c] = a[0] * q[3 + c] + b[0] * q[6 + c];
    out[6 + c] = a[1] * q[3 + c] + b[1] * q[6 + c];
  }
}

void TMeshSurface::eval_patch_homogeneous(int face, double up, double vp, double* out) const {
  const Face& f = faces_[static_cast<std::size_t>(face)];
  require(f.method == FaceMethod::bicubic || f.method == FaceMethod::star || f.method == FaceMethod::non_uniform ||
              f.method == FaceMethod::subdivided || f.method == FaceMethod::crease || f.method == FaceMethod::averaging,
          [&] { return "T-mesh: face " + std::to_string(face) + " is not a subdivision face"; });
  if (f.method == FaceMethod::averaging) {
    averaging_faces_[static_cast<std::size_t>(f.averaging)].eval(up, vp, out);
    return;
  }
  if (f.method == FaceMethod::subdivided) {
    subdivided_[static_cast<std::size_t>(f.subdivided)].eval(up, vp, out);
    return;
  }
  if (f.method == FaceMethod::crease) {
    crease_faces_[static_cast<std::size_t>(f.crease)].eval(up, vp, out);
    return;
  }
  if (f.method == FaceMethod::non_uniform) {
    const Nurcc& z = *nurcc_[static_cast<std::size_t>(f.nurcc)];
    z.star.eval(z.points, f.sector, f.cell[0] + up, f.cell[1] + vp, out, f.cell);
    return;
  }
  // The rules are linear: once on w x, once on the weights (all 1: W = 1, W' = 0).
  const auto run = [&](const std::vector<std::array<double, 3>>& p, double* q) {
    if (f.method == FaceMethod::bicubic && f.knots)
      eval_bicubic_cell(regular_grid(p), (*f.knots)[0], (*f.knots)[1], up, vp, q);
    else if (f.method == FaceMethod::bicubic)
      eval_uniform_bicubic(regular_grid(p), up, vp, q);
    else
      catmull_clark_patch(static_cast<int>((p.size() - 8) / 2)).eval(p, up, vp, q);
  };
  double x[9], w[9] = {1, 0, 0, 0, 0, 0, 0, 0, 0};
  run(f.wx, x);
  if (f.rational) run(f.w, w);
  for (int k = 0; k < 3; ++k) {
    for (int c = 0; c < 3; ++c) out[4 * k + c] = x[3 * k + c];
    out[4 * k + 3] = w[3 * k];
  }
}

const CreaseFace& TMeshSurface::crease_face(int face) const {
  const Face& f = faces_[static_cast<std::size_t>(face)];
  require(f.method == FaceMethod::crease, [&] { return "T-mesh: face " + std::to_string(face) + " is not a crease face"; });
  return crease_faces_[static_cast<std::size_t>(f.crease)];
}

const AveragingFace& TMeshSurface::averaging_face(int face) const {
  const Face& f = faces_[static_cast<std::size_t>(face)];
  require(f.method == FaceMethod::averaging, [&] { return "T-mesh: face " + std::to_string(face) + " is not an averaging face"; });
  return averaging_faces_[static_cast<std::size_t>(f.averaging)];
}

const SubdividedFace& TMeshSurface::subdivided(int face) const {
  const Face& f = faces_[static_cast<std::size_t>(face)];
  require(f.method == FaceMethod::subdivided, [&] { return "T-mesh: face " + std::to_string(face) + " is not a subdivided face"; });
  return subdivided_[static_cast<std::size_t>(f.subdivided)];
}

TMeshSurface::ChartFrame TMeshSurface::chart_frame(int face) const {
  const Face& f = faces_[static_cast<std::size_t>(face)];
  require(f.method == FaceMethod::exact, [&] { return "T-mesh: face " + std::to_string(face) + " is not an exact face"; });
  return {charts_[static_cast<std::size_t>(f.chart)].get(), f.origin, f.axis_u, f.axis_v};
}

std::vector<std::array<double, 3>> TMeshSurface::patch_points(int face) const {
  const Face& f = faces_[static_cast<std::size_t>(face)];
  if (f.method == FaceMethod::non_uniform) {
    std::vector<std::array<double, 3>> p;
    for (const auto& x : nurcc_[static_cast<std::size_t>(f.nurcc)]->points) p.push_back({x[0] / x[3], x[1] / x[3], x[2] / x[3]});
    return p;
  }
  require(f.method == FaceMethod::bicubic || f.method == FaceMethod::star,
          [&] { return "T-mesh: face " + std::to_string(face) + " is not a Catmull-Clark face of one patch"; });
  const TMesh& cm = cc_mesh();
  std::vector<std::array<double, 3>> p(f.points.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    p[i] = cm.points[static_cast<std::size_t>(cm.vertices[static_cast<std::size_t>(f.points[i])].primary)].xyz;
  return p;
}

}  // namespace trivar
