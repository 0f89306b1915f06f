#include "trivar/tspline/t_junction_lines.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <functional>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "trivar/core/error.hpp"
#include "trivar/tspline/boundary_ghosts.hpp"
#include "trivar/tspline/homogeneous_point.hpp"
#include "trivar/tspline/link_builder.hpp"
#include "trivar/tspline/non_uniform_catmull_clark.hpp"
#include "trivar/tspline/sharp_creases.hpp"

namespace trivar {

namespace {

using H = HomogeneousPoint;

// A side of a face: its vertices from the side's corner on (the next side's corner excluded) and the interval
// from each to the next.
struct Side {
  std::vector<int> v;
  std::vector<double> d;
  double length() const {
    double s = 0;
    for (double x : d) s += x;
    return s;
  }
};

struct Face {
  std::array<Side, 4> side;  // counter-clockwise from the first corner: side 0 along u, side 1 along v
  FacePiece piece;
};

// Where a directed edge a -> b lies: the face that has it counter-clockwise, its side and position there.
struct Loc {
  int face = -1, side = 0, index = 0;
};

long long key(int a, int b) { return static_cast<long long>(a) * (1LL << 32) + b; }

// A row the line crosses ends at the stem of another T-junction (vertex `at`, the row coming from `from`): that
// T-junction's line continues the row, so it is completed first. Thrown before the crossing changes anything; the
// line so far ends at the T-junction `front`, from where it goes on.
struct StemFirst {
  int at, from, front = -1;
  std::string message() const {
    return "the row through vertex " + std::to_string(from) + " ends at vertex " + std::to_string(at) + " (the stem of a T-junction)";
  }
};

// The completed mesh while it is built: faces as four sides, the points of the vertices.
class Lines {
public:
  Lines(const TMesh& m, const std::vector<int>& stars, const std::vector<int>& irregular)
      : m_(m), star_(m.vertices.size(), 0), natural_(m.end_conditions == EndConditions::subd_creases) {
    for (int s : stars) star_[static_cast<std::size_t>(s)] = 1;
    for (int s : irregular) star_[static_cast<std::size_t>(s)] = 2;
    if (natural_) {
      rules_ = boundary_rules(m);
      // The corners of one face of a crease boundary: its natural end there takes the corner face's four points.
      const VertexAngles angles = vertex_angles(m);
      for (std::size_t v = 0; v < m.vertices.size(); ++v)
        if (angles.boundary[v] && angles.degrees[v] == 90) corner_.push_back(static_cast<int>(v));
    }
    rules_.resize(m.vertices.size(), CreaseRule::none);
    const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
    for (int f = 0; f < static_cast<int>(m.faces.size()); ++f) {
      const auto& loop = m.faces[static_cast<std::size_t>(f)];
      if (loop.empty()) continue;  // a deleted face: the completed mesh has none
      Face face;
      face.piece.source = f;
      const std::size_t start = static_cast<std::size_t>(std::find(loop.begin(), loop.end(), m.first_corner(f)) - loop.begin());
      int k = -1;
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const TMeshLink& l = L(loop[(start + i) % loop.size()]);
        if (l.flag == 0) ++k;
        require(k < 4 && (l.flag == 0 || l.flag == 1), [&] { return "T-mesh: face " + std::to_string(f) + " is not a rectangle of knot intervals"; });
        const double d = m.intervals[static_cast<std::size_t>(l.edge)];
        face.side[static_cast<std::size_t>(k)].v.push_back(l.vertex);
        face.side[static_cast<std::size_t>(k)].d.push_back(d);
      }
      require(k == 3, [&] { return "T-mesh: face " + std::to_string(f) + " has " + std::to_string(k + 1) + " corners, not 4"; });
      faces.push_back(std::move(face));
    }
    for (int v = 0; v < static_cast<int>(m.vertices.size()); ++v) {
      const int from = m.vertices[static_cast<std::size_t>(v)].split_from;
      origin_.push_back(from >= 0 ? from : v);
    }
    for (const TMeshVertex& v : m.vertices) {
      H h{0, 0, 0, 1};
      if (v.live && v.primary >= 0) {
        h = homogeneous(m.points[static_cast<std::size_t>(v.primary)]);
      }
      p.push_back(h);
      // Its end-condition block points (NaN: an entry without one).
      std::vector<H> b;
      for (int g : v.block) b.push_back(g >= 0 ? homogeneous(m.points[static_cast<std::size_t>(g)]) : H{NAN, NAN, NAN, NAN});
      blocks_ = blocks_ || (!natural_ && !b.empty());
      blk_.push_back(std::move(b));
    }
    for (std::size_t v = 0; v < m.vertices.size(); ++v) cut_ = cut_ || origin_[v] != static_cast<int>(v);
    for (const TMeshLink& k : m.links)
      if (blocks_ && k.vertex >= 0 && k.frame >= 0) frame_[key(k.vertex, m.links[static_cast<std::size_t>(k.opp)].vertex)] = k.frame;
    for (int f = 0; f < static_cast<int>(faces.size()); ++f) index(f);
    // A sharp edge between two darts is cut without copies: its two sides join the same two vertices.
    for (const TMeshLink& k : m.links)
      if (k.vertex >= 0 && k.face >= 0 && L(k.opp).face < 0 && at_map_.count(key(L(k.opp).vertex, k.vertex))) slit_.insert(key(k.vertex, L(k.opp).vertex));
    if (!slit_.empty()) {
      cut_ = true;
      for (int f = 0; f < static_cast<int>(faces.size()); ++f) index(f);  // by_origin_ too
    }
  }

  std::vector<Face> faces;
  std::vector<H> p;
  int inserted = 0;
  std::unordered_map<long long, int> split_at;     // edge (smaller, larger end) -> the vertex inserted on it
  std::unordered_map<long long, long long> along;  // directed edge a -> x from a split -> the edge a -> b it lies along

