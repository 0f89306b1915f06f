#include "trivar/tspline/link_builder.hpp"

#include <string>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar {

int LinkBuilder::add_face(std::span<const int> loop, std::span<const char> straight, std::span<const double> interval) {
  const auto key = [](int a, int b) { return static_cast<long long>(a) * (1LL << 32) + b; };
  const int f = static_cast<int>(m_.faces.size()), base = static_cast<int>(m_.links.size()), n = static_cast<int>(loop.size());
  m_.faces.emplace_back();
  for (int i = 0; i < n; ++i) {
    TMeshLink k;
    k.prev = base + (i + n - 1) % n;
    k.next = base + (i + 1) % n;
    k.vertex = loop[static_cast<std::size_t>(i)];
    k.face = f;
    k.flag = straight[static_cast<std::size_t>(i)] ? 1 : 0;
    const int a = k.vertex, b = loop[static_cast<std::size_t>((i + 1) % n)];
    if (const auto it = by_ends_.find(key(b, a)); it != by_ends_.end() && !apart_.count(key(a, b))) {
      k.opp = it->second;
      k.edge = m_.links[static_cast<std::size_t>(it->second)].edge;
      m_.links[static_cast<std::size_t>(it->second)].opp = base + i;
    } else {
      k.edge = static_cast<int>(m_.intervals.size());
      m_.intervals.push_back(interval[static_cast<std::size_t>(i)]);
    }
    by_ends_[key(a, b)] = base + i;
    m_.links.push_back(k);
    m_.faces.back().push_back(base + i);
  }
  return f;
}

void LinkBuilder::close_boundary() {
  const int inner = static_cast<int>(m_.links.size());
  std::vector<int> turns(m_.vertices.size(), 0), outside_from(m_.vertices.size(), -1);
  for (int l = 0; l < inner; ++l) turns[static_cast<std::size_t>(m_.links[static_cast<std::size_t>(l)].vertex)] += m_.links[static_cast<std::size_t>(l)].flag + 1;
  for (int l = 0; l < inner; ++l) {
    if (m_.links[static_cast<std::size_t>(l)].opp >= 0) continue;
    TMeshLink o;
    o.vertex = m_.links[static_cast<std::size_t>(m_.links[static_cast<std::size_t>(l)].next)].vertex;
    o.opp = l;
    o.edge = m_.links[static_cast<std::size_t>(l)].edge;
    o.flag = 3 - turns[static_cast<std::size_t>(o.vertex)];
    const int id = static_cast<int>(m_.links.size());
    m_.links[static_cast<std::size_t>(l)].opp = id;
    require(outside_from[static_cast<std::size_t>(o.vertex)] < 0, [&] { return "T-mesh: vertex " + std::to_string(o.vertex) + " lies on two boundary arcs"; });
    outside_from[static_cast<std::size_t>(o.vertex)] = id;
    m_.links.push_back(o);
  }
  for (int o = inner; o < static_cast<int>(m_.links.size()); ++o) {
    const int next = outside_from[static_cast<std::size_t>(m_.links[static_cast<std::size_t>(m_.links[static_cast<std::size_t>(o)].opp)].vertex)];
    m_.links[static_cast<std::size_t>(o)].next = next;
    m_.links[static_cast<std::size_t>(next)].prev = o;
  }
}

}  // namespace trivar
