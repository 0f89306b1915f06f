#include "trivar/core/memory_budget.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "trivar/core/error.hpp"

namespace trivar {

double available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024.0;
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page_size > 0 ? static_cast<double>(pages) * static_cast<double>(page_size) : 0.0;
}

std::string format_bytes(double bytes) {
  static const char* const units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (!(bytes >= 1024.0)) {
    std::ostringstream s;
    s << static_cast<long long>(std::isfinite(bytes) ? bytes : 0.0) << " bytes";
    return s.str();
  }
  int unit = -1;
  while (bytes >= 1024.0 && unit < 5) {
    bytes /= 1024.0;
    ++unit;
  }
  char text[64];
  std::snprintf(text, sizeof text, bytes < 10 ? "%.1f %s" : "%.0f %s", bytes, units[unit]);
  return text;
}

void require_memory(double bytes, const std::string& request, double available) {
  require(std::isfinite(bytes) && bytes <= available, [&] {
    const std::string need = std::isfinite(bytes) ? format_bytes(bytes) : "an unbounded amount";
    return request + " would need " + need + " of memory, more than the " + format_bytes(available) +
           " available";
  });
}

}  // namespace trivar
