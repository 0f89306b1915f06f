#pragma once
// Reference cycles are legal in ISO 10303-21 (e.g. topology that points back at its owner), so the reader
// accepts them. A mapper that needs acyclic data (geometry definitions: a point cannot be defined by
// itself) checks the part it walks with these functions and reports the cycle they return.
#include <cstdint>
#include <vector>

#include "trivar/io/step/exchange_file.hpp"

namespace trivar::io::step {

// A cycle reachable from `root` through references between kept instances, as the ids along it with the
// first id repeated at the end (#3 -> #5 -> #3 gives {3, 5, 3}); empty when there is none. Iterative, so
// long reference chains do not exhaust the stack.
std::vector<std::uint64_t> find_reference_cycle(const ExchangeFile& file, std::uint64_t root);
// The same over the whole file.
std::vector<std::uint64_t> find_reference_cycle(const ExchangeFile& file);

}  // namespace trivar::io::step
