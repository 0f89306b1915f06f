#include "trivar/io/step/reference_cycles.hpp"

#include <algorithm>
#include <unordered_map>

namespace trivar::io::step {

namespace {

void collect(const Parameter& p, std::vector<std::uint64_t>& out) {
  if (const auto* r = p.get_if<Reference>()) out.push_back(r->id);
  else if (const auto* l = p.get_if<List>())
    for (const Parameter& q : l->items) collect(q, out);
  else if (const auto* t = p.get_if<Typed>())
    collect(t->value(), out);
}

std::vector<std::uint64_t> references_of(const Instance& i) {
  std::vector<std::uint64_t> out;
  for (const Record& r : i.records)
    for (const Parameter& p : r.params) collect(p, out);
  return out;
}

enum class Mark { open, done };

// Depth-first search from root; `marks` persists across roots so each instance is explored once.
std::vector<std::uint64_t> search(const ExchangeFile& file, std::uint64_t root,
                                  std::unordered_map<std::uint64_t, Mark>& marks) {
  struct Frame {
    std::uint64_t id;
    std::vector<std::uint64_t> refs;
    std::size_t next = 0;
  };
  if (marks.count(root) || !file.find(root)) return {};
  std::vector<Frame> stack;
  stack.push_back({root, references_of(*file.find(root))});
  marks[root] = Mark::open;
  while (!stack.empty()) {
    Frame& f = stack.back();
    if (f.next == f.refs.size()) {
      marks[f.id] = Mark::done;
      stack.pop_back();
      continue;
    }
    const std::uint64_t to = f.refs[f.next++];
    const auto it = marks.find(to);
    if (it != marks.end()) {
      if (it->second == Mark::done) continue;
      std::vector<std::uint64_t> cycle;  // `to` is on the stack: the cycle is the stack from there
      auto from = std::find_if(stack.begin(), stack.end(), [&](const Frame& g) { return g.id == to; });
      for (; from != stack.end(); ++from) cycle.push_back(from->id);
      cycle.push_back(to);
      return cycle;
    }
    const Instance* next = file.find(to);
    if (!next) continue;  // dropped by a filter, or dangling (check_references reports those)
    marks[to] = Mark::open;
    stack.push_back({to, references_of(*next)});
  }
  return {};
}

}  // namespace

std::vector<std::uint64_t> find_reference_cycle(const ExchangeFile& file, std::uint64_t root) {
  std::unordered_map<std::uint64_t, Mark> marks;
  return search(file, root, marks);
}

std::vector<std::uint64_t> find_reference_cycle(const ExchangeFile& file) {
  std::unordered_map<std::uint64_t, Mark> marks;
  for (const Instance& i : file.instances())
    if (auto cycle = search(file, i.id, marks); !cycle.empty()) return cycle;
  return {};
}

}  // namespace trivar::io::step