  // Completes the line of the T-junction at position `index` (inside the side) of side `k` of face `f`.
  void complete(int f, int k, int index, const std::string& where) {
    for (std::size_t guard = 0; guard <= 4 * faces.size() + 4; ++guard) {
      const int e = (k + 2) % 4;
      int j = 0;
      double at = 0, target = 0;
      bool meets = false;
      {
        const Face& w = faces[static_cast<std::size_t>(f)];
        const Side& in = w.side[static_cast<std::size_t>(k)];
        const Side& out = w.side[static_cast<std::size_t>(e)];
        for (const Side& s : w.side)
          for (double d : s.d)
            require(d > 0 && std::isfinite(d), [&] {
              return where + "a face of face " + std::to_string(w.piece.source) + " it crosses has knot interval " + std::to_string(d) + " (positive needed)";
            });
        double o = 0;
        for (int i = 0; i < index; ++i) o += in.d[static_cast<std::size_t>(i)];
        const double len = in.length();
        target = out.length() - o;
        require(std::abs(len - out.length()) <= 1e-9 * len, [&] {
          return where + "a face of face " + std::to_string(w.piece.source) + " has sides of knot intervals " + std::to_string(len) +
                 " and " + std::to_string(out.length()) + " opposite each other";
        });
        // The last vertex of the opposite side at or before the line.
        while (j + 1 < static_cast<int>(out.v.size()) && at + out.d[static_cast<std::size_t>(j)] <= target + 1e-12 * len)
          at += out.d[static_cast<std::size_t>(j++)];
        meets = j > 0 && std::abs(at - target) <= 1e-12 * len;
      }
      if (meets) {
        split_face(f, k, index, j);
        return;
      }
      // The line crosses edge a -> b of the opposite side: a new vertex there, on the row of that edge, which is a
      // T-junction of the face beyond; the line goes on through that face.
      const int a = faces[static_cast<std::size_t>(f)].side[static_cast<std::size_t>(e)].v[static_cast<std::size_t>(j)];
      const int b = vertex_after(f, e, j);
      const double d = faces[static_cast<std::size_t>(f)].side[static_cast<std::size_t>(e)].d[static_cast<std::size_t>(j)];
      const H a_before = p[static_cast<std::size_t>(a)], b_before = p[static_cast<std::size_t>(b)];
      int x = -1;
      try {
        x = split_edge(a, b, target - at, where);
      } catch (StemFirst& stem) {
        stem.front = faces[static_cast<std::size_t>(f)].side[static_cast<std::size_t>(k)].v[static_cast<std::size_t>(index)];
        throw;
      }
      split_face(f, k, index, j + 1);
      Loc c = at_(key(x, a));
      if (c.face < 0) {
        // The boundary: the line ends there, unless it is a side of a sharp crease. Then it goes on from the same
        // place of the other side's edge, whose row (the crease's copies, the same points and intervals) gets the
        // same insertion: both sides keep one crease curve and one set of vertices on it.
        const auto it = by_origin_.find(key(origin_[static_cast<std::size_t>(b)], origin_[static_cast<std::size_t>(a)]));
        if (it == by_origin_.end()) return;
        const int b2 = faces[static_cast<std::size_t>(it->second.face)].side[static_cast<std::size_t>(it->second.side)].v[static_cast<std::size_t>(it->second.index)];
        const int a2 = vertex_after(it->second.face, it->second.side, it->second.index);
        require(across(b2, a2).face < 0 && (a2 != a || b2 != b || slit_.count(key(a, b))), [&] { return where + "the two sides of the crease at vertex " + std::to_string(origin_[static_cast<std::size_t>(a)]) + " do not match"; });
        // The dart that ends a slit is one vertex of both sides: the second side's insertion, the same row, starts
        // from its point before the first.
        if (a2 == a) p[static_cast<std::size_t>(a)] = a_before;
        if (b2 == b) p[static_cast<std::size_t>(b)] = b_before;
        int x2 = -1;
        try {
          x2 = split_edge(b2, a2, d - (target - at), where, x);
        } catch (const StemFirst& stem) {  // the crease's first side is split already: no going back
          throw Error(where + stem.message());
        }
        c = at_(key(x2, a2));
      }
      f = c.face;
      k = c.side;
      index = c.index;
    }
    throw Error(where + "its line does not end within " + std::to_string(faces.size()) + " faces");
  }

  // Where vertex v is a T-junction (inside a side of a face): (face, side, index), or face -1.
  std::array<int, 3> t_junction_of(int v) const {
    for (int f = 0; f < static_cast<int>(faces.size()); ++f)
      for (int k = 0; k < 4; ++k) {
        const Side& s = faces[static_cast<std::size_t>(f)].side[static_cast<std::size_t>(k)];
        for (std::size_t i = 1; i < s.v.size(); ++i)
          if (s.v[i] == v) return {f, k, static_cast<int>(i)};
      }
    return {-1, 0, 0};
  }
  // The first T-junction (a vertex inside a side) of a face within `rings` face rings of a star point's faces, or
  // rings + 1 of an irregular crease vertex's (whose faces within p + 1 rings take local subdivision of their two
  // face rings), or of the face at a corner of a crease boundary (whose natural end needs it quadrilateral,
  // crease_ends): (face, side, index), or face -1.
  std::array<int, 3> t_junction_near_stars(int rings) const {
    const int nf = static_cast<int>(faces.size());
    std::vector<std::vector<int>> vertex_faces(p.size());
    for (int f = 0; f < nf; ++f)
      for (const Side& s : faces[static_cast<std::size_t>(f)].side)
        for (int v : s.v) vertex_faces[static_cast<std::size_t>(v)].push_back(f);
    // Seeded in ring order: the irregular crease vertices' faces at -1, then the star points' at 0.
    std::vector<int> dist(static_cast<std::size_t>(nf), INT_MAX), front, stars;
    for (int f = 0; f < nf; ++f)
      for (const Side& s : faces[static_cast<std::size_t>(f)].side)
        for (int v : s.v)
          if (static_cast<std::size_t>(v) < star_.size() && star_[static_cast<std::size_t>(v)])
            dist[static_cast<std::size_t>(f)] = std::min(dist[static_cast<std::size_t>(f)], star_[static_cast<std::size_t>(v)] == 2 ? -1 : 0);
    for (int f = 0; f < nf; ++f)
      if (dist[static_cast<std::size_t>(f)] < 0)
        front.push_back(f);
      else if (dist[static_cast<std::size_t>(f)] == 0)
        stars.push_back(f);
    front.insert(front.end(), stars.begin(), stars.end());
    for (int v : corner_)
      for (int f : vertex_faces[static_cast<std::size_t>(v)])
        if (dist[static_cast<std::size_t>(f)] == INT_MAX) {
          dist[static_cast<std::size_t>(f)] = rings;
          front.push_back(f);
        }
    for (std::size_t i = 0; i < front.size(); ++i) {
      const int f = front[i];
      const Face& w = faces[static_cast<std::size_t>(f)];
      for (std::size_t k = 0; k < 4; ++k)
        if (w.side[k].v.size() > 1) return {f, static_cast<int>(k), 1};
      if (dist[static_cast<std::size_t>(f)] == rings) continue;
      for (const Side& s : w.side)
        for (int v : s.v)
          for (int g : vertex_faces[static_cast<std::size_t>(v)])
            if (dist[static_cast<std::size_t>(g)] == INT_MAX) {
              dist[static_cast<std::size_t>(g)] = dist[static_cast<std::size_t>(f)] + 1;
              front.push_back(g);
            }
    }
    return {-1, 0, 0};
  }

