#include "trivar/io/tsm_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/tspline/crease_ends.hpp"
#include "trivar/tspline/sharp_creases.hpp"

namespace trivar::io {

namespace {

struct Record {
  int line = 0;
  std::vector<std::string_view> words;  // after the kind; empty: deleted slot
};

struct RawLink {
  int prev, next, opp, vertex, face, edge, flag;
};

class TsmReader {
public:
  TsmReader(std::string_view text, std::string name) : name_(std::move(name)) { split(text); }

  TsmModel build();

private:
  std::string name_;
  std::map<std::string, std::vector<Record>, std::less<>> kinds_;
  std::vector<Record> grip_map_;  // the 0m records in order
  int header_line_ = 0;

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw Error(name_ + ":" + std::to_string(line) + ": " + what);
  }
  [[noreturn]] void fail(const std::string& what) const { throw Error(name_ + ": " + what); }

  void split(std::string_view text) {
    int line = 0;
    std::size_t pos = 0;
    while (pos <= text.size()) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      std::string_view s = text.substr(pos, end - pos);
      pos = end + 1;
      ++line;
      if (line == 1 || header_line_ == 0) {
        const std::size_t b = s.find_first_not_of(" \t\r");
        if (b == std::string_view::npos) continue;
        if (header_line_ == 0) {
          if (s.substr(b, 7) != "#TS0200") fail(line, "not a T-Splines TSM file (the first line must start with #TS0200)");
          header_line_ = line;
          continue;
        }
      }
      if (const std::size_t c = s.find('#'); c != std::string_view::npos) s = s.substr(0, c);
      std::vector<std::string_view> w;
      std::size_t i = 0;
      while (i < s.size()) {
        while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
        std::size_t j = i;
        while (j < s.size() && s[j] != ' ' && s[j] != '\t' && s[j] != '\r') ++j;
        if (j > i) w.push_back(s.substr(i, j - i));
        i = j;
      }
      if (w.empty()) continue;
      Record r{line, {w.begin() + 1, w.end()}};
      if (w[0] == "0m") grip_map_.push_back(r);
      kinds_[std::string(w[0])].push_back(std::move(r));
      if (pos > text.size()) break;
    }
    if (header_line_ == 0) fail(1, "empty file (no #TS0200 header)");
  }

  const std::vector<Record>& all(std::string_view kind) const {
    static const std::vector<Record> none;
    auto it = kinds_.find(kind);
    return it == kinds_.end() ? none : it->second;
  }

  template <class T>
  T number(const Record& r, std::size_t i, const char* what) const {
    if (i >= r.words.size()) fail(r.line, std::string("missing ") + what);
    const std::string_view w = r.words[i];
    T v{};
    auto [p, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc() || p != w.data() + w.size()) fail(r.line, std::string("bad ") + what + " '" + std::string(w) + "'");
    return v;
  }

  std::optional<Record> setting(std::string_view kind) const {
    const auto& v = all(kind);
    if (v.empty()) return std::nullopt;
    return v.front();
  }
};

int direction_of(std::string_view w) {
  if (w == "NORTH") return 0;
  if (w == "WEST") return 1;
  if (w == "SOUTH") return 2;
  if (w == "EAST") return 3;
  return -1;
}

