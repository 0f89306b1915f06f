#include "trivar/lr/lr_spline.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <unordered_map>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/lr/lr_mesh.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/knot_refinement.hpp"

namespace trivar {

namespace {

// Scaling factors written by other tools (or by rounded sums) may exceed 1 by a few ulps; accepted up to this.
constexpr double kGammaSlack = 1e-12;

// +0.0 for -0.0, so that equal values hash equally.
inline std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v); }

template <int D>
std::uint64_t knot_hash(const LRBSpline<D>& b) {
  std::uint64_t h = 1469598103934665603ull;
  for (int k = 0; k < D; ++k)
    for (double v : b.knots[k]) h = (h ^ bits(v)) * 1099511628211ull ^ (h >> 29);
  return h;
}

template <int D>
bool same_knots(const LRBSpline<D>& a, const LRBSpline<D>& b) {
  for (int k = 0; k < D; ++k)
    if (a.knots[k] != b.knots[k]) return false;
  return true;
}

// The id order: lexicographic in the knot vectors, the last direction most significant.
template <int D>
bool knot_less(const LRBSpline<D>& a, const LRBSpline<D>& b) {
  for (int k = D - 1; k >= 0; --k)
    if (a.knots[k] != b.knots[k]) return a.knots[k] < b.knots[k];
  return false;
}

// Ids under 64-bit keys, several ids per key allowed, in one flat array with linear probing: the split loop
// looks a B-spline up twice per split, and a node-based map spent most of that in cache misses.
class HashIndex {
public:
  void reserve(std::size_t n) {
    std::size_t cap = 16;
    while (cap < 2 * n) cap *= 2;
    if (cap > slots_.size()) rehash(cap);
  }
  void insert(std::uint64_t key, int id) {
    // At most half full; when erased slots are most of that, rehashing at the same size clears them.
    if (2 * (used_ + 1) > slots_.size())
      rehash(4 * (live_ + 1) > slots_.size() ? std::max<std::size_t>(16, 2 * slots_.size()) : slots_.size());
    for (std::size_t i = start(key);; i = (i + 1) & mask_) {
      auto& slot = slots_[i];
      if (slot.id >= 0) continue;
      if (slot.id == kEmpty) ++used_;
      slot = {key, id};
      ++live_;
      return;
    }
  }
  void erase(std::uint64_t key, int id) {
    for (std::size_t i = start(key); slots_[i].id != kEmpty; i = (i + 1) & mask_)
      if (slots_[i].id == id && slots_[i].key == key) {
        slots_[i].id = kErased;
        --live_;
        return;
      }
  }
  // The first id under `key` for which match(id) holds, or -1.
  template <class Match>
  int find(std::uint64_t key, Match&& match) const {
    if (slots_.empty()) return -1;
    for (std::size_t i = start(key); slots_[i].id != kEmpty; i = (i + 1) & mask_)
      if (slots_[i].id >= 0 && slots_[i].key == key && match(slots_[i].id)) return slots_[i].id;
    return -1;
  }

private:
  static constexpr int kEmpty = -1, kErased = -2;
  struct Slot {
    std::uint64_t key = 0;
    int id = kEmpty;
  };
  std::vector<Slot> slots_;
  std::size_t mask_ = 0, used_ = 0, live_ = 0;  // used_: live and erased slots

  std::size_t start(std::uint64_t key) const {
    key ^= key >> 31;
    key *= 0x7fb5d329728ea185ull;
    key ^= key >> 27;
    return static_cast<std::size_t>(key) & mask_;
  }
  void rehash(std::size_t cap) {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(cap, Slot{});
    mask_ = cap - 1;
    used_ = live_ = 0;
    for (const auto& slot : old)
      if (slot.id >= 0) insert(slot.key, slot.id);
  }
};

struct PlaneKey {
  int dir;
  double value;
  bool operator==(const PlaneKey& o) const { return dir == o.dir && value == o.value; }
};
struct PlaneHash {
  std::size_t operator()(const PlaneKey& k) const {
    return static_cast<std::size_t>(bits(k.value) * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(k.dir));
  }
};

template <int D>
double volume(const Box<D>& b) {
  double v = 1.0;
  for (int k = 0; k < D; ++k) v *= b.extent(k);
  return v;
}

template <int D>
bool strictly_inside(const Param<D>& c, const Box<D>& s) {
  for (int k = 0; k < D; ++k)
    if (c[k] <= s.lo[k] || c[k] >= s.hi[k]) return false;
  return true;
}

template <int D>
bool center_inside(const Box<D>& e, const Box<D>& s) {
  return strictly_inside(e.center(), s);
}

// The element id order: lower corners lexicographic, the last direction most significant.
template <int D>
bool corner_less(const Box<D>& a, const Box<D>& b) {
  for (int k = D - 1; k >= 0; --k)
    if (a.lo[k] != b.lo[k]) return a.lo[k] < b.lo[k];
  return false;
}

// The element ids in corner order. The first `sorted` elements are usually in that order already (a refinement
// only appends elements and never moves a lower corner), so only the rest is sorted and merged in; the keys are
// sorted by value, not through the ids, so the comparisons read contiguous memory.
template <int D>
std::vector<int> corner_order(std::span<const Box<D>> elements, std::size_t sorted) {
  struct Key {
    Param<D> lo;
    int id;
  };
  const auto less = [](const Key& a, const Key& b) {
    for (int k = D - 1; k >= 0; --k)
      if (a.lo[k] != b.lo[k]) return a.lo[k] < b.lo[k];
    return false;
  };
  std::vector<Key> keys(elements.size());
  for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = {elements[i].lo, static_cast<int>(i)};
  const auto mid = keys.begin() + static_cast<std::ptrdiff_t>(std::min(sorted, keys.size()));
  if (!std::is_sorted(keys.begin(), mid, less)) {
    std::sort(keys.begin(), keys.end(), less);
  } else {
    std::sort(mid, keys.end(), less);
    std::inplace_merge(keys.begin(), mid, keys.end(), less);
  }
  std::vector<int> order(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) order[i] = keys[i].id;
  return order;
}

}  // namespace