  TMesh mesh() const;
  // Whether the mesh was cut along sharp creases.
  bool cut() const { return cut_; }
  // The completed mesh (mesh()) with the two sides of its sharp creases joined again, their vertices one (by
  // origin_): the same faces, for a tessellation that welds across the creases.
  TMesh welded(const TMesh& completed) const {
    TMesh r;
    r.degree = completed.degree;
    r.end_conditions = completed.end_conditions;
    r.vertices = completed.vertices;
    r.points = completed.points;
    for (std::size_t v = 0; v < r.vertices.size(); ++v) r.vertices[v].live = origin_[v] == static_cast<int>(v) && r.vertices[v].live;
    link_faces(r, true);
    return r;
  }

private:
  const TMesh& m_;
  std::vector<char> star_;  // 1: a star point, 2: an irregular vertex of a crease boundary
  std::vector<CreaseRule> rules_;  // a subdivision crease's rules at its boundary vertices (boundary_rules)
  bool natural_;            // rows end in the natural end of a subdivision crease, not in Bezier end conditions
  bool blocks_ = false;     // Bezier end conditions with their block points given (else they lie on the vertices)
  // Per vertex, its end-condition block points as TMeshVertex::block (a vertex inserted on the boundary: its one,
  // outwards), moved by the insertions along the boundary rows; the frames of the links as given (with blocks).
  std::vector<std::vector<H>> blk_;
  std::unordered_map<long long, int> frame_;
  std::unordered_map<long long, Loc> at_map_;
  // Per vertex, the vertex of the mesh before the cut along sharp creases (split_from; an inserted vertex's copy on
  // the other side: the first of the two); the directed edges by those ends.
  std::vector<int> origin_;
  bool cut_ = false;
  std::unordered_map<long long, Loc> by_origin_;  // kept only in a mesh cut open
  std::unordered_set<long long> slit_;            // the sides of sharp edges between two darts, both directions
  std::vector<int> corner_;                       // a crease boundary's corners of one face

  // The face across directed edge a -> b (the one holding b -> a), none across a slit between two darts.
  Loc across(int a, int b) const { return slit_.count(key(a, b)) ? Loc{} : at_(key(b, a)); }

