#pragma once
// An ISO 10303-21 exchange structure in memory: the header and the instances of all data sections in one
// store keyed by id, in the order they were read or added (the order a writer numbers them in).
// A reader with a keyword filter keeps only some instances; the ids of the others are still known
// (skipped()), so a reference into the dropped part is not mistaken for a dangling one.
#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "trivar/io/step/id_set.hpp"
#include "trivar/io/step/instance.hpp"
#include "trivar/io/step/read_warnings.hpp"

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

  // CARTESIAN_POINTs with an empty name, held compactly when the reader is asked to
  // (ReadOptions::compact_points): the bulk of a CAD file's geometry then costs 40 bytes a point instead of
  // a generic instance. They are not in instances() and find() does not see them.
  struct Point {
    std::uint64_t id = 0;
    std::array<double, 3> coordinates{};
    int dimension = 0;  // 1 to 3
  };
  void insert_point(const Point& point);  // throws trivar::Error on a duplicate id
  const Point* point(std::uint64_t id) const;
  std::size_t point_count() const { return points_.size(); }
  // Brings the points into id order after reading (the reader calls it; lookups need it).
  void sort_points();

  // Instances that a reader's filter dropped: their ids, how many of each keyword (complex instances
  // count under Instance::type_name()), and the references their bodies hold (for the dangling-reference
  // and cycle checks; ids only, so this costs a few bytes per reference).
  struct Skipped {
    std::uint64_t id = 0;
    const std::string* type_name = nullptr;  // a key of skipped()
    std::uint32_t line = 0, column = 0;
    std::size_t references_end = 0;  // this instance's references end here in the shared list
  };
  void note_skipped(std::uint64_t id, const std::string& type_name, std::uint32_t line = 0, std::uint32_t column = 0,
                    const std::vector<std::uint64_t>& references = {});
  const std::vector<Skipped>& skipped_instances() const { return skipped_list_; }
  // The references of skipped_instances()[index].
  std::span<const std::uint64_t> skipped_references(std::size_t index) const;
  bool is_skipped(std::uint64_t id) const { return skipped_ids_.contains(id) && !find(id); }
  const std::map<std::string, std::size_t>& skipped() const { return skipped_counts_; }
  std::size_t skipped_total() const;

  // Every id defined in the source (kept or skipped), for duplicate detection while reading.
  bool defines(std::uint64_t id) const { return all_ids_.contains(id); }
  // Throws trivar::Error "where:line:column: #id: KEYWORD refers to undefined instance #r" for the first
  // reference of a kept instance that points at no instance, kept or skipped. `where` prefixes the message.
  // The same in a skipped instance is noted in `sink` (nothing happens without one).
  // Reference cycles are legal here; see reference_cycles.hpp.
  void check_references(const std::string& where = "", ReadWarnings* sink = nullptr) const;

  // What the reader accepted leniently, one line per kind (read_warnings.hpp).
  std::vector<ReadWarning> warnings;

private:
  std::deque<Instance> instances_;
  std::unordered_map<std::uint64_t, std::size_t> index_;
  IdSet all_ids_, skipped_ids_;
  std::map<std::string, std::size_t> skipped_counts_;
  std::vector<Skipped> skipped_list_;
  std::deque<Point> points_;  // by id after sort_points(); a deque grows without a moment of two copies
  std::vector<std::uint64_t> skipped_references_;
  std::uint64_t max_id_ = 0;
};

}  // namespace trivar::io::step
