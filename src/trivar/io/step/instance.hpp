#pragma once
// Entity instances of a P21 data section. A simple instance `#n=A(..);` has one record; a complex
// instance `#n=(A(..)B(..));` has one partial record per entity of the complex type, each with only its
// own attributes. Unknown entities are kept as they are: the layer knows the grammar, not the schemas.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "trivar/io/step/parameter.hpp"

namespace trivar::io::step {

// KEYWORD(parameters): a simple instance's body, one partial record of a complex instance, or a header entity.
struct Record {
  std::string keyword;  // upper case; user-defined keywords keep their leading '!'
  std::vector<Parameter> params;
  friend bool operator==(const Record&, const Record&) = default;
};

struct Instance {
  std::uint64_t id = 0;
  std::vector<Record> records;
  bool complex = false;  // written as #n=(...); even with a single record
  // Where the instance starts in the file it was read from (0 when built in memory), for mapper messages.
  std::uint32_t line = 0, column = 0;

  // The record with this keyword (the only record of a simple instance, a partial record of a complex one).
  const Record* record(std::string_view keyword) const {
    for (const Record& r : records)
      if (r.keyword == keyword) return &r;
    return nullptr;
  }
  bool is(std::string_view keyword) const { return record(keyword) != nullptr; }
  // Keyword of a simple instance; for messages about complex ones, the keywords joined by '+'.
  std::string type_name() const {
    std::string s;
    for (const Record& r : records) {
      if (!s.empty()) s += '+';
      s += r.keyword;
    }
    return s;
  }
  // Equal content; the position in the source file does not count.
  friend bool operator==(const Instance& a, const Instance& b) {
    return a.id == b.id && a.complex == b.complex && a.records == b.records;
  }
};

}  // namespace trivar::io::step