  // The links of the faces (with `weld`, of their vertices' origins), and of the boundary.
  void link_faces(TMesh& r, bool weld) const {
    LinkBuilder links(r);
    if (!weld)
      for (long long k : slit_) links.keep_apart(static_cast<int>(k >> 32), static_cast<int>(k & 0xffffffffLL));
    for (const Face& w : faces) {
      std::vector<int> loop;
      std::vector<double> iv;
      std::vector<char> straight;
      for (const Side& s : w.side)
        for (std::size_t i = 0; i < s.v.size(); ++i) {
          loop.push_back(weld ? origin_[static_cast<std::size_t>(s.v[i])] : s.v[i]);
          iv.push_back(s.d[i]);
          straight.push_back(i == 0 ? 0 : 1);
        }
      links.add_face(loop, straight, iv);
    }
    links.close_boundary();
  }
  Loc at_(long long k) const {
    const auto it = at_map_.find(k);
    return it == at_map_.end() ? Loc{} : it->second;
  }
  // The directed edges of face f (after a change to it: only the faces changed are indexed again).
  void index(int f) {
    for (int k = 0; k < 4; ++k) {
      const Side& s = faces[static_cast<std::size_t>(f)].side[static_cast<std::size_t>(k)];
      for (int i = 0; i < static_cast<int>(s.v.size()); ++i) {
        const int a = s.v[static_cast<std::size_t>(i)], b = vertex_after(f, k, i);
        at_map_[key(a, b)] = {f, k, i};
        if (cut_) by_origin_[key(origin_[static_cast<std::size_t>(a)], origin_[static_cast<std::size_t>(b)])] = {f, k, i};
      }
    }
  }
  int vertex_after(int f, int k, int i) const {
    const Face& w = faces[static_cast<std::size_t>(f)];
    const Side& s = w.side[static_cast<std::size_t>(k)];
    return i + 1 < static_cast<int>(s.v.size()) ? s.v[static_cast<std::size_t>(i + 1)] : w.side[static_cast<std::size_t>((k + 1) % 4)].v[0];
  }
  // The place after place (k, i) of face f's loop.
  std::pair<int, int> after(int f, int k, int i) const {
    return i + 1 < static_cast<int>(faces[static_cast<std::size_t>(f)].side[static_cast<std::size_t>(k)].v.size()) ? std::pair{k, i + 1} : std::pair{(k + 1) % 4, 0};
  }
  int vertex_before(int f, int k, int i) const {
    const Face& w = faces[static_cast<std::size_t>(f)];
    return i > 0 ? w.side[static_cast<std::size_t>(k)].v[static_cast<std::size_t>(i - 1)] : w.side[static_cast<std::size_t>((k + 3) % 4)].v.back();
  }
  struct Spoke {
    int to;
    double d;
    int face, side, index;  // the face left of it (-1: none, the boundary's outside) and the spoke's place there
    int angle;              // that face's angle at the vertex in quarter turns (0: no face)
  };
  // The spokes of vertex a counter-clockwise: round a closed fan from a -> b; round an open one (a boundary vertex)
  // from the boundary edge with the outside clockwise of it to the other, which has no face left of it.
  struct Fan {
    std::vector<Spoke> spokes;
    bool open = false;
    int turn = 0;  // quarter turns of its faces
  };
  Fan fan(int a, int b, const std::string& where) const {
    Fan f;
    // Clockwise to the boundary, if any: the face right of spoke a -> x holds x -> a, and a -> y follows it there.
    int first = b;
    for (std::size_t guard = 0; !f.open && guard < 64; ++guard) {
      const Loc r = at_(key(first, a));
      if (r.face < 0) {
        f.open = true;
        break;
      }
      const auto [k, i] = after(r.face, r.side, r.index);
      first = vertex_after(r.face, k, i);
      if (first == b) break;
    }
    int to = f.open ? first : b;
    for (std::size_t guard = 0; guard < 64; ++guard) {
      const Loc c = at_(key(a, to));
      if (c.face < 0) {  // the open fan's last spoke: its interval from the face right of it
        const Loc r = at_(key(to, a));
        f.spokes.push_back({to, faces[static_cast<std::size_t>(r.face)].side[static_cast<std::size_t>(r.side)].d[static_cast<std::size_t>(r.index)], -1, 0, 0, 0});
        // A dart's fan runs from one side of its slit to the other: closed as before the cut, its two slit spokes
        // (copies of one crease vertex, one point, or of one inserted vertex once both sides have it) one spoke,
        // named by b when b is either.
        if (static_cast<std::size_t>(a) < rules_.size() && rules_[static_cast<std::size_t>(a)] == CreaseRule::dart) {
          f.spokes.pop_back();
          if (to == b) f.spokes.front().to = b;
          f.open = false;
          // From b, as a closed fan is.
          std::rotate(f.spokes.begin(), std::find_if(f.spokes.begin(), f.spokes.end(), [&](const Spoke& k) { return k.to == b; }), f.spokes.end());
        }
        return f;
      }
      const Side& s = faces[static_cast<std::size_t>(c.face)].side[static_cast<std::size_t>(c.side)];
      const int angle = c.index == 0 ? 1 : 2;
      f.spokes.push_back({to, s.d[static_cast<std::size_t>(c.index)], c.face, c.side, c.index, angle});
      f.turn += angle;
      to = vertex_before(c.face, c.side, c.index);
      if (!f.open && to == b) return f;
    }
    throw Error(where + "vertex " + std::to_string(a) + " has no fan of faces");
  }
  // Where the row arriving at the fan's vertex along spoke `from` goes on: the spoke two quarter turns round (-1:
  // none), and the face whose angle holds that direction when no spoke does (-1: none either).
  struct Straight {
    int spoke = -1, face = -1, side = 0;
  };
  static Straight straight(const Fan& f, int from) {
    std::vector<int> theta{0};
    for (const Spoke& s : f.spokes) theta.push_back(theta.back() + s.angle);
    int at = 0;
    while (f.spokes[static_cast<std::size_t>(at)].to != from) ++at;
    Straight out;
    for (int target : {theta[static_cast<std::size_t>(at)] + 2, theta[static_cast<std::size_t>(at)] - 2}) {
      if (!f.open) target = ((target % 4) + 4) % 4;
      for (std::size_t k = 0; k < f.spokes.size(); ++k) {
        if (theta[k] == target) out.spoke = static_cast<int>(k);
        if (f.spokes[k].face >= 0 && theta[k] < target && target < theta[k] + f.spokes[k].angle) out.face = f.spokes[k].face, out.side = f.spokes[k].side;
      }
      if (out.spoke >= 0 || out.face >= 0 || !f.open) return out;
    }
    return out;
  }
  // The node beyond a on the row from b: the vertex on (-1 past a star point: `point`), its interval, and whether
  // the row ends at a (a boundary vertex: its end-condition node lies on it, at a's knot).
  struct Beyond {
    int vertex;
    double d;
    bool end;
    H point{};        // past a star point: the node across_star takes, and the interval after it
    double past = 0;
  };
  Beyond beyond(int a, int b, const std::string& where) const {
    if (const auto t = crease_turn(a, b, where)) return {t->to, t->d, false};
    if (crease_end(a, b, where)) return {a, 0, true};
    const Fan f = fan(a, b, where);
    require_closed(a, f, where);
    if (passes_as_star(a, f)) return across_star(a, b, where);
    require(!f.open || f.turn <= 2, [&] { return where + "a row it crosses passes the concave corner " + std::to_string(a); });
    const Straight s = straight(f, b);
    if (s.spoke >= 0) return {f.spokes[static_cast<std::size_t>(s.spoke)].to, f.spokes[static_cast<std::size_t>(s.spoke)].d, false};
    if (f.open) return {a, 0, true};
    throw StemFirst{a, b};
  }
  // The spokes of star point a counter-clockwise from the one to b, closed: a star point on a Bezier boundary is
  // an interior one of the mesh with its ghost layer (boundary_ghosts), whose fan closes with the ghost spoke; its
  // node is the ghost row of the clamped end across the boundary at a (from a's end-condition node, a and the
  // mean of its interior spokes' ends, on their mean intervals), the ghost interval their mean first interval.
  struct ClosedSpoke {
    H point;
    double d;  // the spoke's interval
    int to;    // -1: the ghost spoke
  };
  std::vector<ClosedSpoke> closed_spokes(int a, int b, const std::string& where) const {
    const Fan f = fan(a, b, where);
    std::vector<ClosedSpoke> out;
    for (const Spoke& s : f.spokes) {
      if (s.to < static_cast<int>(m_.vertices.size())) require_point(s.to, where);
      out.push_back({p[static_cast<std::size_t>(s.to)], s.d, s.to});
    }
    if (f.open) {
      require(f.spokes.size() > 2, [&] { return where + "a row it crosses reaches the boundary star point " + std::to_string(a) + " without interior spokes"; });
      H inner{};
      double d1 = 0, d2 = 0;
      const double share = 1.0 / static_cast<double>(f.spokes.size() - 2);
      for (std::size_t k = 1; k + 1 < f.spokes.size(); ++k) {
        for (std::size_t i = 0; i < 4; ++i) inner[i] += share * out[k].point[i];
        d1 += share * out[k].d;
        const int e = out[k].to;  // at a star point there its own interval (no recursion round adjacent star points)
        d2 += share * (static_cast<std::size_t>(e) < star_.size() && star_[static_cast<std::size_t>(e)] ? out[k].d : interval_beyond(e, a, false, where).d);
      }
      const std::vector<H>& block = blk_[static_cast<std::size_t>(a)];
      const H q0 = block.size() == 1 && !std::isnan(block[0][3]) ? block[0] : p[static_cast<std::size_t>(a)];
      out.push_back({clamped_end_rows(q0, p[static_cast<std::size_t>(a)], inner, d1, d2 > 0 ? d2 : d1, d1).ghost, d1, -1});
      const auto from_b = std::find_if(out.begin(), out.end(), [&](const ClosedSpoke& s) { return s.to == b; });
      require(from_b != out.end(), [&] { return where + "vertex " + std::to_string(b) + " is no neighbour of the boundary star point " + std::to_string(a); });
      std::rotate(out.begin(), from_b, out.end());
    }
    return out;
  }
  // The node beyond star point a on the row from b (the header says why): the backward spokes' nodes, and the
  // intervals after them, in nurcc_across's weights (beyond the ghost spoke the ghost interval again). Only a's own
  // point in Boehm's rule depends on it.
  Beyond across_star(int a, int b, const std::string& where) const {
    const std::vector<ClosedSpoke> spokes = closed_spokes(a, b, where);
    const std::vector<double> w = nurcc_across_weights(static_cast<int>(spokes.size()), 0);  // spoke 0 comes from b
    Beyond r{-1, 0, false};
    for (std::size_t m = 0; m < w.size(); ++m) {
      if (w[m] == 0) continue;
      const ClosedSpoke& s = spokes[m];
      for (std::size_t i = 0; i < 4; ++i) r.point[i] += w[m] * s.point[i];
      r.d += w[m] * s.d;
      r.past += w[m] * (s.to < 0 ? s.d : interval_beyond(s.to, a, false, where).d);
    }
    return r;
  }
  // A row along a crease boundary through an irregular vertex whose rule is the crease rule (a crease turning there,
  // or running through a star point): the crease curve goes on along the vertex's other boundary edge, as on the
  // crease's other side. The spoke it goes on along, if so.
  std::optional<Spoke> crease_turn(int v, int from, const std::string& where) const {
    if (static_cast<std::size_t>(v) >= star_.size() || star_[static_cast<std::size_t>(v)] != 2 || rules_[static_cast<std::size_t>(v)] != CreaseRule::crease)
      return std::nullopt;
    const Fan f = fan(v, from, where);
    if (!f.open) return std::nullopt;
    const Spoke &first = f.spokes.front(), &last = f.spokes.back();
    if (first.to == from) return last;
    if (last.to == from) return first;
    return std::nullopt;
  }
  // Whether a row arriving at an irregular vertex of a crease boundary from `from` ends there, as rows end at a
  // regular one: one from inside the mesh (the interior spokes of a boundary star point or of a corner of several
  // faces), and any at a corner (where the crease curve ends too). Its end is the crease's natural end.
  bool crease_end(int v, int from, const std::string& where) const {
    if (static_cast<std::size_t>(v) >= star_.size() || star_[static_cast<std::size_t>(v)] != 2) return false;
    const CreaseRule r = rules_[static_cast<std::size_t>(v)];
    if (r != CreaseRule::crease && r != CreaseRule::corner) return false;
    const Fan f = fan(v, from, where);
    if (!f.open) return false;
    return r == CreaseRule::corner || (f.spokes.front().to != from && f.spokes.back().to != from);
  }
  // Other irregular vertices of a crease boundary: a dart (its fan closed across the slit) or a cone point (a corner
  // inside the mesh) passes rows as any vertex of its fan does (straight on where its faces' angles make four
  // quarter turns, else as a star point), as local subdivision takes the faces round it; where the fan stays open
  // (a crease vertex of other than two faces, a corner of several) no row goes on.
  bool passes_as_star(int v, const Fan& f) const {
    const int kind = static_cast<std::size_t>(v) < star_.size() ? star_[static_cast<std::size_t>(v)] : 0;
    return kind == 1 || (kind == 2 && f.turn != 4);
  }
  void require_closed(int v, const Fan& f, const std::string& where) const {
    require(static_cast<std::size_t>(v) >= star_.size() || star_[static_cast<std::size_t>(v)] != 2 || !f.open, [&] {
      const int from = m_.vertices[static_cast<std::size_t>(v)].split_from;
      return where + "a row it crosses reaches the irregular crease vertex " + std::to_string(from >= 0 ? from : v);
    });
  }
  // The knot interval beyond node c on the row from a: its straight spoke's, the extent of the face its row enters
  // (a T-junction's stem), at a star point nurcc_across, 0 where the row ends at c on the boundary (`ends`: the
  // end-condition node, at the same knot) or beyond such a node (`end`).
  struct Next {
    double d;
    bool ends;
  };
  Next interval_beyond(int c, int a, bool end, const std::string& where) const {
    if (end) return {0, false};
    if (const auto t = crease_turn(c, a, where)) return {t->d, false};
    if (crease_end(c, a, where)) return {0, true};
    const Fan f = fan(c, a, where);
    require_closed(c, f, where);
    if (passes_as_star(c, f)) {
      std::vector<double> iv;
      for (const ClosedSpoke& s : closed_spokes(c, a, where)) iv.push_back(s.d);
      return {nurcc_across(iv, 0), false};
    }
    require(!f.open || f.turn <= 2, [&] { return where + "a row it crosses passes the concave corner " + std::to_string(c); });
    const Straight s = straight(f, a);
    if (s.spoke >= 0) return {f.spokes[static_cast<std::size_t>(s.spoke)].d, false};
    if (f.open) return {0, true};
    require(s.face >= 0, [&] { return where + "vertex " + std::to_string(c) + " has no straight spoke"; });
    return {faces[static_cast<std::size_t>(s.face)].side[static_cast<std::size_t>((s.side + 1) % 4)].length(), false};
  }
  // The direction of edge v -> w in v's frame (v a vertex as given; w may be inserted on an edge as given).
  int frame(int v, int w) const {
    long long k = key(v, w);
    for (auto it = along.find(k); it != along.end(); it = along.find(k)) k = it->second;
    const auto f = frame_.find(k);
    return f == frame_.end() ? -1 : f->second;
  }
  // Block point (index into blk_[v]) of vertex v one layer towards frame direction `dir` and `side` layers towards
  // the next direction counter-clockwise (TMeshVertex::block's wedges); a vertex inserted on the boundary has one.
  H& block(int v, int dir, int side, const std::string& where) {
    if (static_cast<std::size_t>(v) >= m_.vertices.size() && !blk_[static_cast<std::size_t>(v)].empty()) return blk_[static_cast<std::size_t>(v)][0];
    const std::array<int, 4> dims = static_cast<std::size_t>(v) < m_.vertices.size() ? m_.vertices[static_cast<std::size_t>(v)].block_dims : std::array<int, 4>{};
    std::size_t at = 0;
    for (int j = 0; j < dir && dir >= 0; ++j) at += static_cast<std::size_t>(dims[static_cast<std::size_t>(j)] * (dims[static_cast<std::size_t>((j + 1) % 4)] + 1));
    const bool has = dir >= 0 && dims[static_cast<std::size_t>(dir)] >= 1 && dims[static_cast<std::size_t>((dir + 1) % 4)] >= side;
    require(has && at + static_cast<std::size_t>(side) < blk_[static_cast<std::size_t>(v)].size() &&
                !std::isnan(blk_[static_cast<std::size_t>(v)][at + static_cast<std::size_t>(side)][3]),
            [&] { return where + "boundary vertex " + std::to_string(v) + " has no end-condition node for a row it crosses"; });
    return blk_[static_cast<std::size_t>(v)][at + static_cast<std::size_t>(side)];
  }
  // Bezier end conditions: the end node Q0 of the row that ends at v coming from w (its block point beyond v; without
  // a grip map the vertex's own point, where bezier_equivalent places it).
  H end_block(int v, int w, const std::string& where) {
    if (!blocks_) return p[static_cast<std::size_t>(v)];
    return block(v, (frame(v, w) + 2) % 4, 0, where);
  }
  // The point a row ending at boundary vertex v takes for v's node (Q1) in Boehm's rule. Bezier end conditions: v's
  // own (the end node Q0 beyond it is end_block's). A subdivision crease: the row is the clamped cubic of
  // crease_ends, whose node at v is Q1 = a P0 + b P1 (natural_end_weights, P1 the next vertex inward at d1, d2 the
  // interval after it), while v keeps P0, its end node Q0; the clamped insertion keeps the zero second derivative
  // across the boundary, so the refined row is again that of its natural end.
  H end_node(int v, int inward, double d1, double d2) const {
    if (!natural_) return p[static_cast<std::size_t>(v)];
    const auto [wa, wb] = natural_end_weights(d1, d2);
    H r;
    for (std::size_t i = 0; i < 4; ++i) r[i] = wa * p[static_cast<std::size_t>(v)][i] + wb * p[static_cast<std::size_t>(inward)][i];
    return r;
  }
  void require_point(int v, const std::string& where) const {
    require(m_.vertices[static_cast<std::size_t>(v)].primary >= 0, [&] { return where + "vertex " + std::to_string(v) + " on a row it crosses has no control point"; });
  }

