#include "trivar/core/interrupt_cleanup.hpp"

#include <array>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <mutex>

#include <dirent.h>
#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace trivar {

namespace {

// Slots hold the registered paths. The handler may only call async-signal-safe functions, so the registry is a
// fixed array of atomic pointers: registering stores a pointer to the owner's string, releasing exchanges it
// back to null. The handler exchanges each slot to null too, so exactly one side sees a path.
// 4096 slots leave room for one temporary file per thread at any thread count trivar accepts.
constexpr std::size_t kSlots = 4096;
std::array<std::atomic<const char*>, kSlots> g_slots{};
// Set by the handler: threads still running create no new temporaries while it removes the old ones.
std::atomic<bool> g_interrupted{false};

// Removes everything under the open directory `dir` (then closes it), using system calls only: getdents64 into
// a stack buffer instead of readdir, which may allocate. Depth is bounded because trivar's temporary folders are
// at most two levels deep.
void remove_contents(int dir, int depth) {
  alignas(8) char buf[4096];
  for (bool removed = true; removed;) {
    removed = false;
    const long n = ::syscall(SYS_getdents64, dir, buf, sizeof buf);
    if (n <= 0) break;
    for (long off = 0; off < n;) {
      struct Entry {
        unsigned long long ino;
        long long off;
        unsigned short reclen;
        unsigned char type;
        char name[1];
      };
      const auto* e = reinterpret_cast<const Entry*>(buf + off);
      off += e->reclen;
      if (std::strcmp(e->name, ".") == 0 || std::strcmp(e->name, "..") == 0) continue;
      if (e->type == DT_DIR) {
        if (depth > 0) {
          const int sub = ::openat(dir, e->name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
          if (sub >= 0) remove_contents(sub, depth - 1);
        }
        removed |= ::unlinkat(dir, e->name, AT_REMOVEDIR) == 0;
      } else {
        removed |= ::unlinkat(dir, e->name, 0) == 0;
      }
    }
    // Entries were removed while reading: read again from the beginning until nothing more can be removed.
    ::lseek(dir, 0, SEEK_SET);
  }
  ::close(dir);
}

void remove_path(const char* path) {
  if (::unlink(path) == 0) return;
  // Other threads may still finish a file they had started in the folder: empty it until it can go.
  for (int attempt = 0; attempt < 200; ++attempt) {
    const int dir = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (dir < 0) return;
    remove_contents(dir, 4);
    if (::rmdir(path) == 0 || errno != ENOTEMPTY) return;
    const timespec pause{0, 5'000'000};
    ::nanosleep(&pause, nullptr);
  }
}

extern "C" void on_interrupt(int sig) {
  const int saved = errno;
  g_interrupted.store(true);
  for (auto& slot : g_slots)
    if (const char* p = slot.exchange(nullptr)) remove_path(p);
  errno = saved;
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

void install_interrupt_cleanup() {
  static std::once_flag once;
  std::call_once(once, [] {
    struct sigaction sa {};
    sa.sa_handler = on_interrupt;
    sigemptyset(&sa.sa_mask);
    // The handler runs once per process: further signals of these kinds wait until it re-raises.
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&sa.sa_mask, s);
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      // A signal the caller chose to ignore (nohup, a shell's background job) stays ignored.
      if (::sigaction(s, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
      ::sigaction(s, &sa, nullptr);
    }
  });
}

TemporaryPath::TemporaryPath(std::string path) : path_(std::move(path)) {
  if (g_interrupted.load())
    for (;;) ::pause();  // the process ends as soon as the handler has removed the temporaries
  for (auto& slot : g_slots) {
    const char* expected = nullptr;
    if (slot.compare_exchange_strong(expected, path_.c_str())) {
      slot_ = &slot;
      return;
    }
  }
  // All slots taken: the path is still removed on every normal exit, only an interrupt may leave it.
}

void TemporaryPath::release() {
  if (!slot_) return;
  const char* mine = path_.c_str();
  // Failing means the handler has taken the path and is removing it on another thread: the string must stay
  // alive until the handler ends the process, which happens next.
  if (!slot_->compare_exchange_strong(mine, nullptr))
    for (;;) ::pause();
  slot_ = nullptr;
}

}  // namespace trivar