// The working state of one insertion call: indices that are cheap to build from the compact form (O(size)) and
// make every step of an insertion local, and the lazily deleted B-spline slots. finish() compacts.
//
// Rectangles enter the mesh one at a time, in order, so the mesh, the elements and the decision to skip a
// rectangle are exactly those of inserting them one by one. The B-splines are split lazily (resolve()), once
// for all rectangles since the last resolve: the LR B-splines of a mesh do not depend on the order in which its
// rectangles were inserted (Dokken, Lyche, Pettersen 2013), and splitting a B-spline by all its new lines of a
// direction at once skips intermediate B-splines that splitting after every rectangle goes through (that made
// 1.6 times as many splits on the 3D FULLSPAN benchmark, and twice as many B-splines tested). While splits
// are pending, element_basis_ holds the lists of the "base" elements (those that existed at the last resolve)
// and every element split off since records its base element.
template <int D>
struct LRSpline<D>::Batch {
  using Rect = MeshRectangle<D>;
  LRSpline& s;
  std::vector<char> dead;
  HashIndex by_knots;
  std::unordered_map<PlaneKey, std::vector<int>, PlaneHash> planes;  // mesh_ ids; multiplicity 0 = removed
  // Per direction the planes by value, ascending, so find_split reaches the planes inside a support directly.
  // (Pointers into `planes`: its nodes do not move.)
  struct PlaneEntry {
    double value;
    const std::vector<int>* ids;
  };
  std::array<std::vector<PlaneEntry>, D> plane_values;
  ElementGrid<D> grid;
  // The largest multiplicity of a rectangle strictly inside the domain in its direction (the ends, multiplicity
  // p + 1 on open knot vectors, lie inside no support): only above 1 can a line raise an interior knot.
  int interior_multiplicity = 1;
  bool changed = false;
  // B-splines to test, largest support volume first: a split only makes B-splines of smaller support, so every
  // contribution to a B-spline arrives (merged by add) before it is tested and split, and each distinct B-spline
  // is split once. (Rounding can only break ties; a B-spline split twice would still give the same result.)
  // Supports take few distinct volumes, so a bucket per volume is cheaper than a heap of all entries.
  std::map<double, std::vector<int>, std::greater<>> queue;
  std::vector<int> stamp;
  int epoch = 0;
  std::vector<double> candidates;
  bool all_lines = false;  // find_split chose every multiplicity-one line of its direction
  // Per B-spline, a direction in which it has no multiplicity-one line to split by in the current mesh, or -1:
  // a piece of a split by all such lines of direction k has none in k (its planes across k are its parent's,
  // with the same cross-section, and the parent's lines inside its support are now its knots). Valid while the
  // mesh does not change, so within one resolve().
  std::vector<signed char> settled;
  std::vector<const Rect*> plane_rects;
  std::vector<double> fine, coefs;  // split(): the finer local knots and the coefficients on them
  LRBSpline<D> piece;               // split(): the piece being added
  std::vector<LRBSpline<D>> spare;  // split(): storage of split B-splines, for new pieces
  // B-splines made since the last resolve lack support lists: each one's list is filtered, once it is final,
  // from the list of the B-spline on a touched element it descends from (its root; extended by resolve).
  std::vector<int> root;
  std::vector<int> stale;
  std::vector<int> extended;       // B-splines whose lists resolve extended by the new elements
  std::size_t sorted_count = 0;    // B-splines before the batch, in id order
  std::vector<int> touched;
  std::vector<Param<D>> centres;   // refresh_lists(): element centres
  std::vector<int> group_head, group_next, bucket_start, bucket_of, by_bucket;  // refresh_lists(): scratch
  std::vector<double> cuts;                                                    // refresh_lists(): scratch
  // The support lists while the batch runs: list b is pool[list_at[b] .. + list_len[b]). The pool starts as
  // the spline's flat lists (taken at the first resolve, so a rectangle rejected before any change leaves the
  // spline untouched); a list that changes is written anew at the pool's end, and finish() compacts.
  std::vector<int> pool;
  std::vector<std::size_t> list_at;
  std::vector<int> list_len;
  bool pooled = false;
  std::size_t first_new_element = 0;  // elements before the batch
  std::size_t base = 0;            // elements whose lists element_basis_ holds
  std::vector<int> origin;         // base element of element base + i
  std::vector<int> touched_base;   // base elements touched by a rectangle since the last resolve
  std::vector<char> is_touched;    // per base element

  explicit Batch(LRSpline& spline) : s(spline), grid(spline.domain_, spline.elements_.size()) {
    dead.assign(s.basis_.size(), 0);
    by_knots.reserve(s.basis_.size() * 2);
    for (std::size_t i = 0; i < s.basis_.size(); ++i) by_knots.insert(knot_hash(s.basis_[i]), static_cast<int>(i));
    for (std::size_t i = 0; i < s.mesh_.size(); ++i) {
      const auto& r = s.mesh_[i];
      planes[{r.dir, r.value}].push_back(static_cast<int>(i));
      note_multiplicity(r);
    }
    for (const auto& [key, ids] : planes) plane_values[static_cast<std::size_t>(key.dir)].push_back({key.value, &ids});
    for (auto& v : plane_values)
      std::sort(v.begin(), v.end(), [](const PlaneEntry& a, const PlaneEntry& b) { return a.value < b.value; });
    for (std::size_t e = 0; e < s.elements_.size(); ++e) grid.add(static_cast<int>(e), s.elements_[e]);
    stamp.assign(s.basis_.size(), 0);
    settled.assign(s.basis_.size(), -1);
    sorted_count = s.basis_.size();
    root.resize(s.basis_.size());
    for (std::size_t i = 0; i < root.size(); ++i) root[i] = static_cast<int>(i);
    base = first_new_element = s.elements_.size();
    is_touched.assign(base, 0);
  }

  void note_multiplicity(const Rect& r) {
    if (s.domain_.lo[r.dir] < r.value && r.value < s.domain_.hi[r.dir])
      interior_multiplicity = std::max(interior_multiplicity, r.multiplicity);
  }

  int base_of(int e) const {
    return static_cast<std::size_t>(e) < base ? e : origin[static_cast<std::size_t>(e) - base];
  }

  // The rectangles of the plane (dir, value), plus `extra` when given, in plane_rects.
  void gather_plane(int dir, double value, const Rect* extra) {
    plane_rects.clear();
    const auto it = planes.find({dir, value});
    if (it != planes.end())
      for (int id : it->second) plane_rects.push_back(&s.mesh_[static_cast<std::size_t>(id)]);
    if (extra) plane_rects.push_back(extra);
  }

  // Whether the rectangles `ids` of the plane (dir, value) with multiplicity >= m cover S's cross-section.
  bool plane_covers(const std::vector<int>& ids, int dir, double value, const Box<D>& S, int m) const {
    return mesh_covers<D>(
        ids.size(), [&](std::size_t i) -> const Rect& { return s.mesh_[static_cast<std::size_t>(ids[i])]; }, dir, value,
        S, m);
  }

