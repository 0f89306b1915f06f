#include "step_cli.hpp"

#include <cstdio>

namespace trivar::cli {

io::step::StepContents read_step_warning(const std::string& path, bool strict, bool warn_unmapped_faces) {
  io::step::StepContents c = io::step::read_step(path, strict);
  for (const io::step::ReadWarning& w : c.warnings) std::fprintf(stderr, "trivar: warning: %s\n", w.text().c_str());
  if (const std::string faces = c.unmapped_faces_summary(); warn_unmapped_faces && !faces.empty())
    std::fprintf(stderr, "trivar: warning: %s: %s\n", path.c_str(), faces.c_str());
  return c;
}

}  // namespace trivar::cli
