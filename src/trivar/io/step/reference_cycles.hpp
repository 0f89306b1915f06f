#pragma once
// Reference cycles are legal ISO 10303-21 grammar but no AP schema's data needs one (a geometric or
// topological definition cannot depend on itself), so the reader warns about the first one (refuses it in
// strict mode). A mapper that needs acyclic data checks the part it walks with these functions.
#include <cstdint>
#include <vector>

#include "trivar/io/step/exchange_file.hpp"

namespace trivar::io::step {

// The ids `p` refers to (inside lists and typed parameters too), appended to `out`.
void collect_references(const Parameter& p, std::vector<std::uint64_t>& out);

// A cycle reachable from `root` through references between instances, kept or skipped by the reader, as the ids along it with the
// first id repeated at the end (#3 -> #5 -> #3 gives {3, 5, 3}); empty when there is none. Iterative, so
// long reference chains do not exhaust the stack.
std::vector<std::uint64_t> find_reference_cycle(const ExchangeFile& file, std::uint64_t root);
// The first cycle through `roots`, searched in that order; `roots` must hold every instance that refers to
// another (the parser collects them), as the others are not looked at.
std::vector<std::uint64_t> find_reference_cycle(const ExchangeFile& file, const std::vector<std::uint64_t>& roots);
// The same over the whole file (kept instances first, in file order, then skipped ones).
std::vector<std::uint64_t> find_reference_cycle(const ExchangeFile& file);

}  // namespace trivar::io::step