  bool insert_one(const Rect& r, bool strict) {
    const int k = r.dir;
    const double z = r.value;
    const auto where = [&] {
      return "LRSpline::insert: mesh rectangle in direction " + std::to_string(k) + " at " + std::to_string(z);
    };
    gather_plane(k, z, nullptr);
    if (mesh_covers<D>(plane_rects, k, z, r.extent, r.multiplicity)) return false;

    Box<D> q = r.extent;
    q.lo[k] = q.hi[k] = z;
    touched.clear();
    const auto box = [&](int e) -> const Box<D>& { return s.elements_[static_cast<std::size_t>(e)]; };
    grid.query_dense(q, box, [&](int e) {
      const auto& el = s.elements_[static_cast<std::size_t>(e)];
      if (el.lo[k] <= z && z <= el.hi[k] && r.overlaps_across(el)) touched.push_back(e);
    });
    std::sort(touched.begin(), touched.end());
    // Every element the rectangle cuts or lies on must be cut or bounded across its whole cross-section:
    // otherwise the rectangle ends inside an element or inside an element face.
    // A face the mesh already holds with r's multiplicity may be overlapped partially.
    for (int e : touched) {
      const auto& el = s.elements_[static_cast<std::size_t>(e)];
      const bool straddled = el.lo[k] < z && z < el.hi[k];
      require(r.contains_across(el) || (!straddled && mesh_covers<D>(plane_rects, k, z, el, r.multiplicity)),
              [&] { return where() + ": rectangle ends inside an element or face"; });
    }
    // Decide before changing anything that some support is traversed; the exact test needs the B-splines of
    // the current mesh, so it resolves the pending splits first.
    if (!surely_splits(r)) {
      flush();
      if (!exactly_splits(r)) {
        require(!strict, [&] { return where() + ": splits no B-spline support"; });
        return false;
      }
    }

    changed = true;
    add_to_mesh(r);
    for (int e : touched) {
      const int o = base_of(e);
      if (!is_touched[static_cast<std::size_t>(o)]) {
        is_touched[static_cast<std::size_t>(o)] = 1;
        touched_base.push_back(o);
      }
      auto& el = s.elements_[static_cast<std::size_t>(e)];
      if (!(el.lo[k] < z && z < el.hi[k])) continue;
      Box<D> upper = el;
      upper.lo[k] = z;
      el.hi[k] = z;
      const int e2 = static_cast<int>(s.elements_.size());
      s.elements_.push_back(upper);
      origin.push_back(o);
      grid.add(e2, upper);
    }
    return true;
  }

  // Sufficient for r to split a B-spline of the current collection, from the base B-splines alone: r cuts an
  // element e and crosses completely the support of a base B-spline B on e's base element. B is a positive
  // combination of current B-splines with supports inside its own, one of which contains e; r crosses that
  // support completely, and z, strictly inside the element e, is not among its knots.
  bool surely_splits(const Rect& r) const {
    const int k = r.dir;
    const double z = r.value;
    for (int e : touched) {
      const auto& el = s.elements_[static_cast<std::size_t>(e)];
      if (!(el.lo[k] < z && z < el.hi[k])) continue;
      for (int b : s.element_basis_[base_of(e)])
        if (r.contains_across(s.basis_[static_cast<std::size_t>(b)].support())) return true;
    }
    return false;
  }

  // Whether r traverses a B-spline of the current collection (no splits pending): the B-splines crossing z
  // through r's extent have support on the touched elements.
  bool exactly_splits(const Rect& r) {
    const int k = r.dir;
    const double z = r.value;
    gather_plane(k, z, &r);
    ++epoch;
    for (int e : touched)
      for (int b : s.element_basis_[e]) {
        if (stamp[static_cast<std::size_t>(b)] == epoch) continue;
        stamp[static_cast<std::size_t>(b)] = epoch;
        const auto& fn = s.basis_[static_cast<std::size_t>(b)];
        const Box<D> S = fn.support();
        if (!(S.lo[k] < z && z < S.hi[k]) || !r.overlaps_across(S)) continue;
        const auto& y = fn.knots[k];
        const int m = static_cast<int>(std::count(y.begin(), y.end(), z));
        if (mesh_covers<D>(plane_rects, k, z, S, m + 1)) return true;
      }
    return false;
  }

  // Splits the B-splines the rectangles since the last resolve reach (those on a base element one of them
  // touched; the mesh inside every other support is unchanged) until every support is minimal in the current
  // mesh. Their support lists gain the elements split off their base elements first: refresh_lists() filters
  // the lists of the pieces that survive from them.
  void resolve() {
    if (touched_base.empty()) return;
    take_lists();
    std::vector<int> head(base, -1), chain(origin.size(), -1), pieces(base, 0);
    for (std::size_t i = origin.size(); i-- > 0;) {  // so that every chain ascends
      chain[i] = head[static_cast<std::size_t>(origin[i])];
      head[static_cast<std::size_t>(origin[i])] = static_cast<int>(i);
      ++pieces[static_cast<std::size_t>(origin[i])];
    }
    ++epoch;
    for (int o : touched_base) {
      is_touched[static_cast<std::size_t>(o)] = 0;
      for (int b : s.element_basis_[o]) {
        if (stamp[static_cast<std::size_t>(b)] == epoch) continue;
        stamp[static_cast<std::size_t>(b)] = epoch;
        // The extended list is written at the pool's end: the old list, then the elements split off its own.
        const std::size_t at = list_at[static_cast<std::size_t>(b)];
        const std::size_t n = static_cast<std::size_t>(list_len[static_cast<std::size_t>(b)]);
        std::size_t grown = n;
        for (std::size_t j = 0; j < n; ++j) grown += static_cast<std::size_t>(pieces[static_cast<std::size_t>(pool[at + j])]);
        const std::size_t out = pool.size();
        pool.resize(out + grown);
        std::copy_n(pool.begin() + static_cast<std::ptrdiff_t>(at), n, pool.begin() + static_cast<std::ptrdiff_t>(out));
        int* w = pool.data() + out + n;
        for (std::size_t j = 0; j < n; ++j)
          for (int c = head[static_cast<std::size_t>(pool[at + j])]; c >= 0; c = chain[static_cast<std::size_t>(c)])
            *w++ = static_cast<int>(base) + c;
        list_at[static_cast<std::size_t>(b)] = out;
        list_len[static_cast<std::size_t>(b)] = static_cast<int>(grown);
        extended.push_back(b);
        settled[static_cast<std::size_t>(b)] = -1;
        enqueue(b);
      }
    }
    touched_base.clear();
    while (!queue.empty()) {
      const auto largest = queue.begin();
      const int b = largest->second.back();
      largest->second.pop_back();
      if (largest->second.empty()) queue.erase(largest);
      int dir = 0;
      if (!dead[static_cast<std::size_t>(b)] && find_split(b, dir)) split(b, dir, candidates);
    }
  }

  void take_lists() {
    if (pooled) return;
    pooled = true;
    const std::size_t n = s.basis_.size();
    list_at.resize(n);
    list_len.resize(n);
    for (std::size_t b = 0; b < n; ++b) {
      list_at[b] = static_cast<std::size_t>(s.basis_elements_.offsets[b]);
      list_len[b] = s.basis_elements_.offsets[b + 1] - s.basis_elements_.offsets[b];
    }
    pool = std::move(s.basis_elements_.ids);
    s.basis_elements_ = {};
  }

  void enqueue(int b) {
    queue[volume(s.basis_[static_cast<std::size_t>(b)].support())].push_back(b);
  }

