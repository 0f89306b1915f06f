// Output folders (slice, demo, solve): trivar never removes or replaces what it did not write, refuses the
// current folder, the input's folder and their parents, and an interrupted run leaves no staging folder or
// temporary file behind.
#include <chrono>
#include <csignal>
#include <map>
#include <set>
#include <thread>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli/cli_fixture.hpp"

extern char** environ;

using namespace cli_test;

namespace {

// Every path under `dir` with its contents (folders map to ""), to compare before and after a run byte for byte.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> s;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    s[fs::relative(e.path(), dir).string()] = e.is_directory() ? std::string() : slurp(e.path());
  return s;
}

std::set<std::string> lines_of(const fs::path& file) {
  const auto l = lines(slurp(file));
  return {l.begin(), l.end()};
}

std::set<std::string> files_in(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

// Names containing ".partial-" or ".tmp": what an interrupted run could leave.
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.find(".partial-") != std::string::npos || n.find(".tmp") != std::string::npos) found.push_back(n);
  }
  return found;
}

}  // namespace

class OutputFolderCli : public Cli {
 protected:
  void SetUp() override {
    Cli::SetUp();
    // A 1 x 2 x 3 box: z in [0, 3] exactly, so the layer counts below follow from the layer thickness.
    ok("make box --elements 1 --size 1 2 3 --model --materials 2 -o box.json");
    write("notes.txt", "the user's own file\n");
  }
  // A failing run that must leave the whole temporary root (work folder and its parent) as it was.
  void refused(const std::string& args, const std::string& message_part, int code = 1) {
    const auto before = snapshot(work_);
    const Result r = run(args);
    EXPECT_EQ(r.code, code) << args;
    EXPECT_EQ(lines(r.err).size(), 1u) << r.err;
    EXPECT_NE(r.err.find(message_part), std::string::npos) << r.err;
    EXPECT_EQ(snapshot(work_), before) << args;
  }
};

TEST_F(OutputFolderCli, TheCurrentFolderTheInputsFolderAndTheirParentsAreRefused) {
  refused("slice box.json --out .", "is the current folder or contains it");
  refused("slice box.json --out . --force", "is the current folder or contains it");
  refused("slice box.json --out ..", "is the current folder or contains it");
  refused("slice box.json --out '" + work_.string() + "/'", "is the current folder or contains it");
  fs::create_directories(work_ / "models" / "deep");
  fs::copy_file(work_ / "box.json", work_ / "models" / "deep" / "box.json");
  refused("slice models/deep/box.json --out models/deep --force", "is the folder of the input models/deep/box.json");
  refused("slice models/deep/box.json --out models --force", "is the folder of the input models/deep/box.json");
  refused("solve poisson box.json --out . --force", "is the current folder or contains it");
  // The parent of the work folder holds the captured outputs: nothing else may have appeared there.
  std::set<std::string> parent;
  for (const auto& e : fs::directory_iterator(root_)) parent.insert(e.path().filename().string());
  EXPECT_EQ(parent, (std::set<std::string>{"stderr", "stdout", "work"}));
}

