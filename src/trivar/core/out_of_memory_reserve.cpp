#include "trivar/core/out_of_memory_reserve.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace trivar {

namespace {

std::atomic<void*> g_reserve{nullptr};

// The failed allocation still fails (retrying it could take the room the unwinding needs); freeing the reserve
// returns its pages and address space to the system before the destructors run.
void release_reserve_and_fail() {
  std::free(g_reserve.exchange(nullptr));
  throw std::bad_alloc();
}

}  // namespace

void install_out_of_memory_reserve(std::size_t bytes) {
  std::free(g_reserve.exchange(std::malloc(bytes)));
  std::set_new_handler(release_reserve_and_fail);
}

}  // namespace trivar
