#pragma once
// An ISO 10303-21 exchange structure in memory: the header and the instances of all data sections in one
// store keyed by id, in the order they were read or added (the order a writer numbers them in).
// A reader with a keyword filter keeps only some instances; the ids of the others are still known
// (skipped()), so a reference into the dropped part is not mistaken for a dangling one.
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "trivar/io/step/id_set.hpp"
#include "trivar/io/step/instance.hpp"

namespace trivar::io::step {

// The three mandatory header entities, decoded; any other header entity is kept verbatim in `extra`.
struct Header {
  std::vector<std::string> description;     // FILE_DESCRIPTION.description
  std::string implementation_level = "2;1"; // FILE_DESCRIPTION.implementation_level
  std::string name;                         // FILE_NAME.name
  std::string time_stamp;                   // as read; a writer stamps its own time
  std::vector<std::string> author, organization;
  std::string preprocessor_version;         // as read; a writer names itself ("trivar <version>")
  std::string originating_system, authorization;
  std::vector<std::string> schemas;         // FILE_SCHEMA
  std::vector<Record> extra;                // e.g. FILE_POPULATION, SECTION_LANGUAGE, user-defined
};

class ExchangeFile {
public:
  Header header;

  // A deque: growing it never moves instances (no copies of large stores, stable references).
  const std::deque<Instance>& instances() const { return instances_; }
  std::size_t size() const { return instances_.size(); }
  const Instance* find(std::uint64_t id) const;
  // Throws trivar::Error "#id: no such instance" when absent.
  const Instance& at(std::uint64_t id) const;

  // Adds an instance with its own id; throws trivar::Error on a duplicate id (kept or skipped).
  const Instance& insert(Instance instance);
  // Add with the next free id (largest id so far + 1); return that id.
  std::uint64_t add(Record record);
  std::uint64_t add_complex(std::vector<Record> records);

  // Instances that a reader's filter dropped: their ids and how many of each keyword (complex instances
  // count under Instance::type_name()).
  void note_skipped(std::uint64_t id, const std::string& type_name);
  bool is_skipped(std::uint64_t id) const { return skipped_ids_.contains(id) && !find(id); }
  const std::map<std::string, std::size_t>& skipped() const { return skipped_counts_; }
  std::size_t skipped_total() const;

  // Every id defined in the source (kept or skipped), for duplicate detection while reading.
  bool defines(std::uint64_t id) const { return all_ids_.contains(id); }
  // Throws trivar::Error "where: #id: reference to undefined instance #r" for the first reference that
  // points at no instance, kept or skipped. `where` prefixes the message (file name:line:column of the
  // referencing instance is added when known). Reference cycles are legal here; see reference_cycles.hpp.
  void check_references(const std::string& where = "") const;

private:
  std::deque<Instance> instances_;
  std::unordered_map<std::uint64_t, std::size_t> index_;
  IdSet all_ids_, skipped_ids_;
  std::map<std::string, std::size_t> skipped_counts_;
  std::uint64_t max_id_ = 0;
};

}  // namespace trivar::io::step
