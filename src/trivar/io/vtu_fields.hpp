#pragma once
// Checks of the caller's extra data arrays of a .vtu writer (point or cell fields: anything with name,
// components and value), shared so every writer rejects the same mistakes with the same messages.
#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar::io {

// kind: "point field" or "cell field"; reserved: the names the writer uses itself for that kind of data.
template <class Field>
void validate_fields(const std::string& path, const char* kind, const std::vector<Field>& fields,
                     std::span<const char* const> reserved) {
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const Field& field = fields[f];
    const std::string what = path + ": " + kind;
    require(!field.name.empty(), what + " " + std::to_string(f) + " has no name");
    require(field.components >= 1, what + " '" + field.name + "' needs >= 1 components");
    require(static_cast<bool>(field.value), what + " '" + field.name + "' has no value function");
    require(std::find(reserved.begin(), reserved.end(), field.name) == reserved.end(),
            what + " name '" + field.name + "' is reserved");
    for (std::size_t g = 0; g < f; ++g)
      require(fields[g].name != field.name, path + ": duplicate " + kind + " name '" + field.name + "'");
  }
}

}  // namespace trivar::io
