#pragma once
// One ASCII <DataArray> of a VTK XML file: one tuple per line, scalars eight to a line; reals in shortest
// round-trip form, integers of any width as numbers.
#include <cstddef>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

#include "trivar/core/number_format.hpp"
#include "trivar/io/xml_text.hpp"

namespace trivar::io {

template <class T>
void write_data_array(std::ostream& os, const char* type, const std::string& name, int components,
                      const std::vector<T>& v) {
  os << "        <DataArray type=\"" << type << "\"";
  if (!name.empty()) os << " Name=\"" << xml_escape(name) << "\"";
  os << " NumberOfComponents=\"" << components << "\" format=\"ascii\">\n";
  const std::size_t per_line = components == 1 ? 8 : static_cast<std::size_t>(components);
  for (std::size_t i = 0; i < v.size(); ++i) {
    os << (i % per_line == 0 ? "          " : " ");
    if constexpr (std::is_floating_point_v<T>)
      write_number(os, v[i]);
    else
      os << static_cast<long long>(v[i]);
    if ((i + 1) % per_line == 0 || i + 1 == v.size()) os << '\n';
  }
  os << "        </DataArray>\n";
}

}  // namespace trivar::io
