#include "trivar/io/step/reference_cycles.hpp"

#include <algorithm>
#include <optional>
#include <unordered_map>
#include <unordered_set>

namespace trivar::io::step {

void collect_references(const Parameter& p, std::vector<std::uint64_t>& out) {
  if (const auto* r = p.get_if<Reference>()) out.push_back(r->id);
  else if (const auto* l = p.get_if<List>())
    for (const Parameter& q : l->items) collect_references(q, out);
  else if (const auto* t = p.get_if<Typed>())
    collect_references(t->value(), out);
}

namespace {

bool has_references(const Parameter& p) {
  if (p.get_if<Reference>()) return true;
  if (const auto* l = p.get_if<List>())
    return std::any_of(l->items.begin(), l->items.end(), [](const Parameter& q) { return has_references(q); });
  if (const auto* t = p.get_if<Typed>()) return has_references(t->value());
  return false;
}

// Most instances of a CAD file (points, directions) refer to nothing and cannot be on a cycle.
bool has_references(const Instance& i) {
  for (const Record& r : i.records)
    for (const Parameter& p : r.params)
      if (has_references(p)) return true;
  return false;
}

// The reference graph of kept and skipped instances alike.
class Graph {
public:
  // `referring`: when given, the only instances that hold references (the rest are skipped unlooked-at).
  explicit Graph(const ExchangeFile& file, const std::vector<std::uint64_t>* referring = nullptr) : file_(file) {
    for (std::size_t k = 0; k < file.skipped_instances().size(); ++k) skipped_.emplace(file.skipped_instances()[k].id, k);
    if (referring) referring_.emplace(referring->begin(), referring->end());  // points are never looked up
  }
  // Empty for an instance that refers to nothing and for an id that names no instance.
  std::vector<std::uint64_t> references_of(std::uint64_t id) const {
    std::vector<std::uint64_t> out;
    if (referring_ && !referring_->contains(id)) return out;
    if (const Instance* i = file_.find(id)) {
      for (const Record& r : i->records)
        for (const Parameter& p : r.params) collect_references(p, out);
    } else if (const auto it = skipped_.find(id); it != skipped_.end()) {
      const auto refs = file_.skipped_references(it->second);
      out.assign(refs.begin(), refs.end());
    }
    return out;
  }

private:
  const ExchangeFile& file_;
  std::unordered_map<std::uint64_t, std::size_t> skipped_;
  std::optional<std::unordered_set<std::uint64_t>> referring_;
};

enum class Mark { open, done };

// Depth-first search from root; `marks` persists across roots so each instance is explored once.
std::vector<std::uint64_t> search(const Graph& graph, std::uint64_t root,
                                  std::unordered_map<std::uint64_t, Mark>& marks) {
  struct Frame {
    std::uint64_t id;
    std::vector<std::uint64_t> refs;
    std::size_t next = 0;
  };
  if (marks.count(root)) return {};
  std::vector<Frame> stack;
  stack.push_back({root, graph.references_of(root)});
  if (stack.back().refs.empty()) return {};  // a leaf (most instances: points) needs no mark
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
    std::vector<std::uint64_t> refs = graph.references_of(to);
    if (refs.empty()) continue;  // a leaf, or dangling (check_references reports those)
    marks[to] = Mark::open;
    stack.push_back({to, std::move(refs)});
  }
  return {};
}

}  // namespace

std::vector<std::uint64_t> find_reference_cycle(const ExchangeFile& file, std::uint64_t root) {
  std::unordered_map<std::uint64_t, Mark> marks;
  return search(Graph(file), root, marks);
}

std::vector<std::uint64_t> find_reference_cycle(const ExchangeFile& file, const std::vector<std::uint64_t>& roots) {
  const Graph graph(file, &roots);
  std::unordered_map<std::uint64_t, Mark> marks;
  for (const std::uint64_t root : roots)
    if (auto cycle = search(graph, root, marks); !cycle.empty()) return cycle;
  return {};
}

std::vector<std::uint64_t> find_reference_cycle(const ExchangeFile& file) {
  std::vector<std::uint64_t> roots;
  for (const Instance& i : file.instances())
    if (has_references(i)) roots.push_back(i.id);
  for (std::size_t k = 0; k < file.skipped_instances().size(); ++k)
    if (!file.skipped_references(k).empty()) roots.push_back(file.skipped_instances()[k].id);
  return find_reference_cycle(file, roots);
}

}  // namespace trivar::io::step