TsmModel TsmReader::build() {
  TsmModel out;
  TsmReport& rep = out.report;
  static const std::vector<std::string> geometry{"degree", "cap-type", "star-smoothness", "units",
                                                 "force-bezier-end-conditions", "tol", "ver", "f", "e", "v",
                                                 "l", "ec", "0g", "0m", "end-conditions", "star-knot-rule",
                                                 "geom-tol", "behavior-version", "compat-version", "106ek"};
  // Fusion lists its creased edges and vertices in 100edges / 100verts; Rhino's records of those names are
  // editor selections.
  const bool fusion = setting("end-conditions").has_value();
  for (const auto& [kind, recs] : kinds_)
    if (std::find(geometry.begin(), geometry.end(), kind) == geometry.end() && !(fusion && (kind == "100edges" || kind == "100verts")))
      rep.skipped_records[kind] = static_cast<int>(recs.size());
  int degree = 3;
  if (auto r = setting("degree")) degree = number<int>(*r, 0, "degree");
  if (degree < 1 || degree % 2 == 0)
    fail(setting("degree")->line, "degree " + std::to_string(degree) + ": TSM grip maps are read for odd degrees");
  // A setting's words as written, joined by spaces.
  const auto words = [&](std::string_view kind) {
    std::string w;
    if (const auto r = setting(kind))
      for (std::string_view x : r->words) {
        if (!w.empty()) w += ' ';
        w += x;
      }
    return w;
  };
  rep.units = words("units");
  if (auto r = setting("tol")) rep.tolerance = number<double>(*r, 0, "tolerance");
  if (auto r = setting("ver")) rep.version = number<int>(*r, 0, "version");
  rep.cap_type = words("cap-type");
  rep.star_smoothness = words("star-smoothness");
  rep.behavior_version = words("behavior-version");
  rep.compat_version = words("compat-version");
  if (auto r = setting("geom-tol")) rep.geom_tolerance = number<double>(*r, 0, "geometric tolerance");
  // Fusion's end conditions: MULTIPLE_KNOTS the repeated knots of Bezier end conditions, SUBD_CREASES the boundary
  // as a subdivision crease; its star points: NURCCS, the knot-interval-weighted Catmull-Clark evaluated here.
  EndConditions ends = EndConditions::bezier;
  rep.end_conditions = words("end-conditions");
  if (rep.end_conditions == "SUBD_CREASES") ends = EndConditions::subd_creases;
  else if (!rep.end_conditions.empty() && rep.end_conditions != "MULTIPLE_KNOTS")
    fail(setting("end-conditions")->line, "end-conditions " + rep.end_conditions + " is not read (MULTIPLE_KNOTS or SUBD_CREASES)");
  rep.star_knot_rule = words("star-knot-rule");
  if (!rep.star_knot_rule.empty() && rep.star_knot_rule != "NURCCS")
    fail(setting("star-knot-rule")->line, "star-knot-rule " + rep.star_knot_rule + " is not read (NURCCS: knot-interval-weighted Catmull-Clark)");
  TSpline& ts = out.spline;
  ts.degrees = {degree, degree};
  if (auto r = setting("force-bezier-end-conditions")) ts.force_bezier = number<int>(*r, 0, "flag") != 0;

  const auto& F = all("f");
  const auto& E = all("e");
  const auto& V = all("v");
  const auto& L = all("l");
  const int nf = static_cast<int>(F.size()), ne = static_cast<int>(E.size()), nv = static_cast<int>(V.size()),
            nl = static_cast<int>(L.size());
  // Links.
  std::vector<std::optional<RawLink>> links(static_cast<std::size_t>(nl));
  for (int i = 0; i < nl; ++i) {
    const Record& r = L[static_cast<std::size_t>(i)];
    if (r.words.empty()) {
      ++rep.deleted;
      continue;
    }
    RawLink k{number<int>(r, 0, "prev link"), number<int>(r, 1, "next link"), number<int>(r, 2, "opposite link"),
              number<int>(r, 3, "vertex"),    number<int>(r, 4, "face"),      number<int>(r, 5, "edge"),
              number<int>(r, 6, "corner flag")};
    const auto bad = [&](int id, int n) { return id < 0 || id >= n; };
    if (bad(k.prev, nl) || bad(k.next, nl) || bad(k.opp, nl)) fail(r.line, "link " + std::to_string(i) + " names a link that does not exist");
    if (bad(k.vertex, nv) || V[static_cast<std::size_t>(k.vertex)].words.empty())
      fail(r.line, "link " + std::to_string(i) + " leaves vertex " + std::to_string(k.vertex) + ", which does not exist");
    if (bad(k.edge, ne) || E[static_cast<std::size_t>(k.edge)].words.empty())
      fail(r.line, "link " + std::to_string(i) + " runs along edge " + std::to_string(k.edge) + ", which does not exist");
    if (k.face < -1 || k.face >= nf) fail(r.line, "link " + std::to_string(i) + " names face " + std::to_string(k.face) + ", which does not exist");
    // An outside link's flag may be negative (checked below against its vertex's faces): the outside's angle at a
    // boundary star point is 0 or less.
    if (k.flag > 2 || (k.flag < 0 && k.face >= 0))
      fail(r.line, "link " + std::to_string(i) + ": corner flag " + std::to_string(k.flag) + " is not 0, 1 or 2");
    links[static_cast<std::size_t>(i)] = k;
  }
  const auto link = [&](int i) -> const RawLink& {
    if (!links[static_cast<std::size_t>(i)]) fail(L[static_cast<std::size_t>(i)].line, "link " + std::to_string(i) + " is deleted but referenced");
    return *links[static_cast<std::size_t>(i)];
  };
  for (int i = 0; i < nl; ++i) {
    if (!links[static_cast<std::size_t>(i)]) continue;
    const RawLink& k = *links[static_cast<std::size_t>(i)];
    const int line = L[static_cast<std::size_t>(i)].line;
    if (link(k.opp).opp != i || link(k.opp).edge != k.edge)
      fail(line, "inconsistent links: link " + std::to_string(i) + " and its opposite " + std::to_string(k.opp) +
                     " are not each other's opposite on one edge");
    if (link(k.next).prev != i || link(k.next).face != k.face)
      fail(line, "inconsistent links: link " + std::to_string(i) + "'s next link " + std::to_string(k.next) +
                     " does not have it as previous link in the same face");
    if (link(k.next).vertex != link(k.opp).vertex)
      fail(line, "inconsistent links: link " + std::to_string(i) + " does not end where its next link starts");
  }
  // The flag is the angle / 90 - 1 of the link's face at its vertex; on an outside link the outside's angle,
  // 360 degrees less the faces' (published Rhino models: 2, 1, 0 after one, two, three faces). At a
  // boundary star point (four faces or more) that is 3 - (the faces' right angles): -1 after four faces, -2 after
  // five. Those flags are accepted, and 0 as before (the outside's angle clamped); no other negative flag.
  {
    std::vector<int> right_angles(static_cast<std::size_t>(nv), 0);
    for (const auto& k : links)
      if (k && k->face >= 0 && !F[static_cast<std::size_t>(k->face)].words.empty()) right_angles[static_cast<std::size_t>(k->vertex)] += k->flag + 1;
    for (int i = 0; i < nl; ++i) {
      const auto& k = links[static_cast<std::size_t>(i)];
      if (!k || k->flag >= 0) continue;
      const int faces = right_angles[static_cast<std::size_t>(k->vertex)];
      if (k->flag != 3 - faces)
        fail(L[static_cast<std::size_t>(i)].line, "link " + std::to_string(i) + ": corner flag " + std::to_string(k->flag) +
                                                      " on the boundary at vertex " + std::to_string(k->vertex) + ", whose faces' angles sum to " +
                                                      std::to_string(90 * faces) + " degrees, is not the outside's angle / 90 - 1 (" +
                                                      std::to_string(3 - faces) + ") nor 0, 1 or 2");
    }
  }
  // Faces: loops of links, rectangles.
  std::vector<std::vector<int>> loops(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    const Record& r = F[static_cast<std::size_t>(f)];
    if (r.words.empty()) {
      ++rep.holes;
      continue;
    }
    const int l0 = number<int>(r, 0, "link");
    if (l0 < 0 || l0 >= nl) fail(r.line, "face " + std::to_string(f) + " names link " + std::to_string(l0) + ", which does not exist");
    int l = l0, corners = 0;
    do {
      const RawLink& k = link(l);
      if (k.face != f) fail(r.line, "inconsistent links: link " + std::to_string(l) + " in the loop of face " + std::to_string(f) + " names face " + std::to_string(k.face));
      if (k.flag == 2) fail(r.line, "face " + std::to_string(f) + " is not rectangular (reflex corner at vertex " + std::to_string(k.vertex) + ")");
      if (k.flag == 0) ++corners;
      loops[static_cast<std::size_t>(f)].push_back(l);
      if (static_cast<int>(loops[static_cast<std::size_t>(f)].size()) > nl) fail(r.line, "face " + std::to_string(f) + ": its link loop does not close");
      l = k.next;
    } while (l != l0);
    if (corners != 4) fail(r.line, "face " + std::to_string(f) + " is not rectangular (" + std::to_string(corners) + " corners)");
  }
  // Edge intervals.
  TMesh& mesh = out.mesh;
  mesh.degree = degree;
  mesh.force_bezier = ts.force_bezier;
  mesh.end_conditions = ends;
  mesh.intervals.assign(static_cast<std::size_t>(ne), 0.0);
  for (int e = 0; e < ne; ++e) {
    const Record& r = E[static_cast<std::size_t>(e)];
    if (r.words.empty()) {
      ++rep.deleted;
      continue;
    }
    const int l = number<int>(r, 0, "link");
    if (l < 0 || l >= nl || !links[static_cast<std::size_t>(l)] || link(l).edge != e)
      fail(r.line, "edge " + std::to_string(e) + " names link " + std::to_string(l) + ", which is not one of its links");
    double& d = mesh.intervals[static_cast<std::size_t>(e)];
    d = number<double>(r, 1, "knot interval");
    if (!(d > 0) || !std::isfinite(d))
      fail(r.line, "edge " + std::to_string(e) + ": knot interval " + std::string(r.words[1]) + " is not positive");
  }
  // Fusion's edge knots: one per edge slot, read only where they repeat the edge's knot interval (-1: a deleted
  // edge); they then carry nothing new.
  if (const auto& K = all("106ek"); !K.empty()) {
    if (static_cast<int>(K.size()) != ne)
      fail(K.front().line, std::to_string(K.size()) + " edge knot records (106ek) for " + std::to_string(ne) + " edges");
    for (int e = 0; e < ne; ++e) {
      const Record& r = K[static_cast<std::size_t>(e)];
      const double k = number<double>(r, 0, "edge knot"), d = mesh.intervals[static_cast<std::size_t>(e)];
      const bool same = d > 0 ? std::abs(k - d) <= 1e-12 * std::max(1.0, d) : k == -1;
      if (!same)
        fail(r.line, "edge knot (106ek) " + std::string(r.words[0]) + " of edge " + std::to_string(e) + " is not its knot interval " +
                         (d > 0 ? std::string(E[static_cast<std::size_t>(e)].words[1]) : std::string("(deleted: -1)")) + "; other edge knots are not read");
    }
    rep.skipped_records["106ek"] = static_cast<int>(K.size());
  }
  // The half-edge mesh; each link's direction in its vertex's frame, walking round the vertex from the link its
  // `v` record names (the next link counter-clockwise turns by the angle of the face between them).
  mesh.links.resize(static_cast<std::size_t>(nl));
  for (int i = 0; i < nl; ++i)
    if (links[static_cast<std::size_t>(i)]) {
      const RawLink& k = *links[static_cast<std::size_t>(i)];
      const bool in_face = k.face >= 0 && !loops[static_cast<std::size_t>(k.face)].empty();
      mesh.links[static_cast<std::size_t>(i)] = {k.prev, k.next, k.opp, k.vertex, in_face ? k.face : -1, k.edge, k.flag, -1};
    }
  mesh.faces = loops;
  mesh.vertices.resize(static_cast<std::size_t>(nv));
  for (int v = 0; v < nv; ++v) {
    const Record& vr = V[static_cast<std::size_t>(v)];
    TMeshVertex& x = mesh.vertices[static_cast<std::size_t>(v)];
    if (vr.words.empty()) {
      ++rep.deleted;
      x.live = false;
      continue;
    }
    const int l = number<int>(vr, 0, "link");
    const int fd = vr.words.size() > 1 ? direction_of(vr.words[1]) : -1;
    if (l < 0 || l >= nl || !links[static_cast<std::size_t>(l)] || link(l).vertex != v || fd < 0)
      fail(vr.line, "vertex " + std::to_string(v) + " needs an outgoing link and a direction (NORTH, WEST, SOUTH, EAST)");
    int c = l, frame = fd;
    for (int n = 0; n < 8 && mesh.links[static_cast<std::size_t>(c)].frame < 0; ++n) {
      mesh.links[static_cast<std::size_t>(c)].frame = frame;
      frame = ((frame + link(c).flag + 1) % 4 + 4) % 4;  // a negative outside flag turns clockwise
      c = link(link(c).prev).opp;
    }
  }
  for (const Record& r : all("ec"))
    if (!r.words.empty()) {
      const int e = number<int>(r, 0, "edge");
      if (e < 0 || e >= ne || E[static_cast<std::size_t>(e)].words.empty()) fail(r.line, "edge condition names edge " + std::to_string(e) + ", which does not exist");
      // Fusion writes them on open boundary edges, where the end conditions say what the edge is; between two
      // faces of a SUBD_CREASES mesh one is taken as a sharp crease like those of `100edges` (sharp_creases).
      // Bezier end conditions have no crease rule.
      const TMeshLink& k = mesh.links[static_cast<std::size_t>(number<int>(E[static_cast<std::size_t>(e)], 0, "link"))];
      if (ends == EndConditions::bezier && !rep.end_conditions.empty() && k.face >= 0 && mesh.links[static_cast<std::size_t>(k.opp)].face >= 0)
        fail(r.line, "edge " + std::to_string(e) + " between two faces is a crease (ec); creases inside the mesh are read with end-conditions SUBD_CREASES, not " +
                         rep.end_conditions);
      mesh.conditions.push_back({e, number<int>(r, 1, "condition") != 0 ? 1 : 0});
    }
  // Fusion's crease lists: edge and vertex numbers, kept on the mesh. Crease edges between two faces are sharp
  // creases (sharp_creases), which only a subdivision-crease mesh defines.
  const auto crease_list = [&](std::string_view kind, int count, const std::vector<Record>& slots, std::vector<int>& list) {
    if (!fusion) return;
    for (const Record& r : all(kind))
      for (std::size_t i = 0; i < r.words.size(); ++i) {
        const int x = number<int>(r, i, kind == "100edges" ? "crease edge" : "crease vertex");
        if (x < 0 || x >= count || slots[static_cast<std::size_t>(x)].words.empty())
          fail(r.line, std::string(kind) + " names " + (kind == "100edges" ? "edge " : "vertex ") + std::to_string(x) + ", which does not exist");
        if (kind == "100verts" && ends == EndConditions::bezier)
          fail(r.line, "creased vertex " + std::to_string(x) + ": creased vertices are read with end-conditions SUBD_CREASES, not " + rep.end_conditions);
        if (kind == "100edges" && ends == EndConditions::bezier) {
          const TMeshLink& k = mesh.links[static_cast<std::size_t>(number<int>(E[static_cast<std::size_t>(x)], 0, "link"))];
          if (k.face >= 0 && mesh.links[static_cast<std::size_t>(k.opp)].face >= 0)
            fail(r.line, "crease edge " + std::to_string(x) + " lies between two faces; creases inside the mesh are read with end-conditions SUBD_CREASES, not " +
                             rep.end_conditions);
        }
        list.push_back(x);
      }
  };
  crease_list("100edges", ne, E, mesh.crease_edges);
  crease_list("100verts", nv, V, mesh.crease_vertices);
  std::vector<int> valence(static_cast<std::size_t>(nv), 0), straight(static_cast<std::size_t>(nv), 0);
  for (int l = 0; l < nl; ++l)
    if (links[static_cast<std::size_t>(l)]) {
      ++valence[static_cast<std::size_t>(link(l).vertex)];
      if (link(l).face >= 0 && link(l).flag == 1) ++straight[static_cast<std::size_t>(link(l).vertex)];
    }
  for (int v = 0; v < nv; ++v)
    if (straight[static_cast<std::size_t>(v)] > 0 && valence[static_cast<std::size_t>(v)] == 3) ++rep.t_junctions;

  // Grips and the grip map.
  const auto& G = all("0g");
  std::vector<char> deleted_grip;
  for (const Record& r : G) {
    deleted_grip.push_back(r.words.empty() ? 1 : 0);
    if (r.words.empty()) {  // a deleted grip keeps its number; the grip map gives it vertex -1
      ++rep.deleted;
      mesh.points.push_back({});
      continue;
    }
    RationalPoint p{{number<double>(r, 0, "x"), number<double>(r, 1, "y"), number<double>(r, 2, "z")},
                    r.words.size() > 3 ? number<double>(r, 3, "weight") : 1.0};
    if (!(p.w > 0)) fail(r.line, "control point weight " + std::string(r.words[3]) + " is not positive");
    mesh.points.push_back(p);
  }
  const int ng = static_cast<int>(G.size());
  std::vector<int> grip_vertex;
  std::vector<char> used(static_cast<std::size_t>(ng), 0);
  const auto use = [&](int g, int v, int line) {
    if (deleted_grip[static_cast<std::size_t>(g)]) fail(line, "grip " + std::to_string(g) + " is deleted but used");
    if (used[static_cast<std::size_t>(g)]) fail(line, "grip " + std::to_string(g) + " is used twice");
    used[static_cast<std::size_t>(g)] = 1;
    if (g < static_cast<int>(grip_vertex.size()) && grip_vertex[static_cast<std::size_t>(g)] != v)
      fail(line, "grip " + std::to_string(g) + " belongs to vertex " + std::to_string(grip_vertex[static_cast<std::size_t>(g)]) + ", not " + std::to_string(v));
  };
  std::vector<int> block_line(static_cast<std::size_t>(nv), 0);  // blocks are checked once the map is complete
  rep.grip_map = !grip_map_.empty();
  if (!rep.grip_map && ng > 0) {
    // Fusion's files: the grips in vertex order, one per vertex slot (a deleted vertex's grip deleted too) or
    // one per live vertex.
    const int live = static_cast<int>(std::count_if(mesh.vertices.begin(), mesh.vertices.end(), [](const TMeshVertex& x) { return x.live; }));
    if (ng != nv && ng != live)
      fail(G.back().line, "no grip map (0m) and " + std::to_string(ng) + " control points (0g) for " + std::to_string(live) +
                              " vertices: without a grip map each vertex has one, in vertex order");
    int g = 0;
    for (int v = 0; v < nv; ++v) {
      TMeshVertex& x = mesh.vertices[static_cast<std::size_t>(v)];
      if (!x.live) {
        if (ng != nv) continue;
        if (!deleted_grip[static_cast<std::size_t>(g)])
          fail(G[static_cast<std::size_t>(g)].line, "control point " + std::to_string(g) + " of the deleted vertex " + std::to_string(v) + " is not deleted");
        grip_vertex.push_back(-1);
        ++g;
        continue;
      }
      if (deleted_grip[static_cast<std::size_t>(g)])
        fail(G[static_cast<std::size_t>(g)].line, "control point " + std::to_string(g) + " of vertex " + std::to_string(v) + " is deleted");
      x.primary = g++;
      grip_vertex.push_back(v);
      used[static_cast<std::size_t>(x.primary)] = 1;
    }
  }
  for (const Record& r : grip_map_) {
    if (r.words.empty()) fail(r.line, "empty grip map record");
    const std::string_view w = r.words[0];
    if (w == "odd-grip-map") continue;
    if (w == "gvp" || w == "gv") {
      const int v = number<int>(r, 1, "vertex");
      if (v == -1 && w == "gv") {  // a deleted grip
        grip_vertex.push_back(-1);
        continue;
      }
      if (v < 0 || v >= nv || !mesh.vertices[static_cast<std::size_t>(v)].live) fail(r.line, "grip map names vertex " + std::to_string(v) + ", which does not exist");
      if (w == "gvp") {
        int& p = mesh.vertices[static_cast<std::size_t>(v)].primary;
        if (p >= 0) fail(r.line, "vertex " + std::to_string(v) + " has two primary grips");
        p = static_cast<int>(grip_vertex.size());
        if (p >= ng) fail(r.line, "the grip map lists more grips than the file has control points");
        grip_vertex.push_back(v);
        use(p, v, r.line);
        continue;
      }
      grip_vertex.push_back(v);
    } else if (w == "cg") {
      const int v = number<int>(r, 1, "vertex");
      if (v < 0 || v >= nv || !mesh.vertices[static_cast<std::size_t>(v)].live) fail(r.line, "grip block names vertex " + std::to_string(v) + ", which does not exist");
      TMeshVertex& x = mesh.vertices[static_cast<std::size_t>(v)];
      if (!x.block.empty() || x.block_dims != std::array<int, 4>{}) fail(r.line, "vertex " + std::to_string(v) + " has two grip blocks");
      if (number<int>(r, 2, "valence") != 4) fail(r.line, "grip block of valence other than 4 (a star point)");
      long long count = 0;
      for (int k = 0; k < 4; ++k) x.block_dims[static_cast<std::size_t>(k)] = number<int>(r, 3 + static_cast<std::size_t>(k), "block size");
      for (int k = 0; k < 4; ++k) {
        const int d = x.block_dims[static_cast<std::size_t>(k)];
        if (d < 0 || static_cast<std::size_t>(d) > r.words.size()) fail(r.line, "grip block size " + std::to_string(d) + " out of range");
        count += static_cast<long long>(d) * (x.block_dims[static_cast<std::size_t>((k + 1) % 4)] + 1LL);
      }
      if (static_cast<long long>(r.words.size()) != 7 + count)
        fail(r.line, "grip block of vertex " + std::to_string(v) + " lists " + std::to_string(r.words.size() - 7) +
                         " grips, its sizes need " + std::to_string(count));
      for (long long i = 0; i < count; ++i) {
        const int g = number<int>(r, 7 + static_cast<std::size_t>(i), "grip");
        if (g < -1 || g >= ng) fail(r.line, "grip block names grip " + std::to_string(g) + ", which does not exist");
        x.block.push_back(g);
      }
      block_line[static_cast<std::size_t>(v)] = r.line;
      if (x.block.empty()) x.block.push_back(-1);  // an empty block still counts as the vertex's one block
    } else {
      rep.skipped_records["0m " + std::string(w)]++;
    }
  }
  if (static_cast<int>(grip_vertex.size()) != ng)
    fail("the grip map lists " + std::to_string(grip_vertex.size()) + " grips, the file has " + std::to_string(ng) + " control points");
  for (int v = 0; v < nv; ++v) {
    TMeshVertex& x = mesh.vertices[static_cast<std::size_t>(v)];
    if (x.block.size() == 1 && x.block[0] == -1 && x.block_dims == std::array<int, 4>{}) x.block.clear();
    for (int g : x.block)
      if (g >= 0) {
        use(g, v, block_line[static_cast<std::size_t>(v)]);
        ++rep.repeated_knot_nodes;
      }
  }
  for (int g = 0; g < ng; ++g) {
    if ((grip_vertex[static_cast<std::size_t>(g)] < 0) != (deleted_grip[static_cast<std::size_t>(g)] != 0))
      fail(G[static_cast<std::size_t>(g)].line, "control point " + std::to_string(g) + (deleted_grip[static_cast<std::size_t>(g)] ? " is deleted but the grip map gives it a vertex" : " has no vertex in the grip map"));
    if (!used[static_cast<std::size_t>(g)] && grip_vertex[static_cast<std::size_t>(g)] >= 0)
      fail(G[static_cast<std::size_t>(g)].line, "control point " + std::to_string(g) + " (vertex " + std::to_string(grip_vertex[static_cast<std::size_t>(g)]) +
                                                    ") is neither a primary grip nor in a grip block");
  }
  // Star points (extraordinary vertices): no global (s, t); the model is kept as its mesh (see t_mesh_surface).
  const std::vector<int> stars = star_points(mesh);
  rep.star_points = static_cast<int>(stars.size());
  int seed = -1;
  for (int f = 0; f < nf && seed < 0; ++f)
    if (!loops[static_cast<std::size_t>(f)].empty()) seed = f;
  if (seed < 0) fail("no face");
  for (int v = 0; v < nv; ++v)
    if (mesh.vertices[static_cast<std::size_t>(v)].live && valence[static_cast<std::size_t>(v)] == 0)
      fail(V[static_cast<std::size_t>(v)].line, "vertex " + std::to_string(v) + " is on no face");
  rep.crease_edges = static_cast<int>(crease_edges(mesh).size());
  if (has_creases(mesh)) {
    // Cut open along its creases the mesh may fall apart, and creased vertices are corners: no global (s, t); its
    // sides are checked here.
    try {
      (void)bezier_equivalent(mesh);
    } catch (const Error& e) {
      fail(e.what());
    }
    return out;
  }
  // Irregular vertices of a crease boundary (a concave corner: a crease vertex of three faces) have no Bezier
  // form either: evaluated by local subdivision per face.
  if (!stars.empty() || has_closed_strip(mesh) || !irregular_crease_vertices(mesh).empty()) return out;
  try {
    // The mesh stays as read (crease flag, points); the spline is that of its Bezier end conditions.
    TChart chart = t_spline_chart(bezier_equivalent(mesh), {}, seed, true);
    ts = std::move(chart.spline);
  } catch (const Error& e) {
    fail(e.what());
  }
  return out;
}

}  // namespace

