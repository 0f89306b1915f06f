#include "trivar/tspline/exact_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace trivar {

ExactChart exact_chart(const TMesh& m, std::span<const int> faces, int seed, std::span<const int> members, int threads) {
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  TChart c = t_spline_chart(m, faces, seed, false);
  const auto at = [&](int v) {
    const TVertex& x = c.spline.image.vertices[static_cast<std::size_t>(c.vertex[static_cast<std::size_t>(v)])];
    return std::array<double, 2>{x.s, x.t};
  };
  // The chart's edges with a face outside it on the other side, and that side (along `axis`, `sign`).
  struct Border {
    Box<2> box;
    int axis, sign;
  };
  std::vector<Border> border;
  for (const TMeshLink& k : m.links) {
    if (k.face < 0 || c.face[static_cast<std::size_t>(k.face)] < 0) continue;
    const int g = L(k.opp).face;
    if (g < 0 || c.face[static_cast<std::size_t>(g)] >= 0) continue;
    const auto p = at(k.vertex), q = at(L(k.opp).vertex);
    // The chart's faces lie left of their links: a link going north has the outside east of it, one going east south.
    const int axis = p[0] == q[0] ? 0 : 1, sign = axis == 0 ? (q[1] > p[1] ? 1 : -1) : (q[0] > p[0] ? -1 : 1);
    border.push_back({{{std::min(p[0], q[0]), std::min(p[1], q[1])}, {std::max(p[0], q[0]), std::max(p[1], q[1])}}, axis, sign});
  }
  ExactChart out;
  std::vector<Box<2>> boxes;
  for (int g : members) {
    std::vector<int> corners;
    for (int l : m.faces[static_cast<std::size_t>(g)])
      if (L(l).flag == 0) corners.push_back(L(l).vertex);
    const auto o = at(corners[0]), a = at(corners[1]), b = at(corners[3]), x = at(corners[2]);
    out.frames.push_back({o, {a[0] - o[0], a[1] - o[1]}, {b[0] - o[0], b[1] - o[1]}});
    boxes.push_back({{std::min(o[0], x[0]), std::min(o[1], x[1])}, {std::max(o[0], x[0]), std::max(o[1], x[1])}});
  }
  // The members' elements alone: the chart's other faces are served otherwise (its crease and star faces) or by
  // other charts, and their elements were most of its build.
  out.surface = std::make_unique<TSplineSurface>(c.spline, boxes, threads);
  out.cut.assign(members.size(), 0);
  out.whole.assign(members.size(), 0);
  for (std::size_t j = 0; j < boxes.size(); ++j) {
    const Box<2>& b = boxes[j];
    const int e = out.surface->locate({0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1])});
    out.whole[j] = e >= 0 && out.surface->elements()[static_cast<std::size_t>(e)].lo == b.lo && out.surface->elements()[static_cast<std::size_t>(e)].hi == b.hi;
  }
  const auto overlap = [](const Box<2>& a, const Box<2>& b) {
    return a.lo[0] < b.hi[0] && b.lo[0] < a.hi[0] && a.lo[1] < b.hi[1] && b.lo[1] < a.hi[1];
  };
  // A border edge through a support's interior cuts the function. A ray that reaches the border stops there as at the
  // mesh's boundary, where the mesh's ray goes on: its knot repeats (at the end of the knot vector, on a border edge
  // with the outside beyond it) in place of the knot lines beyond. Of the knots t_0 .. t_(p+1), the piece on the span
  // from t_j depends on t_(j-p+1) .. t_(j+p) only, so with the first repeat t_i at the upper end the function changes
  // above t_(i+1-p), with the last repeat t_i at the lower end below t_(i+p-1), across its whole support; the rays
  // that end at the border without a repeat meet its edge in the chart as in the mesh. Beyond the border, where the
  // mesh's function reaches on, the chart's plane need not be the mesh's (faces across a notch round a star point).
  const auto before = [](const Border& a, const Border& b) {
    return std::tuple(a.axis, a.sign, a.box.lo[static_cast<std::size_t>(a.axis)]) < std::tuple(b.axis, b.sign, b.box.lo[static_cast<std::size_t>(b.axis)]);
  };
  std::sort(border.begin(), border.end(), before);
  const auto stops = [&](int axis, int sign, double x, double line) {
    Border probe{{}, axis, sign};
    probe.box.lo[static_cast<std::size_t>(axis)] = x;
    const auto [first, last] = std::equal_range(border.begin(), border.end(), probe, before);
    return std::any_of(first, last, [&](const Border& e) {
      return e.box.lo[static_cast<std::size_t>(1 - axis)] <= line && line <= e.box.hi[static_cast<std::size_t>(1 - axis)];
    });
  };
  // The members by their least s, to visit those a box can overlap; a function off their hull cuts none.
  std::vector<std::size_t> by_s(boxes.size());
  std::iota(by_s.begin(), by_s.end(), std::size_t{0});
  std::sort(by_s.begin(), by_s.end(), [&](std::size_t a, std::size_t b) { return boxes[a].lo[0] < boxes[b].lo[0]; });
  Box<2> hull = boxes.empty() ? Box<2>{} : boxes.front();
  double widest = 0;
  for (const Box<2>& b : boxes) {
    for (std::size_t k = 0; k < 2; ++k) {
      hull.lo[k] = std::min(hull.lo[k], b.lo[k]);
      hull.hi[k] = std::max(hull.hi[k], b.hi[k]);
    }
    widest = std::max(widest, b.hi[0] - b.lo[0]);
  }
  const auto cut_where = [&](const Box<2>& changed) {
    auto j = std::lower_bound(by_s.begin(), by_s.end(), changed.lo[0] - widest, [&](std::size_t i, double x) { return boxes[i].lo[0] < x; });
    for (; j != by_s.end() && boxes[*j].lo[0] < changed.hi[0]; ++j)
      if (overlap(changed, boxes[*j])) out.cut[*j] = 1;
  };
  const Ints<2>& degrees = out.surface->degrees();
  for (const auto& f : out.surface->basis()) {
    const Box<2> sb = f.support();
    if (!overlap(sb, hull)) continue;
    if (std::any_of(border.begin(), border.end(), [&](const Border& e) { return overlap(e.box, sb); })) {
      cut_where(sb);
      continue;
    }
    for (int k = 0; k < 2; ++k) {
      const std::vector<double>& t = f.knots[static_cast<std::size_t>(k)];
      const int p = degrees[static_cast<std::size_t>(k)], n = p + 2;
      for (int sign : {-1, 1}) {
        const int end = sign < 0 ? 0 : n - 1;
        const double x = t[static_cast<std::size_t>(end)];
        if (t[static_cast<std::size_t>(end - sign)] != x) continue;
        int r = end - sign;  // the repeat of the end knot farthest from the end
        while (r - sign >= 0 && r - sign < n && t[static_cast<std::size_t>(r - sign)] == x) r -= sign;
        const std::vector<double>& o = f.knots[static_cast<std::size_t>(1 - k)];
        const int q = degrees[static_cast<std::size_t>(1 - k)];
        if (!stops(k, sign, x, 0.5 * (o[static_cast<std::size_t>((q + 1) / 2)] + o[static_cast<std::size_t>((q + 2) / 2)]))) continue;
        Box<2> changed = sb;
        (sign < 0 ? changed.hi : changed.lo)[static_cast<std::size_t>(k)] = t[static_cast<std::size_t>(std::clamp(r - sign * (p - 1), 0, n - 1))];
        cut_where(changed);
      }
    }
  }
  return out;
}

