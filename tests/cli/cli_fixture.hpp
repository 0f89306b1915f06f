#pragma once
// Fixture for tests of the `trivar` binary: runs it in a temporary directory and captures its outputs, exit
// code and error lines.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <sys/wait.h>

namespace cli_test {

namespace fs = std::filesystem;

struct Result {
  int code = -1;
  std::string out, err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> r;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) r.push_back(l);
  return r;
}

// The numbers after "label", "label = " or "label: " on the first line that starts with label.
inline std::vector<double> numbers_after(const std::string& text, const std::string& label) {
  for (const std::string& l : lines(text)) {
    if (l.rfind(label, 0) != 0) continue;
    std::size_t pos = l.find_first_not_of(' ', label.size());
    if (pos != std::string::npos && (l[pos] == '=' || l[pos] == ':')) ++pos;
    std::istringstream in(l.substr(std::min(pos, l.size())));
    std::vector<double> v;
    for (double x; in >> x;) v.push_back(x);
    return v;
  }
  ADD_FAILURE() << "no line starting with '" << label << "' in:\n" << text;
  return {};
}

class Cli : public ::testing::Test {
protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "trivar_cli_XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    root_ = tmpl;
    work_ = root_ / "work";
    fs::create_directories(work_);
  }
  void TearDown() override { fs::remove_all(root_); }

  // Runs `trivar args` in the work directory; stdout and stderr are captured outside it so that the work
  // directory holds only what the tool wrote.
  Result run(const std::string& args) const { return run_after("", args); }
  // As run(), after the shell commands `setup` (e.g. "ulimit -v 100000; ") in the same shell.
  Result run_after(const std::string& setup, const std::string& args) const {
    const std::string cmd = "cd '" + work_.string() + "' && " + setup + "'" TRIVAR_CLI_PATH "' " + args + " > '" +
                            (root_ / "stdout").string() + "' 2> '" + (root_ / "stderr").string() + "'";
    const int status = std::system(cmd.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(root_ / "stdout");
    r.err = slurp(root_ / "stderr");
    return r;
  }
  Result ok(const std::string& args) const {
    Result r = run(args);
    EXPECT_EQ(r.code, 0) << "trivar " << args << "\n" << r.err;
    return r;
  }
  // A failing command: one stderr line "trivar: error: ...", the expected exit code, nothing on stdout and
  // no new file in the work directory.
  void fails(const std::string& args, int code = 1) const {
    const auto before = listing();
    const Result r = run(args);
    EXPECT_EQ(r.code, code) << "trivar " << args;
    const auto err = lines(r.err);
    ASSERT_EQ(err.size(), 1u) << "trivar " << args << "\n" << r.err;
    EXPECT_EQ(err[0].rfind("trivar: error: ", 0), 0u) << err[0];
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_EQ(listing(), before) << "trivar " << args << " left files behind";
  }
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(work_)) names.push_back(e.path().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  void write(const std::string& name, const std::string& text) const { std::ofstream(work_ / name) << text; }
  bool exists(const std::string& name) const { return fs::exists(work_ / name); }

  fs::path root_, work_;
};

// Degree-1 unit cube in trivar JSON with x mirrored when `mirrored`: det J = -1 everywhere.
inline std::string unit_cube_json(bool mirrored) {
  nlohmann::json j{{"trivar", 1}, {"kind", "volume"}, {"dim", 3}, {"rational", false}, {"degrees", {1, 1, 1}}};
  j["knots"] = {{0, 0, 1, 1}, {0, 0, 1, 1}, {0, 0, 1, 1}};
  for (int k = 0; k < 2; ++k)
    for (int jj = 0; jj < 2; ++jj)
      for (int i = 0; i < 2; ++i) j["control_points"].push_back({mirrored ? -i : i, jj, k});
  return j.dump();
}

}  // namespace cli_test