  // The support lists of the B-splines made by the last resolve that survive: the elements of their root's
  // list whose centres lie inside their support. Lists stay unsorted within a batch (only their sets matter
  // there): finish() renumbers the elements and rebuilds every list in order by transposition, so sorting here
  // would be wasted. Then every B-spline is its own root again.
  //
  // A root has about ten survivors, each inside a part of the root's support. The root's elements are
  // bucketed once by their centres' last coordinate between the survivors' bounds in that direction, so a
  // survivor tests only the buckets between its own bounds (about half the root's list on the diagonal)
  // instead of the whole list.
  void refresh_lists() {
    // The centres once per call, in a flat array half the size of the boxes: the filter reads each element
    // several times, so this is most of the memory traffic.
    centres.resize(s.elements_.size());
    for (std::size_t e = 0; e < centres.size(); ++e) centres[e] = s.elements_[e].center();
    // The survivors of every root, chained from the root.
    group_head.assign(s.basis_.size(), -1);
    group_next.assign(stale.size(), -1);
    for (std::size_t i = stale.size(); i-- > 0;) {
      const int b = stale[i];
      if (dead[static_cast<std::size_t>(b)]) continue;
      int& head = group_head[static_cast<std::size_t>(root[static_cast<std::size_t>(b)])];
      group_next[i] = head;
      head = static_cast<int>(i);
    }
    for (std::size_t i = 0; i < stale.size(); ++i) {
      const int b = stale[i];
      if (dead[static_cast<std::size_t>(b)]) continue;
      const int r = root[static_cast<std::size_t>(b)];
      const int first = group_head[static_cast<std::size_t>(r)];
      if (first < 0) continue;  // the root's group is done
      group_head[static_cast<std::size_t>(r)] = -1;
      filter_group(r, first);
    }
    for (int b : stale) root[static_cast<std::size_t>(b)] = b;
    for (int b : extended)
      if (dead[static_cast<std::size_t>(b)]) list_len[static_cast<std::size_t>(b)] = 0;
    stale.clear();
    extended.clear();
  }

  // The lists of the survivors chained from stale[first] (through group_next), filtered from the list of their
  // root r.
  void filter_group(int r, int first) {
    const std::size_t from_at = list_at[static_cast<std::size_t>(r)];
    const std::size_t from_size = static_cast<std::size_t>(list_len[static_cast<std::size_t>(r)]);
    constexpr int last = D - 1;
    cuts.clear();
    std::size_t members = 0;
    for (int i = first; i >= 0; i = group_next[static_cast<std::size_t>(i)], ++members) {
      const auto& y = s.basis_[static_cast<std::size_t>(stale[static_cast<std::size_t>(i)])].knots[last];
      cuts.push_back(y.front());
      cuts.push_back(y.back());
    }
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
    // Bucket j holds the elements whose centre lies between cuts[j - 1] and cuts[j] (counting sort).
    const auto bucket = [&](double c) {
      return static_cast<std::size_t>(std::upper_bound(cuts.begin(), cuts.end(), c) - cuts.begin());
    };
    const bool bucketed = members > 2;
    if (bucketed) {
      bucket_start.assign(cuts.size() + 2, 0);
      const int* from = pool.data() + from_at;
      bucket_of.resize(from_size);
      for (std::size_t j = 0; j < from_size; ++j) {
        bucket_of[j] = static_cast<int>(bucket(centres[static_cast<std::size_t>(from[j])][last]));
        ++bucket_start[static_cast<std::size_t>(bucket_of[j]) + 1];
      }
      for (std::size_t j = 1; j < bucket_start.size(); ++j) bucket_start[j] += bucket_start[j - 1];
      by_bucket.resize(from_size);
      for (std::size_t j = 0; j < from_size; ++j)
        by_bucket[static_cast<std::size_t>(bucket_start[static_cast<std::size_t>(bucket_of[j])]++)] = from[j];
      // bucket_start[j] is now the end of bucket j, the start of bucket j + 1.
    }
    for (int i = first; i >= 0; i = group_next[static_cast<std::size_t>(i)]) {
      const int b = stale[static_cast<std::size_t>(i)];
      const Box<D> S = s.basis_[static_cast<std::size_t>(b)].support();
      // Written at the pool's end, sized for every candidate first (the pool may move then, so the candidates
      // are located after it grew) and cut to what passed.
      std::size_t lo = 0, hi = from_size;
      if (bucketed) {
        // Centres strictly inside (S.lo, S.hi) lie in the buckets after S.lo's cut up to S.hi's.
        const std::size_t first_bucket = bucket(S.lo[last]), last_bucket = bucket(S.hi[last]) - 1;
        lo = first_bucket == 0 ? 0 : static_cast<std::size_t>(bucket_start[first_bucket - 1]);
        hi = static_cast<std::size_t>(bucket_start[last_bucket]);
      }
      const std::size_t out = pool.size();
      pool.resize(out + (hi - lo));
      const int* begin = (bucketed ? by_bucket.data() : pool.data() + from_at) + lo;
      const int* end = begin + (hi - lo);
      int* w = pool.data() + out;
      for (const int* e = begin; e != end; ++e)
        if (strictly_inside(centres[static_cast<std::size_t>(*e)], S)) *w++ = *e;
      pool.resize(static_cast<std::size_t>(w - pool.data()));
      list_at[static_cast<std::size_t>(b)] = out;
      list_len[static_cast<std::size_t>(b)] = static_cast<int>(pool.size() - out);
    }
  }

  // resolve() and element lists for every element, so the exact test can run on the current mesh.
  void flush() {
    if (touched_base.empty()) return;
    resolve();
    refresh_lists();
    // Dead B-splines keep their lists in the pool but belong to no element.
    transpose_into(s.element_basis_, s.num_elements(), s.num_basis(), [this](int b) {
      return dead[static_cast<std::size_t>(b)] ? std::span<const int>{} : pooled_list(b);
    });
    base = s.elements_.size();
    origin.clear();
    is_touched.assign(base, 0);
  }

  // Support list b in the pool.
  std::span<const int> pooled_list(int b) const {
    const auto i = static_cast<std::size_t>(b);
    return {pool.data() + list_at[i], static_cast<std::size_t>(list_len[i])};
  }

  void add_to_mesh(const Rect& r) {
    Rect n = r;
    const auto [it, is_new] = planes.try_emplace({r.dir, r.value});
    auto& ids = it->second;
    if (is_new) {
      auto& v = plane_values[static_cast<std::size_t>(r.dir)];
      const auto at = std::lower_bound(v.begin(), v.end(), r.value,
                                       [](const PlaneEntry& a, double x) { return a.value < x; });
      v.insert(at, {r.value, &ids});
    }
    bool merged = true;
    while (merged) {
      merged = false;
      for (std::size_t i = 0; i < ids.size() && !merged; ++i) {
        auto& e = s.mesh_[static_cast<std::size_t>(ids[i])];
        if (e.multiplicity <= n.multiplicity && n.contains_across(e.extent)) {
          merged = true;
        } else if (e.multiplicity == n.multiplicity) {
          // The union is a box when the extents agree in all directions but one and touch or overlap in it.
          int differing = -1, count = 0;
          for (int j = 0; j < D; ++j)
            if (j != n.dir && (e.extent.lo[j] != n.extent.lo[j] || e.extent.hi[j] != n.extent.hi[j])) {
              differing = j;
              ++count;
            }
          if (count == 1 && e.extent.lo[differing] <= n.extent.hi[differing] &&
              n.extent.lo[differing] <= e.extent.hi[differing]) {
            n.extent.lo[differing] = std::min(n.extent.lo[differing], e.extent.lo[differing]);
            n.extent.hi[differing] = std::max(n.extent.hi[differing], e.extent.hi[differing]);
            merged = true;
          }
        }
        if (merged) {
          e.multiplicity = 0;
          ids.erase(ids.begin() + static_cast<std::ptrdiff_t>(i));
        }
      }
    }
    ids.push_back(static_cast<int>(s.mesh_.size()));
    s.mesh_.push_back(n);
    note_multiplicity(n);
  }

