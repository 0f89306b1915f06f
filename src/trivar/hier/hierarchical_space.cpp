#include "trivar/hier/hierarchical_space.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

#include "trivar/core/error.hpp"
#include "trivar/hier/local_tensor.hpp"
#include "trivar/spline/derivative_index.hpp"

namespace trivar {

const char* to_string(HierarchicalBasis b) { return b == HierarchicalBasis::hb ? "hb" : "thb"; }

namespace {

bool contains(const std::vector<CellKey>& sorted, CellKey key) {
  return std::binary_search(sorted.begin(), sorted.end(), key);
}

// Calls f(index) for every multi-index lo <= index < hi, u fastest (so packed keys ascend).
template <int D, class F>
void for_each_index(const Ints<D>& lo, const Ints<D>& hi, F&& f) {
  for (int k = 0; k < D; ++k)
    if (lo[k] >= hi[k]) return;
  Ints<D> i = lo;
  while (true) {
    f(std::as_const(i));
    int k = 0;
    while (k < D && ++i[k] == hi[k]) i[k] = lo[k], ++k;
    if (k == D) return;
  }
}

// Whether pred(index) holds for every multi-index lo <= index < hi (stops at the first that fails).
template <int D, class Pred>
bool all_of_index(const Ints<D>& lo, const Ints<D>& hi, Pred&& pred) {
  for (int k = 0; k < D; ++k)
    if (lo[k] >= hi[k]) return true;
  Ints<D> i = lo;
  while (true) {
    if (!pred(std::as_const(i))) return false;
    int k = 0;
    while (k < D && ++i[k] == hi[k]) i[k] = lo[k], ++k;
    if (k == D) return true;
  }
}

// Adds the sorted unique keys to the sorted unique set.
void merge_into(std::vector<CellKey>& set, const std::vector<CellKey>& keys) {
  std::vector<CellKey> merged;
  merged.reserve(set.size() + keys.size());
  std::set_union(set.begin(), set.end(), keys.begin(), keys.end(), std::back_inserter(merged));
  set = std::move(merged);
}

}  // namespace

template <int D>
HierarchicalSpace<D>::HierarchicalSpace(TensorHierarchy<D> hierarchy, HierarchicalBasis basis)
    : h_(std::move(hierarchy)), basis_(basis) {
  local_size_ = 1;
  for (int k = 0; k < D; ++k) local_size_ *= h_.degree(k) + 1;
  rebuild();
}

template <int D>
bool HierarchicalSpace<D>::cell_in_domain(int level, const Ints<D>& c) const {
  if (level == 0) return true;
  return level < static_cast<int>(domain_.size()) && contains(domain_[static_cast<std::size_t>(level)], pack_key<D>(c));
}

template <int D>
bool HierarchicalSpace<D>::support_in(int level, const Ints<D>& f, const std::vector<CellKey>& cells) const {
  Ints<D> lo, hi;
  for (int k = 0; k < D; ++k) {
    lo[k] = h_.axis(level, k).first_cell(f[k]);
    hi[k] = h_.axis(level, k).end_cell(f[k]);
  }
  return all_of_index<D>(lo, hi, [&](const Ints<D>& c) { return contains(cells, pack_key<D>(c)); });
}

template <int D>
bool HierarchicalSpace<D>::support_in_domain(int level, const Ints<D>& f) const {
  if (level == 0) return true;
  if (level >= static_cast<int>(domain_.size())) return false;
  if (!aligned_) return support_in(level, f, domain_[static_cast<std::size_t>(level)]);
  // Aligned: the support's cells lie in Omega^level when their parents are covered cells of the level below
  // (a few lookups in a smaller set instead of one per cell).
  Ints<D> lo, hi;
  for (int k = 0; k < D; ++k) {
    const HierarchyAxis& a = h_.axis(level, k);
    lo[k] = h_.parent(level, k, a.first_cell(f[k]));
    hi[k] = h_.parent(level, k, a.end_cell(f[k]) - 1) + 1;
  }
  const auto& below = refined_[static_cast<std::size_t>(level) - 1];
  return all_of_index<D>(lo, hi, [&](const Ints<D>& c) { return contains(below, pack_key<D>(c)); });
}

template <int D>
void HierarchicalSpace<D>::rebuild() {
  if (domain_.empty()) domain_.resize(1);
  while (domain_.size() > 1 && domain_.back().empty()) domain_.pop_back();
  const int L = static_cast<int>(domain_.size());
  const auto level_of = [](auto& v, int l) -> auto& { return v[static_cast<std::size_t>(l)]; };
  // Covered and split cells, finest level first (a cell is split when a finer domain cell lies inside it).
  refined_.assign(static_cast<std::size_t>(L), {});
  split_.assign(static_cast<std::size_t>(L), {});
  for (int l = L - 2; l >= 0; --l) {
    const std::vector<CellKey>& finer = level_of(domain_, l + 1);
    std::vector<CellKey> parents;
    for (CellKey key : finer) parents.push_back(pack_key<D>(parent(l + 1, unpack_key<D>(key))));
    std::sort(parents.begin(), parents.end());
    parents.erase(std::unique(parents.begin(), parents.end()), parents.end());
    for (CellKey key : parents) {
      const Ints<D> c = unpack_key<D>(key);
      if (all_of_index<D>(first_children(l, c), end_children(l, c),
                          [&](const Ints<D>& child) { return contains(finer, pack_key<D>(child)); }))
        level_of(refined_, l).push_back(key);
    }
    for (CellKey key : level_of(split_, l + 1)) parents.push_back(pack_key<D>(parent(l + 1, unpack_key<D>(key))));
    std::sort(parents.begin(), parents.end());
    parents.erase(std::unique(parents.begin(), parents.end()), parents.end());
    level_of(split_, l) = std::move(parents);
  }
  aligned_ = true;
  for (int l = 1; l < L && aligned_; ++l) {
    std::size_t children = 0;
    for (CellKey key : level_of(refined_, l - 1)) {
      const Ints<D> lo = first_children(l - 1, unpack_key<D>(key)), hi = end_children(l - 1, unpack_key<D>(key));
      std::size_t n = 1;
      for (int k = 0; k < D; ++k) n *= static_cast<std::size_t>(hi[k] - lo[k]);
      children += n;
    }
    aligned_ = children == level_of(domain_, l).size();
  }
  active_.assign(static_cast<std::size_t>(L), {});
  inside_.assign(static_cast<std::size_t>(L), {});
  leaf_keys_.assign(static_cast<std::size_t>(L), {});
  for (int l = 0; l < L; ++l) {
    const std::vector<CellKey>& refined = level_of(refined_, l);
    const std::vector<CellKey>& split = level_of(split_, l);
    auto& active = level_of(active_, l);
    auto& leaves = level_of(leaf_keys_, l);
    if (l == 0) {
      Ints<D> zero{}, nf, nc;
      for (int k = 0; k < D; ++k) {
        nf[k] = h_.axis(0, k).num_functions();
        nc[k] = h_.axis(0, k).num_cells();
      }
      for_each_index<D>(zero, nf, [&](const Ints<D>& f) {
        if (refined.empty() || !support_in(0, f, refined)) active.push_back(pack_key<D>(f));
      });
      for_each_index<D>(zero, nc, [&](const Ints<D>& c) {
        const CellKey key = pack_key<D>(c);
        if (!contains(split, key)) leaves.push_back(key);
      });
      continue;
    }
    // Cells of the mesh of level l: the children of the split cells of level l - 1.
    std::vector<CellKey> cells;
    for (CellKey key : level_of(split_, l - 1))
      for_each_index<D>(first_children(l - 1, unpack_key<D>(key)), end_children(l - 1, unpack_key<D>(key)),
                        [&](const Ints<D>& c) { cells.push_back(pack_key<D>(c)); });
    std::sort(cells.begin(), cells.end());
    for (CellKey key : cells)
      if (!contains(split, key)) leaves.push_back(key);
    // Functions with support in Omega^l have it among the functions on the domain's cells.
    std::vector<CellKey> candidates;
    for (CellKey key : level_of(domain_, l)) {
      const Ints<D> c = unpack_key<D>(key);
      Ints<D> lo, hi;
      for (int k = 0; k < D; ++k) {
        hi[k] = h_.axis(l, k).span(c[k]) + 1;
        lo[k] = hi[k] - 1 - h_.degree(k);
      }
      for_each_index<D>(lo, hi, [&](const Ints<D>& f) { candidates.push_back(pack_key<D>(f)); });
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    auto& inside = level_of(inside_, l);
    for (CellKey key : candidates) {
      const Ints<D> f = unpack_key<D>(key);
      if (!support_in_domain(l, f)) continue;
      inside.push_back(key);
      if (refined.empty() || !support_in(l, f, refined)) active.push_back(key);
    }
  }
  // Levels whose domain holds no active function still carry leaves (a THB space may have empty levels).
  offset_.assign(1, 0);
  leaf_offset_.assign(1, 0);
  leaves_.clear();
  for (int l = 0; l < L; ++l) {
    offset_.push_back(offset_.back() + static_cast<int>(level_of(active_, l).size()));
    leaf_offset_.push_back(leaf_offset_.back() + static_cast<int>(level_of(leaf_keys_, l).size()));
    for (CellKey key : level_of(leaf_keys_, l)) leaves_.emplace_back(l, key);
  }
}

template <int D>
HierarchicalFunction<D> HierarchicalSpace<D>::function(int id) const {
  require(id >= 0 && id < num_basis(), [&] { return "hier: no function " + std::to_string(id); });
  const int l = static_cast<int>(std::upper_bound(offset_.begin(), offset_.end(), id) - offset_.begin()) - 1;
  return {l, unpack_key<D>(active_[static_cast<std::size_t>(l)][static_cast<std::size_t>(id - offset_[static_cast<std::size_t>(l)])])};
}

template <int D>
int HierarchicalSpace<D>::find_function(int level, const Ints<D>& index) const {
  if (level < 0 || level >= num_levels()) return -1;
  const auto& a = active_[static_cast<std::size_t>(level)];
  const auto it = std::lower_bound(a.begin(), a.end(), pack_key<D>(index));
  if (it == a.end() || *it != pack_key<D>(index)) return -1;
  return offset_[static_cast<std::size_t>(level)] + static_cast<int>(it - a.begin());
}

template <int D>
Box<D> HierarchicalSpace<D>::function_support(int id) const {
  const HierarchicalFunction<D> f = function(id);
  Box<D> b;
  for (int k = 0; k < D; ++k) {
    const HierarchyAxis& a = h_.axis(f.level, k);
    b.lo[k] = a.brk(a.first_cell(f.index[k]));
    b.hi[k] = a.brk(a.end_cell(f.index[k]));
  }
  return b;
}

template <int D>
HierarchicalCell<D> HierarchicalSpace<D>::element(int e) const {
  require(e >= 0 && e < num_elements(), [&] { return "hier: no element " + std::to_string(e); });
  const auto& [l, key] = leaves_[static_cast<std::size_t>(e)];
  return {l, unpack_key<D>(key)};
}

template <int D>
Box<D> HierarchicalSpace<D>::element_box(int e) const {
  const HierarchicalCell<D> c = element(e);
  return h_.cell_box(c.level, c.index);
}

template <int D>
std::vector<Box<D>> HierarchicalSpace<D>::element_boxes() const {
  std::vector<Box<D>> out(leaves_.size());
  for (int e = 0; e < num_elements(); ++e) out[static_cast<std::size_t>(e)] = element_box(e);
  return out;
}

template <int D>
int HierarchicalSpace<D>::find_leaf(int level, const Ints<D>& cell) const {
  if (level < 0 || level >= num_levels()) return -1;
  const auto& keys = leaf_keys_[static_cast<std::size_t>(level)];
  const CellKey key = pack_key<D>(cell);
  const auto it = std::lower_bound(keys.begin(), keys.end(), key);
  if (it == keys.end() || *it != key) return -1;
  return leaf_offset_[static_cast<std::size_t>(level)] + static_cast<int>(it - keys.begin());
}

template <int D>
int HierarchicalSpace<D>::find_element(const Param<D>& u) const {
  Ints<D> c;
  for (int k = 0; k < D; ++k) c[k] = h_.axis(0, k).cell_of(u[k]);
  int l = 0;
  while (l < static_cast<int>(split_.size()) && contains(split_[static_cast<std::size_t>(l)], pack_key<D>(c))) {
    ++l;
    for (int k = 0; k < D; ++k) {
      // The child along k containing u (the children of a cell are consecutive cells of the next level).
      const HierarchyAxis& a = h_.axis(l, k);
      const int lo = h_.first_child(l - 1, k, c[k]), hi = h_.end_child(l - 1, k, c[k]);
      int e = lo;
      while (e + 1 < hi && u[k] >= a.brk(e + 1)) ++e;
      c[k] = e;
    }
  }
  return find_leaf(l, c);
}

template <int D>
bool HierarchicalSpace<D>::uncovered_cell_in_support(int level, const Ints<D>& f, Ints<D>& cell) const {
  Ints<D> lo, hi;
  for (int k = 0; k < D; ++k) {
    lo[k] = h_.axis(level, k).first_cell(f[k]);
    hi[k] = h_.axis(level, k).end_cell(f[k]);
  }
  bool found = false;
  for_each_index<D>(lo, hi, [&](const Ints<D>& c) {
    if (!found && cell_in_domain(level, c) && !is_refined(level, c)) {
      cell = c;
      found = true;
    }
  });
  return found;
}

template <int D>
bool HierarchicalSpace<D>::in_domain(int level, const Ints<D>& cell) const {
  if (level < 0 || level >= h_.num_levels()) return false;
  for (int k = 0; k < D; ++k)
    if (cell[k] < 0 || cell[k] >= h_.axis(level, k).num_cells()) return false;
  return cell_in_domain(level, cell);
}

template <int D>
bool HierarchicalSpace<D>::is_refined(int level, const Ints<D>& cell) const {
  return level >= 0 && level < static_cast<int>(refined_.size()) &&
         contains(refined_[static_cast<std::size_t>(level)], pack_key<D>(cell));
}

template <int D>
bool HierarchicalSpace<D>::is_split(int level, const Ints<D>& cell) const {
  return level >= 0 && level < static_cast<int>(split_.size()) &&
         contains(split_[static_cast<std::size_t>(level)], pack_key<D>(cell));
}

template <int D>
std::span<const CellKey> HierarchicalSpace<D>::domain_cells(int level) const {
  if (level < 1 || level >= static_cast<int>(domain_.size())) return {};
  return domain_[static_cast<std::size_t>(level)];
}

template <int D>
bool HierarchicalSpace<D>::function_inside(int level, const Ints<D>& index) const {
  if (level == 0) return true;
  if (level >= num_levels()) return false;
  return contains(inside_[static_cast<std::size_t>(level)], pack_key<D>(index));
}

template <int D>
int HierarchicalSpace<D>::refine_cells(int level, std::span<const Ints<D>> cells) {
  const int n = mark(level, cells);
  if (n > 0) rebuild();
  return n;
}

template <int D>
int HierarchicalSpace<D>::mark(int level, std::span<const Ints<D>> cells) {
  require(level >= 0 && level < num_levels(), [&] {
    return "hier: cannot refine level " + std::to_string(level) + " (the space has levels 0.." + std::to_string(num_levels() - 1) + ")";
  });
  std::vector<CellKey> keys;
  keys.reserve(cells.size());
  for (const Ints<D>& c : cells) {
    require(in_domain(level, c), [&] {
      std::string s = "hier: cell (";
      for (int k = 0; k < D; ++k) s += (k ? ", " : "") + std::to_string(c[k]);
      return s + ") of level " + std::to_string(level) + " is not inside the level's domain";
    });
    keys.push_back(pack_key<D>(c));
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  auto& r = refined_[static_cast<std::size_t>(level)];
  std::vector<CellKey> added;
  std::set_difference(keys.begin(), keys.end(), r.begin(), r.end(), std::back_inserter(added));
  if (added.empty()) return 0;
  h_.ensure_levels(level + 2);
  if (static_cast<int>(domain_.size()) < level + 2) domain_.resize(static_cast<std::size_t>(level) + 2);
  std::vector<CellKey> children;
  for (CellKey key : added)
    for_each_index<D>(first_children(level, unpack_key<D>(key)), end_children(level, unpack_key<D>(key)),
                      [&](const Ints<D>& c) { children.push_back(pack_key<D>(c)); });
  std::sort(children.begin(), children.end());
  merge_into(domain_[static_cast<std::size_t>(level) + 1], children);
  // Kept current for the coarser levels marked before the next rebuild.
  merge_into(r, added);
  return static_cast<int>(added.size());
}

template <int D>
int HierarchicalSpace<D>::mark_levels(const std::vector<std::vector<Ints<D>>>& per_level) {
  // Finest level first: refining a level never changes the domains of the levels below it.
  int n = 0;
  for (int l = static_cast<int>(per_level.size()) - 1; l >= 0; --l) n += mark(l, per_level[static_cast<std::size_t>(l)]);
  if (n > 0) rebuild();
  return n;
}

template <int D>
int HierarchicalSpace<D>::refine_elements(std::span<const int> elements) {
  std::vector<std::vector<Ints<D>>> per_level(static_cast<std::size_t>(num_levels()));
  // A leaf of level m outside Omega^m (a child of a cell a finer domain cuts, where level m - 1 lives) is
  // halved by its children joining Omega^{m+1}, which brings it into Omega^m too.
  std::vector<std::vector<Ints<D>>> joins;
  int outside = 0;
  for (int e : elements) {
    const HierarchicalCell<D> c = element(e);
    if (cell_in_domain(c.level, c.index)) {
      per_level[static_cast<std::size_t>(c.level)].push_back(c.index);
      continue;
    }
    h_.ensure_levels(c.level + 2);
    if (static_cast<int>(joins.size()) < c.level + 2) joins.resize(static_cast<std::size_t>(c.level) + 2);
    for_each_index<D>(first_children(c.level, c.index), end_children(c.level, c.index),
                      [&](const Ints<D>& child) { joins[static_cast<std::size_t>(c.level) + 1].push_back(child); });
    ++outside;
  }
  const int n = mark_levels(per_level);
  if (outside) extend_domains(joins);
  return n + outside;
}

template <int D>
int HierarchicalSpace<D>::refine_elements_admissible(std::span<const int> elements, int m) {
  require(m >= 2, "hier: admissibility class " + std::to_string(m) + " (at least 2)");
  std::vector<char> marked(static_cast<std::size_t>(num_elements()), 0);
  std::vector<int> stack(elements.begin(), elements.end()), closure;
  const int shift = basis_ == HierarchicalBasis::thb ? 2 : 1;
  while (!stack.empty()) {
    const int e = stack.back();
    stack.pop_back();
    const HierarchicalCell<D> q = element(e);
    if (marked[static_cast<std::size_t>(e)]) continue;
    marked[static_cast<std::size_t>(e)] = 1;
    closure.push_back(e);
    const int k = q.level - m + shift;  // level of the support extension
    if (q.level - m + 1 < 0 || k < 0) continue;
    Ints<D> c = q.index;
    for (int j = q.level; j > k; --j) c = parent(j, c);
    // The support extension as cells of level k, then the cells of level l - m + 1 meeting it.
    Ints<D> lo, hi;
    for (int d = 0; d < D; ++d) {
      const HierarchyAxis& a = h_.axis(k, d);
      const int span = a.span(c[d]);
      lo[d] = a.first_cell(span - h_.degree(d));
      hi[d] = a.end_cell(span);
    }
    const int n = q.level - m + 1;
    if (n < k)
      for (int d = 0; d < D; ++d) {
        lo[d] = h_.parent(k, d, lo[d]);
        hi[d] = h_.parent(k, d, hi[d] - 1) + 1;
      }
    for_each_index<D>(lo, hi, [&](const Ints<D>& cell) {
      const int leaf = find_leaf(n, cell);
      if (leaf >= 0 && !marked[static_cast<std::size_t>(leaf)]) stack.push_back(leaf);
    });
  }
  return refine_elements(closure);
}

template <int D>
int HierarchicalSpace<D>::refine_functions(std::span<const int> ids) {
  std::vector<std::vector<Ints<D>>> per_level(static_cast<std::size_t>(num_levels()));
  for (int id : ids) {
    const HierarchicalFunction<D> f = function(id);
    Ints<D> lo, hi;
    for (int k = 0; k < D; ++k) {
      lo[k] = h_.axis(f.level, k).first_cell(f.index[k]);
      hi[k] = h_.axis(f.level, k).end_cell(f.index[k]);
    }
    for_each_index<D>(lo, hi, [&](const Ints<D>& c) { per_level[static_cast<std::size_t>(f.level)].push_back(c); });
  }
  return mark_levels(per_level);
}

template <int D>
int HierarchicalSpace<D>::extend_domains(const std::vector<std::vector<Ints<D>>>& cells) {
  require(cells.empty() || cells.front().empty(), "hier: level 0 is the whole domain; no cells can join it");
  const int L = static_cast<int>(cells.size());
  if (L > h_.num_levels()) h_.ensure_levels(L);
  for (int l = 1; l < L; ++l)
    for (const Ints<D>& c : cells[static_cast<std::size_t>(l)])
      for (int k = 0; k < D; ++k)
        require(c[k] >= 0 && c[k] < h_.axis(l, k).num_cells(), [&] {
          return "hier: cell index " + std::to_string(c[k]) + " of level " + std::to_string(l) + " outside the " +
                 std::to_string(h_.axis(l, k).num_cells()) + " cells in direction " + std::to_string(k);
        });
  if (static_cast<int>(domain_.size()) < L) domain_.resize(static_cast<std::size_t>(L));
  std::size_t before = 0, after = 0;
  for (const auto& d : domain_) before += d.size();
  for (int l = 1; l < L; ++l) {
    std::vector<CellKey> keys;
    for (const Ints<D>& c : cells[static_cast<std::size_t>(l)]) keys.push_back(pack_key<D>(c));
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    merge_into(domain_[static_cast<std::size_t>(l)], keys);
  }
  close_domains();
  for (const auto& d : domain_) after += d.size();
  rebuild();
  return static_cast<int>(after - before);
}

template <int D>
void HierarchicalSpace<D>::close_domains() {
  for (int l = static_cast<int>(domain_.size()) - 2; l >= 1; --l) {
    const std::vector<CellKey>& finer = domain_[static_cast<std::size_t>(l) + 1];
    std::vector<CellKey> covered;
    for (CellKey key : finer) {
      const Ints<D> p = parent(l + 1, unpack_key<D>(key));
      if (all_of_index<D>(first_children(l, p), end_children(l, p),
                          [&](const Ints<D>& child) { return contains(finer, pack_key<D>(child)); }))
        covered.push_back(pack_key<D>(p));
    }
    std::sort(covered.begin(), covered.end());
    covered.erase(std::unique(covered.begin(), covered.end()), covered.end());
    merge_into(domain_[static_cast<std::size_t>(l)], covered);
  }
}

template <int D>
Ints<D> HierarchicalSpace<D>::parent(int level, const Ints<D>& cell) const {
  Ints<D> p;
  for (int k = 0; k < D; ++k) p[k] = h_.parent(level, k, cell[k]);
  return p;
}

template <int D>
Ints<D> HierarchicalSpace<D>::first_children(int level, const Ints<D>& cell) const {
  Ints<D> c;
  for (int k = 0; k < D; ++k) c[k] = h_.first_child(level, k, cell[k]);
  return c;
}

template <int D>
Ints<D> HierarchicalSpace<D>::end_children(int level, const Ints<D>& cell) const {
  Ints<D> c;
  for (int k = 0; k < D; ++k) c[k] = h_.end_child(level, k, cell[k]);
  return c;
}

template <int D>
template <class AddActive>
void HierarchicalSpace<D>::step(int j, const Ints<D>& c, int stride, double* rows, int count, AddActive&& add) const {
  const int P = local_size_;
  Ints<D> n, first;
  for (int k = 0; k < D; ++k) {
    n[k] = h_.degree(k) + 1;
    first[k] = h_.axis(j, k).span(c[k]) - h_.degree(k);
  }
  if (j > 0 && count > 0) {
    thread_local std::vector<double> tmp;
    double R[D][(kMaxDegree + 1) * (kMaxDegree + 1)];
    std::array<const double*, D> M;
    for (int k = 0; k < D; ++k) {
      h_.local_refinement(j, k, c[k], R[k]);
      M[k] = R[k];
    }
    apply_kronecker<D>(n, M, stride, count, rows, tmp);
  }
  const bool truncate = basis_ == HierarchicalBasis::thb && j > 0 && count > 0;
  Ints<D> a{};
  for (int q = 0; q < P; ++q) {
    Ints<D> f;
    for (int k = 0; k < D; ++k) f[k] = first[k] + a[k];
    if (truncate && function_inside(j, f))
      for (int r = 0; r < count; ++r) std::fill_n(rows + (static_cast<std::ptrdiff_t>(r) * P + q) * stride, stride, 0.0);
    const int id = find_function(j, f);
    if (id >= 0) add(q, id);
    for (int k = 0; k < D && ++a[k] == n[k]; ++k) a[k] = 0;
  }
}

template <int D>
HierarchicalElement<D> HierarchicalSpace<D>::element_operator(int e) const {
  const HierarchicalCell<D> cell = element(e);
  const int P = local_size_;
  std::vector<double> rows;
  std::vector<int> ids;
  int count = 0;
  std::vector<Ints<D>> anc(static_cast<std::size_t>(cell.level) + 1);
  anc.back() = cell.index;
  for (int j = cell.level; j > 0; --j) anc[static_cast<std::size_t>(j) - 1] = parent(j, anc[static_cast<std::size_t>(j)]);
  std::vector<std::pair<int, int>> added;
  for (int j = 0; j <= cell.level; ++j) {
    added.clear();
    step(j, anc[static_cast<std::size_t>(j)], 1, rows.data(), count, [&](int q, int id) { added.emplace_back(q, id); });
    for (const auto& [q, id] : added) {
      rows.resize(static_cast<std::size_t>(count + 1) * P, 0.0);
      rows[static_cast<std::size_t>(count) * P + q] = 1.0;
      ids.push_back(id);
      ++count;
    }
  }
  Ints<D> n;
  std::array<std::vector<double>, D> B;
  std::array<const double*, D> M;
  for (int k = 0; k < D; ++k) {
    n[k] = h_.degree(k) + 1;
    B[k].resize(static_cast<std::size_t>(n[k] * n[k]));
    h_.local_bezier(cell.level, k, cell.index[k], B[k].data());
    M[k] = B[k].data();
  }
  std::vector<double> tmp;
  apply_kronecker<D>(n, M, 1, count, rows.data(), tmp);
  // Truncated functions whose restriction vanishes: every entry is an exact zero (truncation writes zeros
  // and refinement matrices of zero rows stay zero), so the test is exact.
  std::vector<int> order;
  for (int r = 0; r < count; ++r)
    if (std::any_of(rows.begin() + static_cast<std::ptrdiff_t>(r) * P, rows.begin() + static_cast<std::ptrdiff_t>(r + 1) * P,
                    [](double x) { return x != 0.0; }))
      order.push_back(r);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return ids[static_cast<std::size_t>(a)] < ids[static_cast<std::size_t>(b)]; });
  HierarchicalElement<D> out;
  out.box = h_.cell_box(cell.level, cell.index);
  out.C.resize(static_cast<Eigen::Index>(order.size()), P);
  for (std::size_t i = 0; i < order.size(); ++i) {
    out.ids.push_back(ids[static_cast<std::size_t>(order[i])]);
    for (int q = 0; q < P; ++q) out.C(static_cast<Eigen::Index>(i), q) = rows[static_cast<std::size_t>(order[i]) * P + q];
  }
  return out;
}

template <int D>
const std::vector<double>& HierarchicalSpace<D>::cached_expansion(int level, const Ints<D>& cell,
                                                                  std::span<const double> coefs, int stride,
                                                                  ExpansionCache& cache) const {
  if (static_cast<int>(cache.levels.size()) <= level) cache.levels.resize(static_cast<std::size_t>(level) + 1);
  auto& memo = cache.levels[static_cast<std::size_t>(level)];
  const CellKey key = pack_key<D>(cell);
  if (const auto it = memo.find(key); it != memo.end()) return it->second;
  std::vector<double> v = level == 0 ? std::vector<double>(static_cast<std::size_t>(local_size_) * stride, 0.0)
                                     : cached_expansion(level - 1, parent(level, cell), coefs, stride, cache);
  step(level, cell, stride, v.data(), 1, [&](int q, int id) {
    for (int s = 0; s < stride; ++s) v[static_cast<std::size_t>(q * stride + s)] += coefs[static_cast<std::size_t>(id) * stride + s];
  });
  // References into an unordered_map stay valid when it rehashes.
  return memo.emplace(key, std::move(v)).first->second;
}

template <int D>
void HierarchicalSpace<D>::local_expansion(int level, const Ints<D>& cell, std::span<const double> coefs, int stride,
                                           double* out, ExpansionCache& cache) const {
  const std::size_t size = static_cast<std::size_t>(local_size_) * stride;
  if (level == 0)
    std::fill_n(out, size, 0.0);
  else
    std::copy_n(cached_expansion(level - 1, parent(level, cell), coefs, stride, cache).begin(), size, out);
  step(level, cell, stride, out, 1, [&](int q, int id) {
    for (int s = 0; s < stride; ++s) out[q * stride + s] += coefs[static_cast<std::size_t>(id) * stride + s];
  });
}

template <int D>
void HierarchicalSpace<D>::local_expansion(int level, const Ints<D>& cell, std::span<const double> coefs, int stride,
                                           double* out) const {
  ExpansionCache cache;
  local_expansion(level, cell, coefs, stride, out, cache);
}

template <int D>
void HierarchicalSpace<D>::eval_basis(const Param<D>& u, int order, std::vector<int>& ids,
                                      std::vector<double>& values) const {
  require(order >= 0 && order <= kMaxDerivativeOrder, "hier: derivative order " + std::to_string(order) + " out of range");
  const Box<D> dom = domain();
  Param<D> x;
  for (int k = 0; k < D; ++k) x[k] = std::clamp(u[k], dom.lo[k], dom.hi[k]);
  const HierarchicalElement<D> el = element_operator(find_element(x));
  std::array<std::vector<double>, D> B;
  for (int k = 0; k < D; ++k) {
    const int p = h_.degree(k);
    B[k].resize(static_cast<std::size_t>((order + 1) * (p + 1)));
    bernstein_derivatives(p, el.box.lo[k], el.box.hi[k], x[k], order, B[k].data());
  }
  const auto multi = derivative_multi_indices<D>(order);
  const int nd = static_cast<int>(multi.size()), P = local_size_;
  ids = el.ids;
  values.assign(ids.size() * static_cast<std::size_t>(nd), 0.0);
  std::vector<double> tb(static_cast<std::size_t>(P));
  for (int d = 0; d < nd; ++d) {
    Ints<D> a{};
    for (int q = 0; q < P; ++q) {
      double v = 1;
      for (int k = 0; k < D; ++k) v *= B[k][static_cast<std::size_t>(multi[static_cast<std::size_t>(d)][k] * (h_.degree(k) + 1) + a[k])];
      tb[static_cast<std::size_t>(q)] = v;
      for (int k = 0; k < D && ++a[k] == h_.degree(k) + 1; ++k) a[k] = 0;
    }
    for (std::size_t r = 0; r < ids.size(); ++r)
      values[r * static_cast<std::size_t>(nd) + static_cast<std::size_t>(d)] =
          el.C.row(static_cast<Eigen::Index>(r)).dot(Eigen::Map<const Eigen::RowVectorXd>(tb.data(), P));
  }
}

template class HierarchicalSpace<2>;
template class HierarchicalSpace<3>;

}  // namespace trivar
