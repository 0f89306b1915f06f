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

void ExchangeFile::note_skipped(std::uint64_t id, const std::string& type_name) {
  require(all_ids_.insert(id), [&] { return "#" + std::to_string(id) + ": duplicate instance id"; });
  skipped_ids_.insert(id);
  max_id_ = std::max(max_id_, id);
  ++skipped_counts_[type_name];
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

}  // namespace

void ExchangeFile::check_references(const std::string& where) const {
  for (const Instance& i : instances_)
    for (const Record& r : i.records)
      for (const Parameter& p : r.params)
        if (const std::uint64_t d = first_dangling(p, all_ids_)) {
          std::string m = where;
          if (i.line > 0) {
            if (!m.empty()) m += ':';
            m += std::to_string(i.line);
            m += ':';
            m += std::to_string(i.column);
          }
          if (!m.empty()) m += ": ";
          m += '#';
          m += std::to_string(i.id);
          m += ": " + r.keyword + " refers to undefined instance #" + std::to_string(d);
          throw Error(m);
        }
}

}  // namespace trivar::io::step