  // Inserts a vertex on edge a -> b at knot distance t from a; Boehm's rule on the row moves a and b. Returns it.
  // `twin`: the vertex it is a copy of on the other side of a sharp crease (-1: none).
  int split_edge(int a, int b, double t, const std::string& where, int twin = -1) {
    const Beyond bc = beyond(a, b, where), be = beyond(b, a, where);
    const int c = bc.vertex, e = be.vertex;
    const double dca = bc.d, dbe = be.d;
    const bool c_end = bc.end, e_end = be.end;
    require((c_end || dca > 0) && (e_end || dbe > 0), [&] {
      return where + "the row through vertices " + std::to_string(a) + " and " + std::to_string(b) + " has a zero knot interval";
    });
    require(c != b && e != a && (c != e || c < 0 || c_end || e_end), [&] {
      return where + "the row through vertices " + std::to_string(a) + " and " + std::to_string(b) + " closes within 3 edges";
    });
    for (int v : {c, a, b, e})
      if (v >= 0 && v < static_cast<int>(m_.vertices.size())) require_point(v, where);
    const Loc ab = at_(key(a, b)), ba = across(a, b);
    const double d = faces[static_cast<std::size_t>(ab.face)].side[static_cast<std::size_t>(ab.side)].d[static_cast<std::size_t>(ab.index)];
    const Next past_c = c < 0 ? Next{bc.past, false} : interval_beyond(c, a, c_end, where);
    const Next past_e = e < 0 ? Next{be.past, false} : interval_beyond(e, b, e_end, where);
    const double um1 = -dca, um2 = um1 - past_c.d, u1 = d, u2 = d + dbe, u3 = u2 + past_e.d;
    const double a1 = (t - um2) / (u1 - um2), a2 = (t - um1) / (u2 - um1), a3 = t / u3;
    const auto mix = [](const H& x, const H& y, double s) {  // (1 - s) x + s y
      H r;
      for (std::size_t i = 0; i < 4; ++i) r[i] = (1 - s) * x[i] + s * y[i];
      return r;
    };
    // The row's points in Boehm's rule; a row that ends at a or b (c_end, e_end: one interval between two
    // boundaries has d2 = d1, as in crease_ends) or at c or e takes the end node there, and the end vertex stays.
    // Bezier end conditions: a row ending at a or b has its block point there as its end node Q0, the vertex's
    // point (Q1) moves.
    const H pc = c < 0  ? bc.point
                 : c_end ? (natural_ ? p[static_cast<std::size_t>(a)] : end_block(a, b, where))
                         : past_c.ends ? end_node(c, a, dca, d) : p[static_cast<std::size_t>(c)];
    const H pa = c_end && natural_ ? end_node(a, b, d, e_end ? d : dbe) : p[static_cast<std::size_t>(a)];
    const H pb = e_end && natural_ ? end_node(b, a, d, c_end ? d : dca) : p[static_cast<std::size_t>(b)];
    const H pe = e < 0  ? be.point
                 : e_end ? (natural_ ? p[static_cast<std::size_t>(b)] : end_block(b, a, where))
                         : past_e.ends ? end_node(e, b, dbe, d) : p[static_cast<std::size_t>(e)];
    if (!c_end || !natural_) p[static_cast<std::size_t>(a)] = mix(pc, pa, a1);
    if (!e_end || !natural_) p[static_cast<std::size_t>(b)] = mix(pb, pe, a3);
    const int x = static_cast<int>(p.size());
    require(inserted < 16 * static_cast<int>(m_.faces.size()) + 1024, [&] {
      return where + "the lines insert more than " + std::to_string(inserted) + " vertices (16 per face of the mesh)";
    });
    // A row along a Bezier boundary: the row of its block points outside (the boundary curve's control points)
    // takes the same insertion; at a corner where the row ends, its end node is the corner's diagonal block point.
    std::vector<H> x_block;
    if (blocks_ && ba.face < 0) {
      // At a boundary star point the block row's node is its one block point, else its own point (as its ghost layer
      // takes them); past it (c or e virtual, from the closed fan) the row's virtual node keeps the star point's
      // offset from its block node. The star point's surface is its ghost layer's Catmull-Clark limit, which this
      // choice, like across_star's, moves; the T-spline away from it is the same either way.
      const auto star = [&](int v) { return v >= 0 && static_cast<std::size_t>(v) < star_.size() && star_[static_cast<std::size_t>(v)]; };
      const auto star_node = [&](int v, const H& point) {
        const std::vector<H>& nodes = blk_[static_cast<std::size_t>(v)];
        return nodes.size() == 1 && !std::isnan(nodes[0][3]) ? nodes[0] : point;
      };
      const auto shifted = [](const H& virtual_node, const H& node, const H& point) {
        H r;
        for (std::size_t i = 0; i < 4; ++i) r[i] = virtual_node[i] + node[i] - point[i];
        return r;
      };
      const int fa = frame(a, b), fb = frame(b, a);
      // The outside lies right of a -> b: clockwise of each vertex's direction along the row.
      const auto outside = [&](int v, int w, bool forward) { return v < static_cast<int>(m_.vertices.size()) ? (frame(v, w) + (forward ? 3 : 1)) % 4 : -1; };
      const auto corner = [&](int v, int beyond_dir, int out_dir) -> H& {
        // The diagonal node: in the wedge of whichever of the two directions the other follows counter-clockwise.
        return (out_dir == (beyond_dir + 1) % 4) ? block(v, beyond_dir, 1, where) : block(v, out_dir, 1, where);
      };
      const H qa = star(a) ? star_node(a, pa) : block(a, (fa + 3) % 4, 0, where);
      const H qb = star(b) ? star_node(b, pb) : block(b, (fb + 1) % 4, 0, where);
      const H qc = c < 0    ? shifted(pc, qa, pa)
                   : c_end  ? corner(a, (fa + 2) % 4, (fa + 3) % 4)
                   : star(c) ? star_node(c, p[static_cast<std::size_t>(c)])
                             : block(c, outside(c, a, true), 0, where);
      const H qe = e < 0    ? shifted(pe, qb, pb)
                   : e_end  ? corner(b, (fb + 2) % 4, (fb + 1) % 4)
                   : star(e) ? star_node(e, p[static_cast<std::size_t>(e)])
                             : block(e, outside(e, b, false), 0, where);
      x_block = {mix(qa, qb, a2)};
      // A star point without a block point keeps none: its new node is its new point.
      const auto store = [&](int v, int dir, const H& value) {
        if (!star(v))
          block(v, dir, 0, where) = value;
        else if (std::vector<H>& nodes = blk_[static_cast<std::size_t>(v)]; nodes.size() == 1 && !std::isnan(nodes[0][3]))
          nodes[0] = value;
      };
      store(a, (fa + 3) % 4, mix(qc, qa, a1));
      store(b, (fb + 1) % 4, mix(qb, qe, a3));
    }
    p.push_back(mix(pa, pb, a2));
    blk_.push_back(std::move(x_block));
    origin_.push_back(twin >= 0 ? twin : x);
    ++inserted;
    const auto put = [&](const Loc& l, double first) {
      Side& s = faces[static_cast<std::size_t>(l.face)].side[static_cast<std::size_t>(l.side)];
      const double whole = s.d[static_cast<std::size_t>(l.index)];
      s.v.insert(s.v.begin() + l.index + 1, x);
      s.d[static_cast<std::size_t>(l.index)] = first;
      s.d.insert(s.d.begin() + l.index + 1, whole - first);
    };
    put(ab, t);
    if (ba.face >= 0) put(ba, d - t);  // else a boundary edge
    at_map_.erase(key(a, b));
    if (ba.face >= 0) at_map_.erase(key(b, a));
    by_origin_.erase(key(origin_[static_cast<std::size_t>(a)], origin_[static_cast<std::size_t>(b)]));
    if (ba.face >= 0) by_origin_.erase(key(origin_[static_cast<std::size_t>(b)], origin_[static_cast<std::size_t>(a)]));
    index(ab.face);
    if (ba.face >= 0) index(ba.face);
    split_at[key(std::min(a, b), std::max(a, b))] = x;
    along[key(a, x)] = key(a, b);
    along[key(b, x)] = key(b, a);
    return x;
  }

