#include "trivar/core/atomic_file.hpp"

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "trivar/core/error.hpp"
#include "trivar/core/interrupt_cleanup.hpp"

namespace trivar {

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write, bool binary) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  fs::path tmp = target;
  tmp += ".tmp" + std::to_string(::getpid());
  std::error_code ec;
  // The temporary name is trivar's own only while nothing else carries it.
  require(!fs::exists(fs::symlink_status(tmp, ec)), "cannot write output file " + path + ": " + tmp.string() +
                                                        " exists and is not trivar's");
  TemporaryPath guard(tmp.string());
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::binary | std::ios::out : std::ios::out);
      require(static_cast<bool>(out), "cannot create output file " + path);
      write(out);
      out.flush();
      require(static_cast<bool>(out), "write failed for output file " + path);
    }
    fs::rename(tmp, target, ec);
    require(!ec, "cannot write output file " + path + ": " + ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace trivar
