#pragma once
// Writes a file through a temporary in the same directory and renames it into place, so a failure while
// writing (bad geometry, full disk, exception) never leaves a partial output file behind.
#include <functional>
#include <ostream>
#include <string>

namespace trivar {

// Calls write(stream) on a temporary file and renames it to `path` when write returns; on an exception the
// temporary is removed and the exception propagates. Throws trivar::Error when the file cannot be created.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                           bool binary = false);

}  // namespace trivar