TsmModel parse_tsm(std::string_view text, const std::string& name) { return TsmReader(text, name).build(); }

TsmModel read_tsm(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  require(f.good(), [&] { return "cannot open " + path; });
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_tsm(ss.str(), path);
}

}  // namespace trivar::io

namespace trivar::io {

namespace {

int compass(const TImage& im, int l) {
  const TVertex& a = im.vertices[static_cast<std::size_t>(im.link_start(l))];
  const TVertex& b = im.vertices[static_cast<std::size_t>(im.link_end(l))];
  return a.s == b.s ? (b.t > a.t ? 0 : 2) : (b.s > a.s ? 3 : 1);
}

void write_grip(std::ostream& os, const RationalPoint& p) {
  os << "0g";
  for (double x : {p.xyz[0], p.xyz[1], p.xyz[2], p.w}) {
    os << ' ';
    write_number(os, x);
  }
  os << "\n";
}

// The text first, so that nothing is written on error.
template <class Write>
void write_tsm_file(const std::string& path, const Write& write) {
  std::ostringstream text;
  write(text);
  write_file_atomically(path, [&](std::ostream& os) { os << text.str(); });
}

}  // namespace

void write_tsm(std::ostream& os, const TSpline& ts) {
  validate(ts);
  require(ts.degrees[0] == ts.degrees[1] && ts.degrees[0] % 2 == 1,
          "TSM: the format holds one odd degree for both directions");
  const TImage& im = ts.image;
  const int nl = static_cast<int>(im.links.size());
  // Faces of links, and for the links outside every face the next link along the boundary.
  std::vector<int> face(static_cast<std::size_t>(nl), -1), next(static_cast<std::size_t>(nl), -1),
      prev(static_cast<std::size_t>(nl), -1), flag(static_cast<std::size_t>(nl), 0);
  for (int f = 0; f < static_cast<int>(im.faces.size()); ++f) {
    const auto& loop = im.faces[static_cast<std::size_t>(f)].loop;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int l = loop[i], n = loop[(i + 1) % loop.size()], p = loop[(i + loop.size() - 1) % loop.size()];
      face[static_cast<std::size_t>(l)] = f;
      next[static_cast<std::size_t>(l)] = n;
      prev[static_cast<std::size_t>(l)] = p;
      flag[static_cast<std::size_t>(l)] = compass(im, p) == compass(im, l) ? 1 : 0;
    }
  }
  for (int l = 0; l < nl; ++l) {
    if (face[static_cast<std::size_t>(l)] >= 0) continue;
    // The outside turns the other way round: at the end vertex take the outgoing boundary link turning right
    // first (the outside region on the left of a clockwise boundary walk).
    const int d = compass(im, l);
    const TVertex& v = im.vertices[static_cast<std::size_t>(im.link_end(l))];
    int n = -1;
    for (int turn : {3, 0, 1}) {
      const int c = v.links[static_cast<std::size_t>((d + turn) % 4)];
      if (c >= 0 && face[static_cast<std::size_t>(c)] < 0) {
        n = c;
        break;
      }
    }
    require(n >= 0, "TSM: the boundary is not a simple loop at vertex " + std::to_string(im.link_end(l)));
    next[static_cast<std::size_t>(l)] = n;
    prev[static_cast<std::size_t>(n)] = l;
  }
  for (int l = 0; l < nl; ++l)
    if (face[static_cast<std::size_t>(l)] < 0) {
      const int turn = (compass(im, l) - compass(im, prev[static_cast<std::size_t>(l)]) + 4) % 4;
      flag[static_cast<std::size_t>(l)] = turn == 0 ? 1 : turn == 3 ? 2 : 0;  // angle of the outside at the vertex
    }
  // The opposite link of every link: the other link of its edge.
  std::vector<std::array<int, 2>> edge_links(im.edges.size(), {-1, -1});
  for (int l = 0; l < nl; ++l) edge_links[static_cast<std::size_t>(im.links[static_cast<std::size_t>(l)].edge)][im.links[static_cast<std::size_t>(l)].sense ? 0 : 1] = l;
  for (const auto& e : edge_links) require(e[0] >= 0 && e[1] >= 0, "TSM: an edge needs both its links");
  const auto opp = [&](int l) {
    const auto& e = edge_links[static_cast<std::size_t>(im.links[static_cast<std::size_t>(l)].edge)];
    return e[0] == l ? e[1] : e[0];
  };
  // Node blocks per vertex: positions along the coincident-neighbour chains from the vertex's first node.
  const std::size_t nv = im.vertices.size();
  std::vector<std::vector<int>> on(nv);
  for (int n = 0; n < static_cast<int>(ts.connect.nodes.size()); ++n) {
    const TNode& x = ts.connect.nodes[static_cast<std::size_t>(n)];
    require(x.kind == TAnchorKind::vertex, "TSM: node " + std::to_string(n) + " is not on a vertex");
    on[static_cast<std::size_t>(x.anchor)].push_back(n);
  }
  static constexpr std::array<std::array<int, 2>, 4> step{{{0, 1}, {-1, 0}, {0, -1}, {1, 0}}};
  std::vector<int> grip_of(ts.connect.nodes.size(), -1);
  std::vector<int> grip_node;  // grips in order: the primaries first (vertex order), then the blocks
  std::vector<std::string> blocks;
  for (std::size_t v = 0; v < nv; ++v) {
    if (on[v].empty()) continue;
    grip_of[static_cast<std::size_t>(on[v][0])] = static_cast<int>(grip_node.size());
    grip_node.push_back(on[v][0]);
  }
  std::vector<int> grip_vertex(grip_node.size());
  for (std::size_t g = 0; g < grip_node.size(); ++g) grip_vertex[g] = ts.connect.nodes[static_cast<std::size_t>(grip_node[g])].anchor;
  for (std::size_t v = 0; v < nv; ++v) {
    if (on[v].size() < 2) continue;
    std::map<std::array<int, 2>, int> at{{{0, 0}, on[v][0]}};
    std::map<int, std::array<int, 2>> pos{{on[v][0], {0, 0}}};
    std::vector<int> todo{on[v][0]};
    while (!todo.empty()) {
      const int n = todo.back();
      todo.pop_back();
      for (int d = 0; d < 4; ++d) {
        const int m = ts.connect.nodes[static_cast<std::size_t>(n)].neighbours[static_cast<std::size_t>(d)];
        if (m < 0 || ts.connect.nodes[static_cast<std::size_t>(m)].anchor != static_cast<int>(v) || pos.count(m)) continue;
        const std::array<int, 2> p{pos[n][0] + step[static_cast<std::size_t>(d)][0], pos[n][1] + step[static_cast<std::size_t>(d)][1]};
        pos[m] = p;
        at[p] = m;
        todo.push_back(m);
      }
    }
    require(pos.size() == on[v].size(), "TSM: the nodes of vertex " + std::to_string(v) + " are not one block");
    std::array<int, 4> dims{0, 0, 0, 0};
    for (const auto& [p, n] : at)
      for (int d = 0; d < 4; ++d) {
        const int along = p[0] * step[static_cast<std::size_t>(d)][0] + p[1] * step[static_cast<std::size_t>(d)][1];
        dims[static_cast<std::size_t>(d)] = std::max(dims[static_cast<std::size_t>(d)], along);
      }
    std::ostringstream rec;
    rec << "0m cg " << v << " 4";
    for (int d : dims) rec << ' ' << d;
    std::size_t listed = 0;
    for (int k = 0; k < 4; ++k)
      for (int i = 1; i <= dims[static_cast<std::size_t>(k)]; ++i)
        for (int j = 0; j <= dims[static_cast<std::size_t>((k + 1) % 4)]; ++j) {
          const auto& a = step[static_cast<std::size_t>(k)];
          const auto& c = step[static_cast<std::size_t>((k + 1) % 4)];
          auto it = at.find({i * a[0] + j * c[0], i * a[1] + j * c[1]});
          if (it == at.end()) {
            rec << " -1";
            continue;
          }
          grip_of[static_cast<std::size_t>(it->second)] = static_cast<int>(grip_node.size());
          grip_node.push_back(it->second);
          grip_vertex.push_back(static_cast<int>(v));
          rec << ' ' << grip_of[static_cast<std::size_t>(it->second)];
          ++listed;
        }
    require(listed + 1 == on[v].size(), "TSM: the nodes of vertex " + std::to_string(v) + " do not fit the four wedges of a grip block");
    blocks.push_back(rec.str());
  }
  os << "#TS0200\n\ndegree " << ts.degrees[0] << "\ncap-type 1\nstar-smoothness 0\nunits 1 millimeters\n"
     << "force-bezier-end-conditions " << (ts.force_bezier ? 1 : 0) << '\n';
  for (const TFace& f : im.faces) os << "f " << f.loop.front() << " 0\n";
  for (std::size_t e = 0; e < im.edges.size(); ++e) {
    const Box<2> b = im.edge_box(static_cast<int>(e));
    os << "e " << edge_links[e][0] << ' ';
    write_number(os, b.extent(0) + b.extent(1));
    os << '\n';
  }
  for (const TVertex& x : im.vertices) {
    int d = 0;
    while (d < 4 && x.links[static_cast<std::size_t>(d)] < 0) ++d;
    require(d < 4, "TSM: a vertex without edges");
    static constexpr std::array<const char*, 4> kName{"NORTH", "WEST", "SOUTH", "EAST"};
    os << "v " << x.links[static_cast<std::size_t>(d)] << ' ' << kName[static_cast<std::size_t>(d)] << '\n';
  }
  for (int l = 0; l < nl; ++l)
    os << "l " << prev[static_cast<std::size_t>(l)] << ' ' << next[static_cast<std::size_t>(l)] << ' ' << opp(l) << ' '
       << im.link_start(l) << ' ' << face[static_cast<std::size_t>(l)] << ' ' << im.links[static_cast<std::size_t>(l)].edge
       << ' ' << flag[static_cast<std::size_t>(l)] << '\n';
  for (const TEdgeCondition& c : im.conditions) os << "ec " << c.edge << ' ' << (c.flag ? 1 : 0) << '\n';
  os << "0m odd-grip-map\n";
  for (std::size_t g = 0; g < grip_node.size(); ++g)
    os << "0m " << (grip_of[static_cast<std::size_t>(on[static_cast<std::size_t>(grip_vertex[g])][0])] == static_cast<int>(g) ? "gvp " : "gv ")
       << grip_vertex[g] << '\n';
  for (const std::string& b : blocks) os << b << '\n';
  for (int n : grip_node) write_grip(os, ts.pointset.points[static_cast<std::size_t>(ts.connect.nodes[static_cast<std::size_t>(n)].point)]);
  os << "\ntol 1e-05\nver 1\n";
}

