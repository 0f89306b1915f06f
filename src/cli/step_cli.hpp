#pragma once
// Reading a STEP file on the command line: what the reader accepted leniently and the faces whose geometry
// is not extracted are said on stderr, one "trivar: warning: ..." line each, so nothing is dropped silently.
#include <string>

#include "trivar/io/step/step_file.hpp"

namespace trivar::cli {

// read_step(path, strict), then the warnings on stderr; the unextracted faces too unless the caller reports
// them itself (`info` lists them with the entities).
io::step::StepContents read_step_warning(const std::string& path, bool strict, bool warn_unmapped_faces = true);

}  // namespace trivar::cli
