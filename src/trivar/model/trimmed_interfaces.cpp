#include "trivar/model/trimmed_interfaces.hpp"

#include <algorithm>
#include <map>

namespace trivar {

std::vector<long> paired_trimming_triangles(const VModel& model, std::vector<long>& first_triangle) {
  // Vertices are merged by their exact coordinates, so matching corners become equal ids.
  std::map<std::array<double, 3>, int> ids;
  struct Tri {
    std::array<int, 3> v;
    int cell;
  };
  std::vector<Tri> tris;
  first_triangle.assign(static_cast<std::size_t>(model.num_cells()) + 1, 0);
  for (int ci = 0; ci < model.num_cells(); ++ci) {
    first_triangle[static_cast<std::size_t>(ci)] = static_cast<long>(tris.size());
    const VCell& c = model.cell(ci);
    if (!c.is_trimmed()) continue;
    const TriangleMesh& m = c.trim()->boundary().mesh;
    std::vector<int> local(m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i)
      local[i] = ids.try_emplace(m.vertices[i], static_cast<int>(ids.size())).first->second;
    for (const auto& t : m.triangles) tris.push_back({{local[t[0]], local[t[1]], local[t[2]]}, ci});
  }
  first_triangle.back() = static_cast<long>(tris.size());
  // A triangle by its corners in rotation-normalised order; the opposite orientation has the last two swapped.
  const auto key = [](std::array<int, 3> v) {
    std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
    return v;
  };
  std::map<std::array<int, 3>, std::vector<long>> by_key;
  for (std::size_t t = 0; t < tris.size(); ++t) by_key[key(tris[t].v)].push_back(static_cast<long>(t));
  std::vector<long> twin(tris.size(), -1);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    if (twin[t] >= 0) continue;
    const auto& v = tris[t].v;
    const auto it = by_key.find(key({v[0], v[2], v[1]}));
    if (it == by_key.end()) continue;
    for (long o : it->second)
      if (twin[static_cast<std::size_t>(o)] < 0 && tris[static_cast<std::size_t>(o)].cell != tris[t].cell) {
        twin[t] = o;
        twin[static_cast<std::size_t>(o)] = static_cast<long>(t);
        break;
      }
  }
  return twin;
}

TrimmedInterfaces trimmed_interfaces(const VModel& model) {
  std::vector<long> first;
  const std::vector<long> twin = paired_trimming_triangles(model, first);
  const int n = model.num_cells();
  // The cell and face of a global triangle index.
  const auto owner = [&](long t) {
    const int c = static_cast<int>(std::upper_bound(first.begin(), first.end(), t) - first.begin()) - 1;
    const auto& tf = model.cell(c).trim()->boundary().triangle_face;
    return TrimmedFaceRef{c, tf[static_cast<std::size_t>(t - first[static_cast<std::size_t>(c)])]};
  };
  TrimmedInterfaces r;
  r.twin.resize(static_cast<std::size_t>(n));
  r.neighbours.resize(static_cast<std::size_t>(n));
  for (int c = 0; c < n; ++c) {
    if (!model.cell(c).is_trimmed()) continue;
    const TrimmedBoundary& b = model.cell(c).trim()->boundary();
    // Per face: the one face its paired triangles lie on ({-2, -2} once they lie on several), and whether some
    // triangle of it is unpaired.
    std::vector<TrimmedFaceRef> other(b.faces.size());
    std::vector<char> paired(b.faces.size(), 0), unpaired(b.faces.size(), 0);
    for (std::size_t t = 0; t < b.triangle_face.size(); ++t) {
      const auto f = static_cast<std::size_t>(b.triangle_face[t]);
      const long o = twin[static_cast<std::size_t>(first[static_cast<std::size_t>(c)]) + t];
      if (o < 0) {
        unpaired[f] = 1;
        continue;
      }
      const TrimmedFaceRef of = owner(o);
      if (!paired[f]) other[f] = of;
      else if (!(other[f] == of)) other[f] = {-2, -2};
      paired[f] = 1;
    }
    r.twin[static_cast<std::size_t>(c)].assign(b.faces.size(), {});
    for (std::size_t f = 0; f < b.faces.size(); ++f) {
      const TrimmedFaceRef self{c, static_cast<int>(f)};
      if (!paired[f]) {
        r.surfaces.push_back({self, {}});
        ++r.boundary;
      } else if (unpaired[f] || other[f].cell < 0) {
        r.non_conforming.push_back(self);
      } else {
        r.twin[static_cast<std::size_t>(c)][f] = other[f];
      }
    }
  }
  // A pair counts as shared when each side names the other (the twin's own triangles may be partly unpaired).
  for (int c = 0; c < n; ++c)
    for (std::size_t f = 0; f < r.twin[static_cast<std::size_t>(c)].size(); ++f) {
      TrimmedFaceRef& o = r.twin[static_cast<std::size_t>(c)][f];
      if (o.cell < 0) continue;
      const auto& back = r.twin[static_cast<std::size_t>(o.cell)];
      if (!(back[static_cast<std::size_t>(o.face)] == TrimmedFaceRef{c, static_cast<int>(f)})) {
        r.non_conforming.push_back({c, static_cast<int>(f)});
        o = {};
        continue;
      }
      r.neighbours[static_cast<std::size_t>(c)].push_back(o.cell);
      if (c < o.cell) {
        r.surfaces.push_back({TrimmedFaceRef{c, static_cast<int>(f)}, o});
        ++r.shared;
      }
    }
  // Boundary V-surfaces after the shared ones.
  std::stable_partition(r.surfaces.begin(), r.surfaces.end(), [](const auto& s) { return s[1].cell >= 0; });
  for (auto& nb : r.neighbours) {
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  }
  return r;
}

}  // namespace trivar