  // A mesh line that crosses B-spline b's support completely with more multiplicity than b's knots have,
  // decided from the rectangles of the planes strictly inside the support (a few per plane) rather than from
  // the support's elements (about 170 per B-spline on the 3D FULLSPAN benchmark). Multiplicity one: a plane
  // value that is not a knot and whose rectangles cover the support's cross-section. Higher multiplicities: the
  // plane's rectangles at an interior knot. On success the lines are in `candidates`, ascending: all
  // multiplicity-one lines of direction dir at once (splitting by all of them together avoids queueing the
  // intermediate B-splines), or one line otherwise.
  bool find_split(int b, int& dir) {
    const auto& fn = s.basis_[static_cast<std::size_t>(b)];
    const Box<D> S = fn.support();
    for (int k = 0; k < D; ++k) {
      const auto& y = fn.knots[k];
      const auto& v = plane_values[static_cast<std::size_t>(k)];
      candidates.clear();
      if (settled[static_cast<std::size_t>(b)] != k)
        for (auto it = std::upper_bound(v.begin(), v.end(), S.lo[k],
                                        [](double x, const PlaneEntry& a) { return x < a.value; });
             it != v.end() && it->value < S.hi[k]; ++it)
          if (std::find(y.begin(), y.end(), it->value) == y.end() && plane_covers(*it->ids, k, it->value, S, 1))
            candidates.push_back(it->value);
      if (!candidates.empty()) {
        dir = k;
        all_lines = true;
        return true;
      }
      if (interior_multiplicity > 1) {
        for (std::size_t i = 1; i + 1 < y.size(); ++i) {
          if (y[i] == y[i - 1] || !(S.lo[k] < y[i] && y[i] < S.hi[k])) continue;
          const int m = static_cast<int>(std::count(y.begin(), y.end(), y[i]));
          gather_plane(k, y[i], nullptr);
          if (mesh_covers<D>(plane_rects, k, y[i], S, m + 1)) {
            dir = k;
            all_lines = false;
            candidates.assign(1, y[i]);
            return true;
          }
        }
      }
    }
    return false;
  }

  // Splits b by the lines zs (ascending) of direction k, each crossing b's support completely: b's knots in k
  // with the lines inserted are a finer local knot sequence, and express_in writes B[y] exactly in its B-splines
  // (pieces of distinct knots, all with positive coefficients); then the pieces join the collection. Called
  // right after find_split(b) chose the lines.
  void split(int b, int k, std::span<const double> zs) {
    LRBSpline<D> fn = std::move(s.basis_[static_cast<std::size_t>(b)]);
    kill(b, knot_hash(fn));
    const int from = root[static_cast<std::size_t>(b)];
    const int p = s.degrees_[k];
    const auto& y = fn.knots[k];
    fine.resize(y.size() + zs.size());
    std::merge(y.begin(), y.end(), zs.begin(), zs.end(), fine.begin());
    coefs.resize(fine.size() - static_cast<std::size_t>(p) - 1);
    express_in<double>(y, fine, coefs.data());
    for (std::size_t j = 0; j < coefs.size(); ++j) {
      // Built in the reused `piece` (copy assignment keeps its storage): most pieces merge into an existing
      // B-spline, and only a new one takes the storage away; then the storage of a B-spline split before
      // (the same sizes) replaces it, so a split allocates nothing while split B-splines outnumber new ones.
      if (piece.coef.capacity() == 0 && !spare.empty()) {
        piece = std::move(spare.back());
        spare.pop_back();
      }
      piece.knots = fn.knots;
      piece.coef = fn.coef;
      piece.knots[k].assign(fine.begin() + static_cast<std::ptrdiff_t>(j),
                            fine.begin() + static_cast<std::ptrdiff_t>(j) + p + 2);
      piece.gamma = fn.gamma * coefs[j];
      add(piece, from, all_lines ? k : -1);
    }
    spare.push_back(std::move(fn));
  }

  // gamma c is what the function sees: keep sum gamma_i c_i for the merged B-spline.
  static void combine(LRBSpline<D>& old, const LRBSpline<D>& b) {
    // Sums of scaling factors that are 1 in exact arithmetic may round above it.
    const double g = std::min(old.gamma + b.gamma, 1.0);
    for (std::size_t i = 0; i < old.coef.size(); ++i) old.coef[i] = (old.gamma * old.coef[i] + b.gamma * b.coef[i]) / g;
    old.gamma = g;
  }

  void kill(int b, std::uint64_t h) {
    dead[static_cast<std::size_t>(b)] = 1;
    by_knots.erase(h, b);
  }

  // A piece descending from `from`; a merge keeps the old B-spline's list (or root: both supports contain it).
  // b is moved into the collection when it is new.
  void add(LRBSpline<D>& b, int from, int settled_dir) {
    const std::uint64_t h = knot_hash(b);
    const int same = by_knots.find(h, [&](int i) { return same_knots(s.basis_[static_cast<std::size_t>(i)], b); });
    if (same >= 0) {
      combine(s.basis_[static_cast<std::size_t>(same)], b);
      return;
    }
    const int id = static_cast<int>(s.basis_.size());
    s.basis_.push_back(std::move(b));
    list_at.push_back(pool.size());
    list_len.push_back(0);
    root.push_back(from);
    stale.push_back(id);
    dead.push_back(0);
    stamp.push_back(0);
    settled.push_back(static_cast<signed char>(settled_dir));
    by_knots.insert(h, id);
    enqueue(id);
  }

