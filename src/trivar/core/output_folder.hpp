#pragma once
// A folder of output files that trivar writes without ever deleting or overwriting what it did not create.
//
// The files are written into a fresh staging folder next to the target (`<target>.partial-<pid>`, removed on an
// error or an interrupting signal) and moved into place at the end:
//   - a target that does not exist, or an empty folder, receives the staging folder as it is;
//   - a folder trivar wrote before (it holds the list of its files, kOwnedFilesList) loses the files of that
//     list, and only those, before the new ones move in; anything else in it is kept;
//   - any other non-empty folder is refused unless `force`, and even then only the names trivar writes are
//     replaced;
//   - a target that is not a folder, the current folder, the folder of an input file or any folder containing
//     them is always refused.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace trivar {

class TemporaryPath;

// The file in each output folder listing the names trivar wrote there, one per line.
inline constexpr const char* kOwnedFilesList = ".trivar-files";

struct OutputFolderOptions {
  std::string command;              // names the command in messages ("slice")
  std::vector<std::string> inputs;  // files the command reads; their folders are never output folders
  bool force = false;               // write into a non-empty folder that trivar did not write
};

// The rules above checked without creating anything, so that a long computation can refuse a bad output folder
// before it starts; returns the target's absolute path. Throws trivar::Error naming the folder.
std::filesystem::path check_output_folder(const std::string& target, const OutputFolderOptions& options);

class OutputFolder {
 public:
  // Checks the rules above and creates the staging folder; throws trivar::Error naming the folder otherwise.
  OutputFolder(const std::string& target, const OutputFolderOptions& options);
  // Without commit(), removes the staging folder and everything in it.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Where to write the output `name` (a plain file or folder name) now; it ends up in the target at commit().
  std::filesystem::path path(const std::string& name);
  // Moves every file recorded by path() into the target, as described above.
  void commit();

 private:
  std::filesystem::path target_, staging_;
  std::vector<std::string> names_;
  std::unique_ptr<TemporaryPath> guard_;
  bool committed_ = false;
};

}  // namespace trivar