  // Splits face f by an edge from vertex `i` of side k to vertex `j` of side k + 2 (both inside their sides).
  void split_face(int f, int k, int i, int j) {
    if (k >= 2) {
      std::swap(i, j);
      k -= 2;
    }
    Face w = std::move(faces[static_cast<std::size_t>(f)]);
    const auto head = [](const Side& s, int n) { return Side{{s.v.begin(), s.v.begin() + n}, {s.d.begin(), s.d.begin() + n}}; };
    const auto tail = [](const Side& s, int n) { return Side{{s.v.begin() + n, s.v.end()}, {s.d.begin() + n, s.d.end()}}; };
    Side& lo = w.side[static_cast<std::size_t>(k)];      // side 0 (a line along v) or side 1 (along u)
    Side& hi = w.side[static_cast<std::size_t>(k + 2)];
    const double span = w.side[static_cast<std::size_t>(k + 1)].length();
    double o = 0;
    for (int n = 0; n < i; ++n) o += lo.d[static_cast<std::size_t>(n)];
    const double frac = o / lo.length();
    const int x = lo.v[static_cast<std::size_t>(i)], y = hi.v[static_cast<std::size_t>(j)];
    Face a = w, b = w;  // a: before the line (smaller u or v), b: beyond it
    FacePiece& pa = a.piece;
    FacePiece& pb = b.piece;
    const std::size_t axis = static_cast<std::size_t>(k == 0 ? 0 : 1);
    pa.size[axis] = w.piece.size[axis] * frac;
    pb.lo[axis] = w.piece.lo[axis] + pa.size[axis];
    pb.size[axis] = w.piece.size[axis] - pa.size[axis];
    if (k == 0) {  // x on the bottom side, y on the top side
      a.side = {head(lo, i), Side{{x}, {span}}, tail(hi, j), w.side[3]};
      b.side = {tail(lo, i), w.side[1], head(hi, j), Side{{y}, {span}}};
    } else {  // x on the right side, y on the left side
      a.side = {w.side[0], head(lo, i), Side{{x}, {span}}, tail(hi, j)};
      b.side = {Side{{y}, {span}}, tail(lo, i), w.side[2], head(hi, j)};
    }
    faces[static_cast<std::size_t>(f)] = std::move(a);
    faces.push_back(std::move(b));
    index(f);
    index(static_cast<int>(faces.size()) - 1);
  }
};

TMesh Lines::mesh() const {
  TMesh r;
  r.degree = m_.degree;
  r.force_bezier = m_.force_bezier;
  r.end_conditions = m_.end_conditions;
  r.vertices = m_.vertices;
  r.points = m_.points;
  for (std::size_t v = 0; v < p.size(); ++v) {
    const RationalPoint x = rational(p[v]);
    if (v < m_.vertices.size()) {
      if (r.vertices[v].live && r.vertices[v].primary >= 0) r.points[static_cast<std::size_t>(r.vertices[v].primary)] = x;
      for (std::size_t k = 0; !natural_ && k < r.vertices[v].block.size(); ++k)
        if (const int g = r.vertices[v].block[k]; g >= 0) r.points[static_cast<std::size_t>(g)] = rational(blk_[v][k]);
      continue;
    }
    r.points.push_back(x);
    r.vertices.push_back({});
    r.vertices.back().primary = static_cast<int>(r.points.size()) - 1;
  }
  link_faces(r, false);
  const auto L = [&](int l) -> TMeshLink& { return r.links[static_cast<std::size_t>(l)]; };
  const auto to = [&](int l) { return L(L(l).opp).vertex; };
  // Frame directions: a link along a link of the mesh as given (or a piece of one) keeps its frame; the others
  // follow round their vertex, a quarter turn per right angle counter-clockwise (north after east).
  std::unordered_map<long long, int> given;
  for (const TMeshLink& k : m_.links)
    if (k.vertex >= 0 && k.frame >= 0) given[key(k.vertex, m_.links[static_cast<std::size_t>(k.opp)].vertex)] = k.frame;
  const auto known = [&](long long e) {
    for (auto it = along.find(e); it != along.end(); it = along.find(e)) e = it->second;
    const auto g = given.find(e);
    return g == given.end() ? -1 : g->second;
  };
  std::vector<int> spoke(r.vertices.size(), -1);
  for (int l = 0; l < static_cast<int>(r.links.size()); ++l)
    if (spoke[static_cast<std::size_t>(L(l).vertex)] < 0) spoke[static_cast<std::size_t>(L(l).vertex)] = l;
  for (int first : spoke) {
    if (first < 0) continue;
    std::vector<int> round{first};
    std::vector<int> theta{0};
    for (int l = L(L(first).prev).opp; l != first && round.size() <= 64; l = L(L(l).prev).opp) {
      theta.push_back(theta.back() + L(round.back()).flag + 1);
      round.push_back(l);
    }
    int base = 3, at = 0;
    for (std::size_t k = 0; k < round.size(); ++k)
      if (const int f = known(key(L(round[k]).vertex, to(round[k]))); f >= 0) {
        base = f;
        at = theta[k];
        break;
      }
    for (std::size_t k = 0; k < round.size(); ++k) L(round[k]).frame = (((base + theta[k] - at) % 4) + 4) % 4;
  }
  // A vertex inserted on the boundary gets the end-condition node of a straight boundary vertex, outwards, from the
  // insertion along the boundary's block row, when the mesh as given carries such nodes (else bezier_equivalent
  // places them).
  for (int l = 0; blocks_ && l < static_cast<int>(r.links.size()); ++l) {
    const std::size_t v = static_cast<std::size_t>(L(l).vertex);
    TMeshVertex& x = r.vertices[v];
    if (L(l).face >= 0 || v < m_.vertices.size() || !x.block.empty()) continue;
    x.block_dims[static_cast<std::size_t>((L(l).frame + 1) % 4)] = 1;
    r.points.push_back(rational(blk_[v].at(0)));
    x.block = {static_cast<int>(r.points.size()) - 1};
  }
  // Edge conditions and crease lists on the pieces of their edges.
  std::unordered_map<long long, int> edge_of;
  for (const TMeshLink& k : r.links) edge_of[key(std::min(k.vertex, L(k.opp).vertex), std::max(k.vertex, L(k.opp).vertex))] = k.edge;
  const std::function<void(int, int, std::vector<int>&)> pieces = [&](int a, int b, std::vector<int>& out) {
    const long long e = key(std::min(a, b), std::max(a, b));
    if (const auto it = split_at.find(e); it != split_at.end()) {
      pieces(a, it->second, out);
      pieces(it->second, b, out);
    } else {
      out.push_back(edge_of.at(e));
    }
  };
  std::vector<std::array<int, 2>> ends(m_.intervals.size(), {-1, -1});
  for (const TMeshLink& k : m_.links)
    if (k.vertex >= 0) ends[static_cast<std::size_t>(k.edge)] = {k.vertex, m_.links[static_cast<std::size_t>(k.opp)].vertex};
  const auto remap = [&](int e, const std::function<void(int)>& take) {
    std::vector<int> out;
    pieces(ends[static_cast<std::size_t>(e)][0], ends[static_cast<std::size_t>(e)][1], out);
    for (int x : out) take(x);
  };
  for (const auto& [e, flag] : m_.conditions) remap(e, [&, f = flag](int x) { r.conditions.push_back({x, f}); });
  for (int e : m_.crease_edges) remap(e, [&](int x) { r.crease_edges.push_back(x); });
  r.crease_vertices = m_.crease_vertices;
  return r;
}

}  // namespace