  void finish() {
    if (!changed) return;
    take_lists();
    resolve();
    refresh_lists();
    std::vector<int> order;
    order.reserve(s.basis_.size());
    for (std::size_t i = 0; i < s.basis_.size(); ++i)
      if (!dead[i]) order.push_back(static_cast<int>(i));
    // The B-splines from before the batch are in id order already: sort only the new ones and merge.
    const auto less = [&](int a, int b) {
      return knot_less(s.basis_[static_cast<std::size_t>(a)], s.basis_[static_cast<std::size_t>(b)]);
    };
    const auto fresh = std::lower_bound(order.begin(), order.end(), static_cast<int>(sorted_count));
    // The new ones are sorted on their knots copied into one flat row each (last direction first, so a row
    // compares lexicographically as knot_less does): the comparisons then read one contiguous row instead of
    // D separately allocated vectors.
    std::size_t width = 0;
    for (int k = 0; k < D; ++k) width += static_cast<std::size_t>(s.degrees_[k] + 2);
    std::vector<double> rows((s.basis_.size() - sorted_count) * width);
    for (auto it = fresh; it != order.end(); ++it) {
      double* row = rows.data() + (static_cast<std::size_t>(*it) - sorted_count) * width;
      for (int k = D - 1; k >= 0; --k) row = std::copy(s.basis_[static_cast<std::size_t>(*it)].knots[k].begin(),
                                                       s.basis_[static_cast<std::size_t>(*it)].knots[k].end(), row);
    }
    std::sort(fresh, order.end(), [&](int a, int b) {
      const double* ra = rows.data() + (static_cast<std::size_t>(a) - sorted_count) * width;
      const double* rb = rows.data() + (static_cast<std::size_t>(b) - sorted_count) * width;
      return std::lexicographical_compare(ra, ra + width, rb, rb + width);
    });
    std::inplace_merge(order.begin(), fresh, order.end(), less);
    std::vector<LRBSpline<D>> basis;
    std::vector<std::size_t> at;
    std::vector<int> len;
    basis.reserve(order.size());
    at.reserve(order.size());
    len.reserve(order.size());
    for (int i : order) {
      basis.push_back(std::move(s.basis_[static_cast<std::size_t>(i)]));
      at.push_back(list_at[static_cast<std::size_t>(i)]);
      len.push_back(list_len[static_cast<std::size_t>(i)]);
    }
    s.basis_ = std::move(basis);
    list_at = std::move(at);
    list_len = std::move(len);
    // The elements in id order: transpose twice (element lists ascending in B-spline id, renumbering the
    // elements on the way, then support lists ascending in element id) without a sort.
    const std::vector<int> corner = corner_order<D>(s.elements_, first_new_element);
    std::vector<int> new_id(corner.size());
    std::vector<Box<D>> elements(corner.size());
    for (std::size_t i = 0; i < corner.size(); ++i) {
      new_id[static_cast<std::size_t>(corner[i])] = static_cast<int>(i);
      elements[i] = s.elements_[static_cast<std::size_t>(corner[i])];
    }
    s.elements_ = std::move(elements);
    transpose_into(s.element_basis_, s.num_elements(), s.num_basis(), [this](int b) { return pooled_list(b); },
                   [&](int e) { return new_id[static_cast<std::size_t>(e)]; });
    // The support lists, sorted, into the pool's storage, which is large enough and needs no zero fill; every
    // list keeps its length.
    s.basis_elements_.ids = std::move(pool);
    transpose_into(s.basis_elements_, s.num_basis(), s.num_elements(), [this](int e) { return s.element_basis_[e]; },
                   std::identity{}, list_len);
    pooled = false;
    std::erase_if(s.mesh_, [](const Rect& r) { return r.multiplicity == 0; });
    s.evaluator_.reset();
  }
};

template <int D>
LRSpline<D>::LRSpline(const TensorSpline<D>& s) : dim_(s.dim()), rational_(s.is_rational()), domain_(s.domain()) {
  for (int k = 0; k < D; ++k) {
    require(s.knots(k).is_clamped(), "LRSpline: knot vector in direction " + std::to_string(k) + " is not clamped");
    degrees_[k] = s.degree(k);
  }
  const int st = stride();
  basis_.reserve(static_cast<std::size_t>(s.num_coefs()));
  for (int i = 0; i < s.num_coefs(); ++i) {
    const auto idx = s.multi_index(i);
    LRBSpline<D> b;
    for (int k = 0; k < D; ++k) {
      const auto& t = s.knots(k).knots();
      b.knots[k].assign(t.begin() + idx[k], t.begin() + idx[k] + degrees_[k] + 2);
    }
    b.coef.assign(s.coef(i), s.coef(i) + st);
    basis_.push_back(std::move(b));
  }
  std::array<std::vector<double>, D> breaks;
  for (int k = 0; k < D; ++k) {
    breaks[k] = s.knots(k).breakpoints();
    for (double v : breaks[k])
      mesh_.push_back(MeshRectangle<D>::make(k, v, domain_.lo, domain_.hi, s.knots(k).multiplicity(v)));
  }
  Ints<D> c{};
  for (;;) {
    Box<D> e;
    for (int k = 0; k < D; ++k) {
      e.lo[k] = breaks[k][c[k]];
      e.hi[k] = breaks[k][c[k] + 1];
    }
    elements_.push_back(e);
    int k = 0;
    for (; k < D; ++k) {
      if (++c[k] + 1 < static_cast<int>(breaks[k].size())) break;
      c[k] = 0;
    }
    if (k == D) break;
  }
  sort_basis();
  build_support_lists();
}

