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

TMesh split_creases(const TMesh& m) {
  const std::vector<int> creases = crease_edges(m);
  if (creases.empty()) return m;
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
    int creases_here = 0, outside = 0, right_angles_round = 0;
    for (int l : leaving[vi]) {
      if (crease[static_cast<std::size_t>(L(l).edge)]) ++creases_here;
      if (!in_face(m, l)) ++outside;
      else right_angles_round += L(l).flag + 1;
    }
    if (creases_here == 0) continue;
    if (outside == 0 && creases_here == 1)
      fail(v, "ends its crease inside the mesh (a dart: subdivision smooths there, so the crease cannot be cut open); a crease runs from boundary to boundary, closes, or meets other creases");
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
    const bool corner = creases_here + 2 * outside >= 3;
    int wedge = 0;
    for (std::size_t i = 0; i < round.size();) {
      std::size_t j = i;
      int right_angles = 0;
      while (!outside_link(round[j])) right_angles += L(round[j++]).flag + 1;
      const int o = round[j];
      if (corner && right_angles != 1)
        fail(v, "is a corner of " + std::to_string(creases_here + 2 * outside) + " sharp edges with a side of " + std::to_string(90 * right_angles) +
                    " degrees of faces; crease corners are evaluated with one quadrilateral per side (90 degrees)");
      if (!corner && right_angles != 2)
        fail(v, "has a side of " + std::to_string(90 * right_angles) + " degrees of faces (" +
                    (right_angles_round == 4 ? "the crease turns there" : "a star point on the crease") +
                    "); a crease is evaluated running straight through vertices of four faces");
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

}  // namespace trivar