std::vector<int> embedded_faces(const TMesh& m, int seed, std::span<const char> allowed) {
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const auto interval = [&](int l) { return m.intervals[static_cast<std::size_t>(L(l).edge)]; };
  double extent = 0;
  for (double d : m.intervals) extent += d;
  const double tol = 1e-9 * std::max(extent, 1e-300);
  std::vector<int> dir(m.links.size(), -1);  // compass direction in the chart (TDir), as t_spline_chart's
  std::vector<std::array<double, 2>> pos(m.vertices.size());
  std::vector<char> placed(m.vertices.size(), 0), decided(m.faces.size(), 0);
  // The faces taken, as boxes in a hash grid of cells of the seed's longer side, for the overlap test.
  std::vector<Box<2>> taken;
  std::vector<int> seen;  // per box taken, the last face whose test met it
  int stamp = 0;
  std::unordered_map<std::int64_t, std::vector<int>> cells;
  double cell = 0;
  // With the boxes that touch it; the cells offset by half their side, so that a box of the seed's size on the
  // knot lines meets 2 x 2 cells, not 3 x 3.
  const auto cell_range = [&](const Box<2>& b, int k) {
    return std::array<std::int64_t, 2>{static_cast<std::int64_t>(std::floor((b.lo[static_cast<std::size_t>(k)] - tol) / cell + 0.5)),
                                       static_cast<std::int64_t>(std::floor((b.hi[static_cast<std::size_t>(k)] + tol) / cell + 0.5))};
  };
  const auto key = [](std::int64_t i, std::int64_t j) { return i * (std::int64_t{1} << 32) + j; };
  std::vector<int> out, loop_dir;
  std::vector<std::array<double, 2>> loop_pos;
  // (face, its link whose direction and first vertex are known, that direction, that vertex's position)
  struct Entry {
    int face, link, dir;
    std::array<double, 2> at;
  };
  std::vector<Entry> queue{{seed, m.first_corner(seed), static_cast<int>(TDir::east), {0, 0}}};
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const Entry e = queue[head];
    if (decided[static_cast<std::size_t>(e.face)]) continue;
    decided[static_cast<std::size_t>(e.face)] = 1;
    const auto& loop = m.faces[static_cast<std::size_t>(e.face)];
    const std::size_t n = loop.size(), start = static_cast<std::size_t>(std::find(loop.begin(), loop.end(), e.link) - loop.begin());
    // The face's layout from the entering link, turning left at every corner (as t_spline_chart's).
    loop_dir.assign(n, -1);
    loop_pos.assign(n, {});
    int d = e.dir;
    std::array<double, 2> p = e.at;
    Box<2> box{p, p};
    bool fits = true;
    for (std::size_t i = 0; i < n && fits; ++i) {
      const int l = loop[(start + i) % n], v = L(l).vertex;
      if (i > 0 && L(l).flag == 0) d = (d + 1) % 4;
      loop_dir[i] = d;
      loop_pos[i] = p;
      const int back = dir[static_cast<std::size_t>(L(l).opp)];
      fits = (!placed[static_cast<std::size_t>(v)] || (std::abs(pos[static_cast<std::size_t>(v)][0] - p[0]) <= tol &&
                                                       std::abs(pos[static_cast<std::size_t>(v)][1] - p[1]) <= tol)) &&
             (back < 0 || back == tdir_opposite(d));
      p[static_cast<std::size_t>(tdir_axis(d))] += tdir_sign(d) * interval(l);
      for (std::size_t k = 0; k < 2; ++k) {
        box.lo[k] = std::min(box.lo[k], p[k]);
        box.hi[k] = std::max(box.hi[k], p[k]);
      }
    }
    fits = fits && std::abs(p[0] - e.at[0]) <= tol && std::abs(p[1] - e.at[1]) <= tol;
    if (cell == 0) cell = std::max({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], tol});
    const auto ci = cell_range(box, 0), cj = cell_range(box, 1);
    ++stamp;
    for (std::int64_t i = ci[0]; i <= ci[1] && fits; ++i)
      for (std::int64_t j = cj[0]; j <= cj[1] && fits; ++j)
        if (const auto it = cells.find(key(i, j)); it != cells.end())
          for (int t : it->second) {
            if (seen[static_cast<std::size_t>(t)] == stamp) continue;  // met in another cell
            seen[static_cast<std::size_t>(t)] = stamp;
            // The boxes' common part: an overlap, or a side or corner the faces must share in the mesh as well (else
            // the chart's rays would pass from one to the other: the two sides of a sharp crease, a layout round a
            // boundary vertex whose faces' angles sum to 360 degrees).
            const Box<2>& b = taken[static_cast<std::size_t>(t)];
            const double wx = std::min(box.hi[0], b.hi[0]) - std::max(box.lo[0], b.lo[0]),
                         wy = std::min(box.hi[1], b.hi[1]) - std::max(box.lo[1], b.lo[1]);
            if (wx < -tol || wy < -tol) continue;
            const int g = out[static_cast<std::size_t>(t)];
            const bool side = wx > tol || wy > tol;
            fits = fits && !(wx > tol && wy > tol) &&
                   std::any_of(loop.begin(), loop.end(), [&](int l) {
                     return side ? L(L(l).opp).face == g : std::any_of(m.faces[static_cast<std::size_t>(g)].begin(), m.faces[static_cast<std::size_t>(g)].end(),
                                                                       [&](int k) { return L(k).vertex == L(l).vertex; });
                   });
          }
    if (!fits) continue;
    for (std::int64_t i = ci[0]; i <= ci[1]; ++i)
      for (std::int64_t j = cj[0]; j <= cj[1]; ++j) cells[key(i, j)].push_back(static_cast<int>(taken.size()));
    taken.push_back(box);
    seen.push_back(0);
    out.push_back(e.face);
    for (std::size_t i = 0; i < n; ++i) {
      const int l = loop[(start + i) % n], v = L(l).vertex, o = L(l).opp;
      placed[static_cast<std::size_t>(v)] = 1;
      pos[static_cast<std::size_t>(v)] = loop_pos[i];
      dir[static_cast<std::size_t>(l)] = loop_dir[i];
      dir[static_cast<std::size_t>(o)] = tdir_opposite(loop_dir[i]);
      const int g = L(o).face;
      // The opposite link leaves the far end of l, laid out at the next position of the loop.
      if (g >= 0 && allowed[static_cast<std::size_t>(g)] && !decided[static_cast<std::size_t>(g)])
        queue.push_back({g, o, tdir_opposite(loop_dir[i]), loop_pos[(i + 1) % n]});
    }
  }
  return out;
}

}  // namespace trivar
