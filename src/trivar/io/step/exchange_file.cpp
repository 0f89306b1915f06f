#include "trivar/io/step/exchange_file.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"

namespace trivar::io::step {

const Instance* ExchangeFile::find(std::uint64_t id) const {
  const auto it = index_.find(id);
  return it == index_.end() ? nullptr : &instances_[it->second];
}

const Instance& ExchangeFile::at(std::uint64_t id) const {
  const Instance* i = find(id);
  if (!i) throw Error("#" + std::to_string(id) + ": no such instance" + (is_skipped(id) ? " (skipped by the reader's filter)" : ""));
  return *i;
}

const Instance& ExchangeFile::insert(Instance instance) {
  require(instance.id > 0, "instance id must be positive");
  require(!instance.records.empty(), [&] { return "#" + std::to_string(instance.id) + ": instance without records"; });
  require(all_ids_.insert(instance.id), [&] { return "#" + std::to_string(instance.id) + ": duplicate instance id"; });
  max_id_ = std::max(max_id_, instance.id);
  index_.emplace(instance.id, instances_.size());
  instances_.push_back(std::move(instance));
  return instances_.back();
}

std::uint64_t ExchangeFile::add(Record record) {
  Instance i{max_id_ + 1, {}, false};
  i.records.push_back(std::move(record));
  return insert(std::move(i)).id;
}

std::uint64_t ExchangeFile::add_complex(std::vector<Record> records) {
  return insert(Instance{max_id_ + 1, std::move(records), true}).id;
}

void ExchangeFile::insert_point(const Point& point) {
  require(point.id > 0, "instance id must be positive");
  require(all_ids_.insert(point.id), [&] { return "#" + std::to_string(point.id) + ": duplicate instance id"; });
  max_id_ = std::max(max_id_, point.id);
  points_.push_back(point);
}

const ExchangeFile::Point* ExchangeFile::point(std::uint64_t id) const {
  const auto it = std::lower_bound(points_.begin(), points_.end(), id, [](const Point& p, std::uint64_t i) { return p.id < i; });
  return it != points_.end() && it->id == id ? &*it : nullptr;
}

void ExchangeFile::sort_points() {
  const auto by_id = [](const Point& a, const Point& b) { return a.id < b.id; };
  if (!std::is_sorted(points_.begin(), points_.end(), by_id)) std::sort(points_.begin(), points_.end(), by_id);
}

void ExchangeFile::note_skipped(std::uint64_t id, const std::string& type_name, std::uint32_t line,
                                std::uint32_t column, const std::vector<std::uint64_t>& references) {
  require(all_ids_.insert(id), [&] { return "#" + std::to_string(id) + ": duplicate instance id"; });
  skipped_ids_.insert(id);
  max_id_ = std::max(max_id_, id);
  const auto counted = skipped_counts_.try_emplace(type_name, 0).first;
  ++counted->second;
  skipped_references_.insert(skipped_references_.end(), references.begin(), references.end());
  skipped_list_.push_back({id, &counted->first, line, column, skipped_references_.size()});
}

std::span<const std::uint64_t> ExchangeFile::skipped_references(std::size_t index) const {
  const std::size_t begin = index == 0 ? 0 : skipped_list_[index - 1].references_end;
  return {skipped_references_.data() + begin, skipped_list_[index].references_end - begin};
}

std::size_t ExchangeFile::skipped_total() const {
  std::size_t n = 0;
  for (const auto& [keyword, count] : skipped_counts_) n += count;
  return n;
}

namespace {

// First reference below p that names no defined instance, or 0.
std::uint64_t first_dangling(const Parameter& p, const IdSet& ids) {
  switch (p.kind()) {
    case Kind::reference: {
      const std::uint64_t id = p.get_if<Reference>()->id;
      return ids.contains(id) ? 0 : id;
    }
    case Kind::list:
      for (const Parameter& q : p.get_if<List>()->items)
        if (const std::uint64_t d = first_dangling(q, ids)) return d;
      return 0;
    case Kind::typed: return first_dangling(p.get_if<Typed>()->value(), ids);
    default: return 0;
  }
}

// "where:line:column: #id: KEYWORD refers to undefined instance #target".
std::string dangling_message(const std::string& where, std::uint32_t line, std::uint32_t column, std::uint64_t id,
                             const std::string& keyword, std::uint64_t target) {
  std::string m = where;
  if (line > 0) {
    if (!m.empty()) m += ':';
    m += std::to_string(line);
    m += ':';
    m += std::to_string(column);
  }
  if (!m.empty()) m += ": ";
  m += '#';
  m += std::to_string(id);
  m += ": " + keyword + " refers to undefined instance #" + std::to_string(target);
  return m;
}

}  // namespace

void ExchangeFile::check_references(const std::string& where, ReadWarnings* sink) const {
  for (const Instance& i : instances_)
    for (const Record& r : i.records)
      for (const Parameter& p : r.params)
        if (const std::uint64_t d = first_dangling(p, all_ids_))
          throw Error(dangling_message(where, i.line, i.column, i.id, r.keyword, d));
  if (!sink) return;
  for (std::size_t k = 0; k < skipped_list_.size(); ++k)
    for (const std::uint64_t target : skipped_references(k))
      if (!all_ids_.contains(target)) {
        const Skipped& s = skipped_list_[k];
        sink->note(Departure::dangling_reference,
                       [&] { return dangling_message(where, s.line, s.column, s.id, *s.type_name, target); });
      }
}

}  // namespace trivar::io::step