TEST_F(OutputFolderCli, AFileOrAForeignFolderIsNeverReplaced) {
  write("slices", "a file named like the output folder\n");
  refused("slice box.json --out slices --layer 1 --dpi 50", "exists and is not a folder");
  refused("slice box.json --out slices --layer 1 --dpi 50 --force", "exists and is not a folder");
  // A file where a parent folder would be made is refused before solving (no output line, nothing written).
  refused("solve poisson box.json --out notes.txt/out", "notes.txt is not a folder");
  refused("slice box.json --out notes.txt/deep/out --layer 1 --dpi 50", "notes.txt is not a folder");
  fs::create_directory(work_ / "mine");
  write("mine/keep.txt", "keep me\n");
  write("mine/layer_00000.png", "not an image, but the user's\n");
  refused("slice box.json --out mine --layer 1 --dpi 50", "not empty and was not written by trivar");
  refused("demo --out mine", "not empty and was not written by trivar");

  // --force adds trivar's files: its own names are replaced, everything else stays byte for byte.
  ok("slice box.json --out mine --layer 1 --dpi 50 --force");
  EXPECT_EQ(slurp(work_ / "mine" / "keep.txt"), "keep me\n");
  EXPECT_NE(slurp(work_ / "mine" / "layer_00000.png").substr(1, 3), "not");  // replaced by a PNG
  EXPECT_EQ(slurp(work_ / "mine" / "layer_00000.png").substr(1, 3), "PNG");
  // z from 0 to 3 in 1 mm layers: 3 layers; the list names exactly what was written.
  const auto m = nlohmann::json::parse(slurp(work_ / "mine" / "manifest.json"));
  ASSERT_EQ(m.at("layers").get<int>(), 3);
  const std::set<std::string> written{"layer_00000.png", "layer_00001.png", "layer_00002.png", "manifest.json"};
  EXPECT_EQ(lines_of(work_ / "mine" / ".trivar-files"), written);
  std::set<std::string> all = written;
  all.insert({".trivar-files", "keep.txt"});
  EXPECT_EQ(files_in(work_ / "mine"), all);
  EXPECT_EQ(slurp(work_ / "notes.txt"), "the user's own file\n");

  // An empty folder is as good as a new one.
  fs::create_directory(work_ / "empty");
  ok("slice box.json --out empty --layer 1 --dpi 50");
  EXPECT_EQ(lines_of(work_ / "empty" / ".trivar-files"), written);
}

TEST_F(OutputFolderCli, ARerunReplacesOnlyTrivarsOwnFiles) {
  ok("slice box.json --out s --layer 0.5 --dpi 50");
  EXPECT_EQ(nlohmann::json::parse(slurp(work_ / "s" / "manifest.json")).at("layers").get<int>(), 6);
  write("s/annotations.txt", "added by the user\n");
  // Fewer layers: the stale layer files trivar wrote go, the user's file stays.
  ok("slice box.json --out s --layer 1.5 --dpi 50");
  EXPECT_EQ(nlohmann::json::parse(slurp(work_ / "s" / "manifest.json")).at("layers").get<int>(), 2);
  EXPECT_EQ(files_in(work_ / "s"), (std::set<std::string>{".trivar-files", "annotations.txt", "layer_00000.png",
                                                          "layer_00001.png", "manifest.json"}));
  EXPECT_EQ(slurp(work_ / "s" / "annotations.txt"), "added by the user\n");

  EXPECT_TRUE(leftovers(work_).empty());
}

// Starts `trivar args` in the work folder, waits until its staging folder exists, sends `sig` and checks
// that the process died of that signal and left nothing behind.
void interrupt_slice(const fs::path& work, int sig) {
  const std::vector<std::string> args{TRIVAR_CLI_PATH, "--threads", "2", "slice", "box.json", "--out", "big",
                                      "--layer", "0.01", "--dpi", "4000"};
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  const fs::path old = fs::current_path();
  fs::current_path(work);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  fs::current_path(old);
  posix_spawn_file_actions_destroy(&actions);
  const fs::path staging = work / ("big.partial-" + std::to_string(pid));
  // Wait for a few layers so that files and temporaries exist in the staging folder.
  for (int i = 0; i < 600; ++i) {
    std::error_code ec;
    if (fs::exists(staging / "layer_00003.png", ec)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(fs::exists(staging)) << "the slice run did not start";
  ASSERT_EQ(::kill(pid, sig), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << status;
  EXPECT_EQ(WTERMSIG(status), sig);
  EXPECT_TRUE(leftovers(work).empty()) << leftovers(work).front();
  EXPECT_FALSE(fs::exists(work / "big"));
}

TEST_F(OutputFolderCli, InterruptedRunsLeaveNothingBehind) {
  const auto before = snapshot(work_);
  interrupt_slice(work_, SIGINT);
  interrupt_slice(work_, SIGTERM);
  EXPECT_EQ(snapshot(work_), before);
}