void write_tsm(const std::string& path, const TSpline& ts) {
  write_tsm_file(path, [&](std::ostream& os) { write_tsm(os, ts); });
}

void write_tsm(std::ostream& os, const TMesh& m, const TsmReport& settings) {
  static constexpr std::array<const char*, 4> kName{"NORTH", "WEST", "SOUTH", "EAST"};
  // Fusion's dialect for a mesh read from its files, and for subdivision-crease boundaries, which only it has.
  const bool fusion = !settings.end_conditions.empty() || m.end_conditions == EndConditions::subd_creases;
  const auto or_else = [](const std::string& s, const char* fallback) { return s.empty() ? std::string(fallback) : s; };
  // Each grip's vertex (its own node or a block node); grips no vertex names are deleted slots.
  std::vector<int> grip_vertex(m.points.size(), -1);
  std::vector<char> primary(m.points.size(), 0);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const TMeshVertex& x = m.vertices[v];
    if (!x.live) continue;
    if (x.primary >= 0) {
      grip_vertex[static_cast<std::size_t>(x.primary)] = static_cast<int>(v);
      primary[static_cast<std::size_t>(x.primary)] = 1;
    }
    for (int g : x.block)
      if (g >= 0) grip_vertex[static_cast<std::size_t>(g)] = static_cast<int>(v);
  }
  // Without a grip map (as Fusion writes) when every live vertex has one grip, its own number, and no block.
  bool positional = fusion && !settings.grip_map && m.points.size() == m.vertices.size();
  for (std::size_t v = 0; v < m.vertices.size() && positional; ++v)
    positional = m.vertices[v].live ? m.vertices[v].primary == static_cast<int>(v) && m.vertices[v].block.empty() : grip_vertex[v] < 0;
  os << "#TS0200\n\ndegree " << m.degree << "\ncap-type " << or_else(settings.cap_type, fusion ? "G1CAPS" : "1")
     << "\nstar-smoothness " << or_else(settings.star_smoothness, "0") << "\nunits " << or_else(settings.units, "1 millimeters") << '\n';
  if (fusion)
    os << "end-conditions " << (m.end_conditions == EndConditions::subd_creases ? "SUBD_CREASES" : "MULTIPLE_KNOTS")
       << "\nstar-knot-rule " << or_else(settings.star_knot_rule, "NURCCS") << '\n';
  else
    os << "force-bezier-end-conditions " << (m.force_bezier ? 1 : 0) << '\n';
  for (const auto& loop : m.faces) {
    if (loop.empty()) os << "f\n";
    else os << "f " << loop.front() << " 0\n";
  }
  std::vector<int> edge_link(m.intervals.size(), -1);
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l)
    if (m.links[static_cast<std::size_t>(l)].vertex >= 0 && edge_link[static_cast<std::size_t>(m.links[static_cast<std::size_t>(l)].edge)] < 0)
      edge_link[static_cast<std::size_t>(m.links[static_cast<std::size_t>(l)].edge)] = l;
  for (std::size_t e = 0; e < m.intervals.size(); ++e) {
    if (edge_link[e] < 0) {
      os << "e\n";
      continue;
    }
    os << "e " << edge_link[e] << ' ';
    write_number(os, m.intervals[e]);
    os << '\n';
  }
  std::vector<int> vertex_link(m.vertices.size(), -1);
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l) {
    const TMeshLink& k = m.links[static_cast<std::size_t>(l)];
    if (k.vertex >= 0 && k.frame >= 0 && vertex_link[static_cast<std::size_t>(k.vertex)] < 0) vertex_link[static_cast<std::size_t>(k.vertex)] = l;
  }
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    if (!m.vertices[v].live) {
      os << "v\n";
      continue;
    }
    require(vertex_link[v] >= 0, "TSM: vertex " + std::to_string(v) + " has no link with a frame direction");
    os << "v " << vertex_link[v] << ' ' << kName[static_cast<std::size_t>(m.links[static_cast<std::size_t>(vertex_link[v])].frame)] << '\n';
  }
  for (const TMeshLink& k : m.links) {
    if (k.vertex < 0) os << "l\n";
    else os << "l " << k.prev << ' ' << k.next << ' ' << k.opp << ' ' << k.vertex << ' ' << k.face << ' ' << k.edge << ' ' << k.flag << '\n';
  }
  for (const auto& [e, flag] : m.conditions) os << "ec " << e << ' ' << flag << '\n';
  if (!positional) {
    os << "0m odd-grip-map\n";
    for (std::size_t g = 0; g < m.points.size(); ++g) os << "0m " << (primary[g] ? "gvp " : "gv ") << grip_vertex[g] << '\n';
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      const TMeshVertex& x = m.vertices[v];
      if (!x.live || x.block.empty()) continue;
      os << "0m cg " << v << " 4";
      for (int d : x.block_dims) os << ' ' << d;
      for (int g : x.block) os << ' ' << g;
      os << '\n';
    }
  }
  for (std::size_t g = 0; g < m.points.size(); ++g) {
    if (grip_vertex[g] < 0) {
      os << "0g\n";
      continue;
    }
    write_grip(os, m.points[g]);
  }
  // Fusion's crease lists, both records when either has entries (Fusion writes an empty 100verts so).
  if (fusion && !(m.crease_edges.empty() && m.crease_vertices.empty())) {
    os << "100edges";
    for (int e : m.crease_edges) os << ' ' << e;
    os << "\n100verts";
    for (int v : m.crease_vertices) os << ' ' << v;
    os << '\n';
  }
  os << "\ntol ";
  write_number(os, settings.tolerance > 0 ? settings.tolerance : 1e-5);
  if (fusion) {
    os << "\ngeom-tol ";
    write_number(os, settings.geom_tolerance > 0 ? settings.geom_tolerance : 1e-5);
  }
  os << "\nver " << (settings.version != 0 ? settings.version : 1) << '\n';
  if (!settings.behavior_version.empty()) os << "behavior-version " << settings.behavior_version << '\n';
  if (!settings.compat_version.empty()) os << "compat-version " << settings.compat_version << '\n';
}

void write_tsm(const std::string& path, const TMesh& m, const TsmReport& settings) {
  write_tsm_file(path, [&](std::ostream& os) { write_tsm(os, m, settings); });
}

}  // namespace trivar::io
