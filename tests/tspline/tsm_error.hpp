#pragma once
// The reader's refusal of a malformed TSM text: one line, starting with the file's name, naming what is wrong; and
// the refusal of a mesh's surface (TMeshSurface): one line naming what no rule covers.
#include <gtest/gtest.h>

#include <string>

#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"

namespace trivar::test {

inline void expect_tsm_error(const std::string& text, const std::string& fragment) {
  try {
    io::parse_tsm(text, "bad.tsm");
    ADD_FAILURE() << "no error for " << fragment;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(msg.rfind("bad.tsm:", 0), 0u) << msg;
  }
}

inline void expect_surface_refusal(const TMesh& m, const std::string& fragment) {
  try {
    const TMeshSurface s(m, 1);
    ADD_FAILURE() << "loaded; expected " << fragment;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  }
}

}  // namespace trivar::test