template <int D>
LRSpline<D>::LRSpline(const Ints<D>& degrees, int dim, bool rational, std::vector<LRBSpline<D>> basis,
                      std::vector<MeshRectangle<D>> mesh)
    : degrees_(degrees), dim_(dim), rational_(rational), basis_(std::move(basis)), mesh_(std::move(mesh)) {
  for (int k = 0; k < D; ++k)
    require(degrees_[k] >= 1 && degrees_[k] <= kMaxDegree,
            "LRSpline: degree " + std::to_string(degrees_[k]) + " in direction " + std::to_string(k) + " outside 1.." +
                std::to_string(kMaxDegree));
  require(dim_ >= 1, "LRSpline: control dimension " + std::to_string(dim_) + " is not positive");
  require(!mesh_.empty(), "LRSpline: empty mesh");
  domain_ = Box<D>::empty();
  for (std::size_t i = 0; i < mesh_.size(); ++i) {
    const auto& r = mesh_[i];
    const auto where = [&] { return "LRSpline: mesh rectangle " + std::to_string(i); };
    require(r.dir >= 0 && r.dir < D, [&] { return where() + ": direction out of range"; });
    for (int j = 0; j < D; ++j) {
      if (j == r.dir) continue;
      require(r.extent.lo[j] < r.extent.hi[j], [&] { return where() + ": empty extent in direction " + std::to_string(j); });
      domain_.lo[j] = std::min(domain_.lo[j], r.extent.lo[j]);
      domain_.hi[j] = std::max(domain_.hi[j], r.extent.hi[j]);
    }
    domain_.lo[r.dir] = std::min(domain_.lo[r.dir], r.value);
    domain_.hi[r.dir] = std::max(domain_.hi[r.dir], r.value);
  }
  for (int k = 0; k < D; ++k)
    require(domain_.lo[k] < domain_.hi[k], "LRSpline: the mesh spans no interval in direction " + std::to_string(k));
  for (std::size_t i = 0; i < mesh_.size(); ++i) {
    auto& r = mesh_[i];
    r.extent.lo[r.dir] = r.extent.hi[r.dir] = r.value;
    validate_rectangle(r, ("LRSpline: mesh rectangle " + std::to_string(i)).c_str());
  }
  const int st = stride();
  for (std::size_t i = 0; i < basis_.size(); ++i) {
    const auto& b = basis_[i];
    const auto where = [&] { return "LRSpline: B-spline " + std::to_string(i); };
    for (int k = 0; k < D; ++k) {
      const auto& y = b.knots[k];
      require(static_cast<int>(y.size()) == degrees_[k] + 2, [&] {
        return where() + ": " + std::to_string(y.size()) + " knots in direction " + std::to_string(k) + ", expected " +
               std::to_string(degrees_[k] + 2);
      });
      require(std::is_sorted(y.begin(), y.end()) && y.front() < y.back(),
              [&] { return where() + ": knots in direction " + std::to_string(k) + " decrease or span no interval"; });
      require(domain_.lo[k] <= y.front() && y.back() <= domain_.hi[k],
              [&] { return where() + ": support outside the domain in direction " + std::to_string(k); });
    }
    require(b.gamma > 0.0 && b.gamma <= 1.0 + kGammaSlack, [&] { return where() + ": scaling factor outside (0, 1]"; });
    require(static_cast<int>(b.coef.size()) == st, [&] {
      return where() + ": " + std::to_string(b.coef.size()) + " control values, expected " + std::to_string(st);
    });
  }
  // Elements: the domain cut by every rectangle (cutting whole elements; a rectangle that ends inside an element
  // is caught below, where it leaves an element it touches but does not cross completely).
  elements_.push_back(domain_);
  std::array<std::vector<double>, D> values;
  for (const auto& r : mesh_) values[static_cast<std::size_t>(r.dir)].push_back(r.value);
  std::size_t cells = 1;
  for (auto& v : values) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    cells = std::min<std::size_t>(cells * std::max<std::size_t>(v.size(), 1), std::size_t{1} << 20);
  }
  ElementGrid<D> grid(domain_, cells);
  grid.add(0, domain_);
  const auto touched = [&](const MeshRectangle<D>& r) {
    Box<D> q = r.extent;
    std::vector<int> out;
    grid.query(q, [&](int e) {
      const auto& el = elements_[static_cast<std::size_t>(e)];
      if (el.lo[r.dir] <= r.value && r.value <= el.hi[r.dir] && r.overlaps_across(el)) out.push_back(e);
    });
    return out;
  };
  std::unordered_map<PlaneKey, std::vector<const MeshRectangle<D>*>, PlaneHash> planes;
  for (const auto& r : mesh_) planes[{r.dir, r.value}].push_back(&r);
  // A plane cuts an element only where its rectangles together cross it completely: a T-junction rectangle
  // listed before the line it ends on must not cut beyond that line, and a plane given as several pieces (a
  // mesh rebuilt from knot lines, a file listing a cross as four half lines) cuts where their union crosses.
  // Repeat until no cut is left; the final elements do not depend on the order of the rectangles.
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& r : mesh_) {
      const int k = r.dir;
      const auto& plane = planes[{k, r.value}];
      for (int e : touched(r)) {
        auto& el = elements_[static_cast<std::size_t>(e)];
        if (!(el.lo[k] < r.value && r.value < el.hi[k])) continue;
        if (!r.contains_across(el) && !mesh_covers<D>(plane, k, r.value, el, 1)) continue;
        Box<D> upper = el;
        upper.lo[k] = r.value;
        el.hi[k] = r.value;
        elements_.push_back(upper);
        grid.add(static_cast<int>(elements_.size()) - 1, upper);
        changed = true;
      }
    }
  }
  for (std::size_t i = 0; i < mesh_.size(); ++i) {
    const auto& r = mesh_[i];
    const auto& plane = planes[{r.dir, r.value}];
    for (int e : touched(r)) {
      const auto& el = elements_[static_cast<std::size_t>(e)];
      // Where another rectangle of the plane covers the element face, r may end inside it.
      if (r.contains_across(el)) continue;
      const bool straddled = el.lo[r.dir] < r.value && r.value < el.hi[r.dir];
      require(!straddled && mesh_covers<D>(plane, r.dir, r.value, el, 1), [&] {
        return "LRSpline: mesh rectangle " + std::to_string(i) + " ends inside an element or an element face";
      });
    }
  }
  std::sort(elements_.begin(), elements_.end(), corner_less<D>);
  sort_basis();
  for (std::size_t i = 1; i < basis_.size(); ++i)
    require(!same_knots(basis_[i - 1], basis_[i]), "LRSpline: two B-splines with the same knots");
  build_support_lists();
  for (std::size_t i = 0; i < basis_.size(); ++i) {
    const Box<D> S = basis_[i].support();
    double volume = 1.0, covered = 0.0;
    for (int k = 0; k < D; ++k) volume *= S.extent(k);
    for (int e : basis_elements_[static_cast<int>(i)]) {
      const auto& el = elements_[static_cast<std::size_t>(e)];
      double v = 1.0;
      for (int k = 0; k < D; ++k) v *= el.extent(k);
      covered += v;
    }
    require(std::abs(covered - volume) <= 1e-12 * volume,
            "LRSpline: the support of a B-spline (knots starting at " + std::to_string(S.lo[0]) +
                ") is not a union of elements");
  }
  check_partition_of_unity();
}

// On an element, sum gamma_i B_i is a tensor polynomial; it is 1 exactly when all its Bernstein coefficients
// are 1 (the Bernstein polynomials are a basis summing to one). The coefficients are the gamma-weighted sums of
// outer products of the B-splines' univariate Bernstein rows, so the test is exact up to rounding and needs no
// sample points. A deleted B-spline, a wrong scaling factor or an element no support covers fails it.
template <int D>
void LRSpline<D>::check_partition_of_unity() const {
  std::size_t n = 1;
  for (int k = 0; k < D; ++k) n *= static_cast<std::size_t>(degrees_[k] + 1);
  std::vector<double> sum(n), term(n);
  std::array<std::vector<double>, D> rows;
  for (int k = 0; k < D; ++k) rows[k].resize(static_cast<std::size_t>(degrees_[k] + 1));
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Box<D>& el = elements_[e];
    std::fill(sum.begin(), sum.end(), 0.0);
    for (int b : element_basis_[static_cast<int>(e)]) {
      const LRBSpline<D>& fn = basis_[static_cast<std::size_t>(b)];
      for (int k = 0; k < D; ++k)
        bernstein_coefficients<double>(fn.knots[k], el.lo[k], el.hi[k], rows[k].data());
      // Outer product, direction 0 fastest.
      term[0] = fn.gamma;
      std::size_t len = 1;
      for (int k = 0; k < D; ++k) {
        const std::size_t m = rows[k].size();
        for (std::size_t j = m; j-- > 0;)
          for (std::size_t i = 0; i < len; ++i) term[j * len + i] = term[i] * rows[k][j];
        len *= m;
      }
      for (std::size_t i = 0; i < n; ++i) sum[i] += term[i];
    }
    for (std::size_t i = 0; i < n; ++i)
      require(std::abs(sum[i] - 1.0) <= 1e-9, [&] {
        std::string box;
        for (int k = 0; k < D; ++k)
          box += (k ? " x [" : "[") + format_number(el.lo[k]) + ", " + format_number(el.hi[k]) + "]";
        return "LRSpline: the scaled B-splines do not sum to one on element " + box + " (" +
               std::to_string(element_basis_[static_cast<int>(e)].size()) + " B-splines there, Bernstein coefficient " +
               format_number(sum[i]) + "): a B-spline is missing or a scaling factor is wrong";
      });
  }
}

