#pragma once
// Departures from ISO 10303-21 that a lenient reader accepts: lower-case keywords and enumerations, stray
// bytes in strings, references to no instance from instances a filter skipped (the geometry's own dangling
// references are errors), and reference cycles. Real files from old or careless writers carry them, so by
// default each kind becomes one warning line naming where it first occurred and how often it occurred; a
// strict reader refuses the first occurrence with that line as a trivar::Error.
#include <cstddef>
#include <string>
#include <vector>

namespace trivar::io::step {

enum class Departure { lowercase_keyword, stray_bytes, dangling_reference, reference_cycle };

struct ReadWarning {
  Departure kind;
  std::string first;       // "file:line:column: #id: what" of the first occurrence
  std::size_t count = 0;   // occurrences in the file
  // The warning line: `first`, plus "(N occurrences in the file)" when there was more than one.
  std::string text() const;
};

class ReadWarnings {
public:
  explicit ReadWarnings(bool strict = false) : strict_(strict) {}

  // One occurrence; `message` is called only for the first of its kind (or to throw it when strict).
  template <class Message>
  void note(Departure kind, Message&& message) {
    for (ReadWarning& w : list_)
      if (w.kind == kind) {
        ++w.count;
        return;
      }
    add(kind, message());
  }
  bool strict() const { return strict_; }
  std::vector<ReadWarning> take() { return std::move(list_); }

private:
  void add(Departure kind, std::string first);  // throws when strict
  bool strict_;
  std::vector<ReadWarning> list_;
};

}  // namespace trivar::io::step
