#pragma once
// Temporary files and folders trivar creates (a file written through a temporary name, a folder of slices
// written before it is moved into place) are removed when the process is interrupted by SIGINT, SIGTERM or
// SIGHUP, so an interrupted run leaves nothing behind. The handler then re-raises the signal, so the exit status
// still tells the caller which signal ended the run.
#include <atomic>
#include <string>

namespace trivar {

// Installs the handlers for SIGINT, SIGTERM and SIGHUP (once; later calls do nothing). Programs call it at start.
void install_interrupt_cleanup();

// A path trivar has just created and will rename or remove itself; while the object lives, an interrupting
// signal removes the path (a folder with everything in it). Call release() once the path is renamed or removed.
class TemporaryPath {
 public:
  explicit TemporaryPath(std::string path);
  ~TemporaryPath() { release(); }
  TemporaryPath(const TemporaryPath&) = delete;
  TemporaryPath& operator=(const TemporaryPath&) = delete;

  const std::string& path() const { return path_; }
  // The path no longer needs removing on a signal.
  void release();

 private:
  std::string path_;
  std::atomic<const char*>* slot_ = nullptr;
};

}  // namespace trivar