std::optional<CompletedLines> complete_t_junction_lines(const TMesh& m, int rings) {
  const std::vector<int> stars = star_points(m), irregular = irregular_crease_vertices(m);
  const bool t_faces = std::any_of(m.faces.begin(), m.faces.end(), [](const std::vector<int>& loop) { return loop.size() > 4; });
  if (!t_faces || (stars.empty() && irregular.empty() && m.end_conditions != EndConditions::subd_creases)) return std::nullopt;
  Lines lines(m, stars, irregular);
  std::array<int, 3> t = lines.t_junction_near_stars(rings);
  if (t[0] < 0) return std::nullopt;
  CompletedLines out;
  std::size_t guard = 0;
  for (; t[0] >= 0; t = lines.t_junction_near_stars(rings)) {
    // The T-junctions whose lines are under way: a line waits for those of the T-junctions whose stems end the rows
    // it crosses, and goes on from where it stopped.
    std::vector<int> pending{lines.faces[static_cast<std::size_t>(t[0])].side[static_cast<std::size_t>(t[1])].v[static_cast<std::size_t>(t[2])]};
    while (!pending.empty()) {
      const int v = pending.back();
      const std::string where = "T-mesh: the T-junction at vertex " + std::to_string(v) + " near a star point, an irregular crease vertex or a crease corner (completed into a knot line): ";
      require(m.degree == 3, [&] { return where + "degree " + std::to_string(m.degree) + ", not 3"; });
      require(++guard < 4 * m.faces.size() + 4, [&] { return where + "the lines do not end"; });
      const std::array<int, 3> at = lines.t_junction_of(v);
      if (at[0] < 0) {  // another line has completed it
        pending.pop_back();
        continue;
      }
      try {
        lines.complete(at[0], at[1], at[2], where);
        ++out.lines;
        pending.pop_back();
      } catch (const StemFirst& stem) {
        require(std::find(pending.begin(), pending.end(), stem.at) == pending.end(), [&] { return where + stem.message(); });
        pending.back() = stem.front;
        pending.push_back(stem.at);
      }
    }
  }
  out.vertices = lines.inserted;
  out.mesh = lines.mesh();
  if (lines.cut()) out.welded = lines.welded(out.mesh);
  for (const Face& w : lines.faces) out.pieces.push_back(w.piece);
  return out;
}

}  // namespace trivar