template <int D>
void LRSpline<D>::reorder_elements(std::span<const int> order) {
  const std::size_t n = elements_.size();
  require(order.size() == n, "LRSpline::reorder_elements: " + std::to_string(order.size()) + " ids for " +
                                 std::to_string(n) + " elements");
  std::vector<int> new_id(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const int e = order[i];
    require(e >= 0 && static_cast<std::size_t>(e) < n && new_id[static_cast<std::size_t>(e)] < 0,
            "LRSpline::reorder_elements: not a permutation of the element ids (entry " + std::to_string(i) + ")");
    new_id[static_cast<std::size_t>(e)] = static_cast<int>(i);
  }
  std::vector<Box<D>> elements(n);
  Incidence element_basis;
  element_basis.offsets.reserve(n + 1);
  element_basis.ids.reserve(element_basis_.ids.size());
  for (std::size_t i = 0; i < n; ++i) {
    elements[i] = elements_[static_cast<std::size_t>(order[i])];
    const auto list = element_basis_[order[i]];
    element_basis.ids.insert(element_basis.ids.end(), list.begin(), list.end());
    element_basis.offsets.push_back(static_cast<int>(element_basis.ids.size()));
  }
  elements_ = std::move(elements);
  element_basis_ = std::move(element_basis);
  basis_elements_ = element_basis_.transposed(num_basis());
  evaluator_.reset();
}

template <int D>
void LRSpline<D>::validate_rectangle(const MeshRectangle<D>& r, const char* who) const {
  const int k = r.dir;
  const auto where = [&] {
    return std::string(who) + " (direction " + std::to_string(k) + " at " + std::to_string(r.value) + ")";
  };
  require(k >= 0 && k < D, [&] { return where() + ": direction out of range"; });
  require(r.multiplicity >= 1 && r.multiplicity <= degrees_[k] + 1,
          [&] { return where() + ": multiplicity " + std::to_string(r.multiplicity) + " outside 1..p+1"; });
  require(domain_.lo[k] <= r.value && r.value <= domain_.hi[k], [&] { return where() + ": value outside the domain"; });
  for (int j = 0; j < D; ++j)
    if (j != k)
      require(domain_.lo[j] <= r.extent.lo[j] && r.extent.lo[j] < r.extent.hi[j] && r.extent.hi[j] <= domain_.hi[j],
              [&] { return where() + ": extent in direction " + std::to_string(j) + " empty or outside the domain"; });
}

template <int D>
void LRSpline<D>::sort_basis() {
  std::sort(basis_.begin(), basis_.end(), knot_less<D>);
}

template <int D>
void LRSpline<D>::build_support_lists() {
  ElementGrid<D> grid(domain_, elements_.size());
  for (std::size_t e = 0; e < elements_.size(); ++e) grid.add(static_cast<int>(e), elements_[e]);
  basis_elements_ = {};
  basis_elements_.offsets.reserve(basis_.size() + 1);
  auto& ids = basis_elements_.ids;
  for (std::size_t i = 0; i < basis_.size(); ++i) {
    const Box<D> S = basis_[i].support();
    const std::size_t first = ids.size();
    grid.query(S, [&](int e) {
      if (center_inside(elements_[static_cast<std::size_t>(e)], S)) ids.push_back(e);
    });
    std::sort(ids.begin() + static_cast<std::ptrdiff_t>(first), ids.end());
    basis_elements_.offsets.push_back(static_cast<int>(ids.size()));
  }
  element_basis_ = basis_elements_.transposed(num_elements());
}

template <int D>
bool LRSpline<D>::insert(const MeshRectangle<D>& r) {
  validate_rectangle(r, "LRSpline::insert: mesh rectangle");
  require(r.value > domain_.lo[r.dir] && r.value < domain_.hi[r.dir],
          "LRSpline::insert: mesh rectangle in direction " + std::to_string(r.dir) + " at " + std::to_string(r.value) +
              ": value not inside the domain");
  Batch batch(*this);
  const bool inserted = batch.insert_one(r, true);
  batch.finish();
  return inserted;
}

template <int D>
int LRSpline<D>::insert(std::span<const MeshRectangle<D>> rects) {
  for (std::size_t i = 0; i < rects.size(); ++i) {
    const auto& r = rects[i];
    const std::string who = "LRSpline::insert: mesh rectangle " + std::to_string(i);
    validate_rectangle(r, who.c_str());
    require(r.value > domain_.lo[r.dir] && r.value < domain_.hi[r.dir], who + ": value not inside the domain");
  }
  if (rects.empty()) return 0;
  Batch batch(*this);
  int count = 0;
  try {
    for (const auto& r : rects)
      if (batch.insert_one(r, false)) ++count;
  } catch (...) {
    batch.finish();
    throw;
  }
  batch.finish();
  return count;
}

template <int D>
const ElementEvaluator<D>& LRSpline<D>::evaluator() const {
  if (const auto* p = evaluator_.ready.load(std::memory_order_acquire)) return *p;
  std::lock_guard lock(evaluator_.mutex);
  if (!evaluator_.owner) {
    evaluator_.owner = std::make_shared<const ElementEvaluator<D>>(
        degrees_, dim_, rational_, domain_, std::span<const LRBSpline<D>>(basis_), std::span<const Box<D>>(elements_), element_basis_);
    evaluator_.ready.store(evaluator_.owner.get(), std::memory_order_release);
  }
  return *evaluator_.owner;
}

template <int D>
void LRSpline<D>::eval(const Param<D>& u, double* out) const {
  evaluator().eval(u, out);
}

template <int D>
void LRSpline<D>::eval_first_derivatives(const Param<D>& u, double* out) const {
  evaluator().eval_first_derivatives(u, out);
}

template <int D>
void LRSpline<D>::eval_many(std::span<const Param<D>> u, std::span<double> out, int threads) const {
  const auto n = static_cast<std::size_t>(dim_);
  require(out.size() >= u.size() * n, "LRSpline::eval_many: output holds fewer than points * dim values");
  const auto& ev = evaluator();
  parallel_for(static_cast<std::ptrdiff_t>(u.size()), threads,
               [&](std::ptrdiff_t i) { ev.eval(u[static_cast<std::size_t>(i)], out.data() + static_cast<std::size_t>(i) * n); });
}

template <int D>
void LRSpline<D>::eval_first_derivatives_many(std::span<const Param<D>> u, std::span<double> out, int threads) const {
  const auto n = static_cast<std::size_t>((D + 1) * dim_);
  require(out.size() >= u.size() * n,
          "LRSpline::eval_first_derivatives_many: output holds fewer than points * (D + 1) * dim values");
  const auto& ev = evaluator();
  parallel_for(static_cast<std::ptrdiff_t>(u.size()), threads, [&](std::ptrdiff_t i) {
    ev.eval_first_derivatives(u[static_cast<std::size_t>(i)], out.data() + static_cast<std::size_t>(i) * n);
  });
}

template class LRSpline<2>;
template class LRSpline<3>;

}  // namespace trivar
