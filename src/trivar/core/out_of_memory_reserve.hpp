#pragma once
// Some destructors allocate: nlohmann::json, for one, moves the elements of a large array onto a heap-allocated
// stack while destroying it. When such a destructor runs while unwinding from std::bad_alloc, its own failing
// allocation terminates the program ("terminate called after throwing std::bad_alloc"). A reserve of memory
// taken at start and released at the first failed allocation gives that unwinding room to finish, so the
// std::bad_alloc reaches the caller, which can report it and exit cleanly.
#include <cstddef>

namespace trivar {

// Reserves `bytes` (address space only: the pages are never touched) and installs a new-handler that releases
// the reserve and throws std::bad_alloc. Call once at program start.
void install_out_of_memory_reserve(std::size_t bytes);

}  // namespace trivar
