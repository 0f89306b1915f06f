#pragma once
// Large allocations are estimated before they are made, so a request that cannot fit ends in a one-line
// message naming the request and the memory it would need, instead of std::bad_alloc or the OOM killer.
#include <cstdint>
#include <string>

namespace trivar {

// Memory the system can still give this process, in bytes: MemAvailable of /proc/meminfo, or the
// physical memory where that is not readable.
double available_memory_bytes();

// "1.5 GiB", "312 MiB", "4.0 KiB", "12 bytes".
std::string format_bytes(double bytes);

// Throws Error("<request> would need <bytes> of memory, more than the <available> available") when
// `bytes` (an estimate, kept in double so products of huge counts cannot overflow) exceeds `available`.
void require_memory(double bytes, const std::string& request, double available = available_memory_bytes());

}  // namespace trivar
