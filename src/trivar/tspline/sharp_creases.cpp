#include "trivar/tspline/sharp_creases.hpp"

#include <algorithm>
#include <string>

#include "trivar/core/error.hpp"

namespace trivar {

namespace {

bool in_face(const TMesh& m, int l) {
  const int f = m.links[static_cast<std::size_t>(l)].face;
  return f >= 0 && m.live_face(f);
}

}  // namespace

std::vector<int> crease_edges(const TMesh& m) {
  std::vector<int> out;
  if (m.end_conditions != EndConditions::subd_creases) return out;
  std::vector<int> link_of(m.intervals.size(), -1);
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l) {
    const TMeshLink& k = m.links[static_cast<std::size_t>(l)];
    if (k.vertex >= 0 && k.edge >= 0 && k.edge < static_cast<int>(link_of.size()) && link_of[static_cast<std::size_t>(k.edge)] < 0)
      link_of[static_cast<std::size_t>(k.edge)] = l;
  }
  const auto add = [&](int e) {
    if (e < 0 || e >= static_cast<int>(link_of.size()) || link_of[static_cast<std::size_t>(e)] < 0) return;
    const int l = link_of[static_cast<std::size_t>(e)];
    if (in_face(m, l) && in_face(m, m.links[static_cast<std::size_t>(l)].opp)) out.push_back(e);
  };
  for (const auto& [e, flag] : m.conditions) add(e);
  for (int e : m.crease_edges) add(e);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool has_creases(const TMesh& m) {
  return m.end_conditions == EndConditions::subd_creases && (!m.crease_vertices.empty() || !crease_edges(m).empty());
}

TMesh split_creases(const TMesh& m) {
  const std::vector<int> creases = crease_edges(m);
  // Creased vertices (Fusion's `100verts`): corners whatever their sharp edges.
  if (!has_creases(m)) return m;
  std::vector<char> creased(m.vertices.size(), 0);
  for (int v : m.crease_vertices) creased[static_cast<std::size_t>(v)] = 1;
  const int nl = static_cast<int>(m.links.size());
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const auto fail = [](int v, const std::string& what) { throw Error("T-mesh: crease vertex " + std::to_string(v) + " " + what); };
  std::vector<char> crease(m.intervals.size(), 0);
  for (int e : creases) crease[static_cast<std::size_t>(e)] = 1;
  TMesh x = m;
  // Each crease edge's first link keeps the edge; the second side's link moves to a new edge of the same
  // interval. Both get a new outside link as opposite: new_opp[l] (the link it replaces is l's opposite).
  std::vector<int> new_opp(static_cast<std::size_t>(nl), -1);
  std::vector<std::vector<int>> leaving(m.vertices.size());
  for (int l = 0; l < nl; ++l)
    if (L(l).vertex >= 0) leaving[static_cast<std::size_t>(L(l).vertex)].push_back(l);
  for (int l = 0; l < nl; ++l) {
    if (L(l).vertex < 0 || !crease[static_cast<std::size_t>(L(l).edge)] || new_opp[static_cast<std::size_t>(l)] >= 0) continue;
    const int o = L(l).opp;
    new_opp[static_cast<std::size_t>(l)] = static_cast<int>(x.links.size());
    new_opp[static_cast<std::size_t>(o)] = static_cast<int>(x.links.size()) + 1;
    const int e2 = static_cast<int>(x.intervals.size());
    x.intervals.push_back(m.intervals[static_cast<std::size_t>(L(l).edge)]);
    x.links[static_cast<std::size_t>(o)].edge = e2;
    x.links.push_back({-1, -1, l, -1, -1, L(l).edge, 0, -1});
    x.links.push_back({-1, -1, o, -1, -1, e2, 0, -1});
    x.links[static_cast<std::size_t>(l)].opp = new_opp[static_cast<std::size_t>(l)];
    x.links[static_cast<std::size_t>(o)].opp = new_opp[static_cast<std::size_t>(o)];
  }
  const auto x_opp = [&](int l) { return x.links[static_cast<std::size_t>(l)].opp; };
  const std::size_t nv = m.vertices.size();
  for (std::size_t vi = 0; vi < nv; ++vi) {
    const int v = static_cast<int>(vi);
    if (!m.vertices[vi].live || leaving[vi].empty()) continue;
    int creases_here = 0, outside = 0;
    for (int l : leaving[vi]) {
      if (crease[static_cast<std::size_t>(L(l).edge)]) ++creases_here;
      if (!in_face(m, l)) ++outside;
    }
    if (creases_here == 0) {
      // A creased vertex on no crease: a corner (inside the mesh a cone point, its faces all round it).
      if (creased[vi]) x.vertices[vi].crease_rule = CreaseRule::corner;
      continue;
    }
    // A crease ending inside the mesh (a dart) is cut up to its end vertex, which stays one vertex: its fan of
    // faces runs from one side of the slit to the other.
    const bool dart = outside == 0 && creases_here == 1 && !creased[vi];
    if (outside > 1) fail(v, "lies on " + std::to_string(outside) + " boundary arcs; a crease is cut open at a vertex on one");
    // The links round the vertex counter-clockwise (the next after l: the opposite of l's previous link), with
    // the new outside link before every crease link: the side of the crease before it.
    std::vector<int> round;
    int start = leaving[vi][0];
    for (int l : leaving[vi])
      if (!in_face(m, l)) start = l;
    int c = start;
    do {
      if (crease[static_cast<std::size_t>(L(c).edge)]) {
        const int n = new_opp[static_cast<std::size_t>(L(c).opp)];
        x.links[static_cast<std::size_t>(n)].frame = L(c).frame;  // along the same edge as c
        round.push_back(n);
      }
      round.push_back(c);
      c = L(L(c).prev).opp;
    } while (c != start && round.size() <= leaving[vi].size() + static_cast<std::size_t>(creases_here));
    if (c != start || round.size() != leaving[vi].size() + static_cast<std::size_t>(creases_here))
      fail(v, "has links that are not one fan round it");
    // Start after an outside link, so that the wedges (faces between two outside links) are runs of `round`.
    const auto outside_link = [&](int l) { return l >= nl || !in_face(m, l); };
    const auto first = std::find_if(round.begin(), round.end(), outside_link);
    std::rotate(round.begin(), first + 1, round.end());
    const bool corner = creases_here + 2 * outside >= 3 || creased[vi];
    int wedge = 0;
    for (std::size_t i = 0; i < round.size();) {
      std::size_t j = i;
      int right_angles = 0;
      while (!outside_link(round[j])) right_angles += L(round[j++]).flag + 1;
      // Its rule is the original vertex's, whatever the side's faces (one face: a crease turning there).
      const int o = round[j];
      int id = v;
      if (wedge++ > 0) {
        id = static_cast<int>(x.vertices.size());
        TMeshVertex copy;
        copy.split_from = v;
        if (const int p = m.vertices[vi].primary; p >= 0) {
          copy.primary = static_cast<int>(x.points.size());
          x.points.push_back(m.points[static_cast<std::size_t>(p)]);
        }
        x.vertices.push_back(copy);
      }
      x.vertices[static_cast<std::size_t>(id)].crease_rule = corner ? CreaseRule::corner : dart ? CreaseRule::dart : CreaseRule::crease;
      for (std::size_t k = i; k <= j; ++k) x.links[static_cast<std::size_t>(round[k])].vertex = id;
      // The outside link: the outside's angle / 90 - 1 as flag, its previous link the one arriving along the
      // wedge's first link.
      TMeshLink& out = x.links[static_cast<std::size_t>(o)];
      out.flag = 3 - right_angles;
      out.prev = x_opp(round[i]);
      x.links[static_cast<std::size_t>(out.prev)].next = o;
      i = j + 1;
    }
  }
  return x;
}

std::vector<CreaseRule> boundary_rules(const TMesh& m) {
  const std::size_t nv = m.vertices.size();
  std::vector<int> faces(nv, 0), flags(nv, 0);
  std::vector<char> boundary(nv, 0);
  for (const TMeshLink& k : m.links) {
    if (k.vertex < 0) continue;
    const auto v = static_cast<std::size_t>(k.vertex);
    if (k.face >= 0 && m.live_face(k.face)) {
      ++faces[v];
      flags[v] += k.flag;
    } else {
      boundary[v] = 1;
    }
  }
  std::vector<CreaseRule> r(nv, CreaseRule::none);
  for (std::size_t v = 0; v < nv; ++v) {
    if (!m.vertices[v].live) continue;
    r[v] = m.vertices[v].crease_rule;  // inside the mesh: a cone point's corner
    if (!boundary[v]) continue;
    // The mesh's own boundary: a corner at a vertex of one quadrilateral corner.
    if (r[v] == CreaseRule::none) r[v] = faces[v] == 1 && flags[v] == 0 ? CreaseRule::corner : CreaseRule::crease;
  }
  return r;
}

std::vector<int> irregular_crease_vertices(const TMesh& m) {
  std::vector<int> out;
  if (m.end_conditions != EndConditions::subd_creases) return out;
  const std::vector<CreaseRule> rules = boundary_rules(m);
  std::vector<int> faces(m.vertices.size(), 0);
  for (const TMeshLink& k : m.links)
    if (k.vertex >= 0 && k.face >= 0 && m.live_face(k.face)) ++faces[static_cast<std::size_t>(k.vertex)];
  for (std::size_t v = 0; v < rules.size(); ++v)
    if ((rules[v] == CreaseRule::crease && faces[v] != 2) || (rules[v] == CreaseRule::corner && faces[v] != 1) || rules[v] == CreaseRule::dart)
      out.push_back(static_cast<int>(v));
  return out;
}

CreaseSingularities crease_singularities(const TMesh& m) {
  CreaseSingularities out;
  std::vector<char> boundary(m.vertices.size(), 0);
  for (const TMeshLink& k : m.links)
    if (k.vertex >= 0 && (k.face < 0 || !m.live_face(k.face))) boundary[static_cast<std::size_t>(k.vertex)] = 1;
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    if (!m.vertices[v].live) continue;
    const CreaseRule r = m.vertices[v].crease_rule;
    if (r == CreaseRule::dart) out.darts.push_back(static_cast<int>(v));
    if (r == CreaseRule::corner && !boundary[v]) out.cone_points.push_back(static_cast<int>(v));
  }
  return out;
}

}  // namespace trivar
