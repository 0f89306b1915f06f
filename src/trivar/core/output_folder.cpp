#include "trivar/core/output_folder.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <unistd.h>

#include "trivar/core/error.hpp"
#include "trivar/core/interrupt_cleanup.hpp"

namespace trivar {

namespace fs = std::filesystem;

namespace {

// A name that stays inside its folder: a list edited by hand must not make trivar remove files elsewhere.
bool plain_name(const std::string& n) {
  return !n.empty() && n != "." && n != ".." && n.find('/') == std::string::npos && n != kOwnedFilesList;
}

// True when `outer` is `inner` or one of its parents (both canonical).
bool contains(const fs::path& outer, const fs::path& inner) {
  auto o = outer.begin(), i = inner.begin();
  for (; o != outer.end(); ++o, ++i)
    if (i == inner.end() || *o != *i) return false;
  return true;
}

std::set<std::string> owned_names(const fs::path& dir) {
  std::set<std::string> names;
  std::ifstream in(dir / kOwnedFilesList);
  for (std::string line; std::getline(in, line);)
    if (plain_name(line)) names.insert(line);
  return names;
}

// Sorted, so the list does not depend on the order in which threads finished their files.
void write_owned_names(const fs::path& dir, std::vector<std::string> names) {
  std::sort(names.begin(), names.end());
  std::ofstream out(dir / kOwnedFilesList);
  for (const std::string& n : names) out << n << '\n';
  require(static_cast<bool>(out), "cannot write " + (dir / kOwnedFilesList).string());
}

// Removes what trivar listed in `dir` and is gone from the new output; a listed folder loses only its own
// listed files, and is removed when nothing else is left in it.
void remove_owned(const fs::path& dir, const std::set<std::string>& keep) {
  for (const std::string& n : owned_names(dir)) {
    if (keep.count(n)) continue;
    const fs::path p = dir / n;
    const fs::file_status st = fs::symlink_status(p);
    if (fs::is_directory(st)) {
      remove_owned(p, {});
      fs::remove(p / kOwnedFilesList);
      std::error_code ec;
      fs::remove(p, ec);  // fails, and so keeps the folder, when the user put files of their own in it
    } else if (fs::is_regular_file(st)) {
      fs::remove(p);
    }
  }
}

// Moves the staged `names` of `from` into the existing folder `to`; staged folders merge recursively.
void merge(const fs::path& from, const fs::path& to, const std::vector<std::string>& names) {
  remove_owned(to, std::set<std::string>(names.begin(), names.end()));
  for (const std::string& n : names) {
    const fs::path s = from / n, d = to / n;
    const bool staged_dir = fs::is_directory(fs::symlink_status(s));
    const fs::file_status existing = fs::symlink_status(d);
    if (staged_dir && fs::is_directory(existing)) {
      const std::set<std::string> inner = owned_names(s);
      merge(s, d, std::vector<std::string>(inner.begin(), inner.end()));
      continue;
    }
    require(!fs::exists(existing) || (!staged_dir && fs::is_regular_file(existing)),
            "cannot write " + d.string() + ": a " + (fs::is_directory(existing) ? "folder" : "file") +
                " of that name is in the way");
    fs::rename(s, d);
  }
  write_owned_names(to, names);
}

}  // namespace

fs::path check_output_folder(const std::string& target, const OutputFolderOptions& o) {
  const std::string what = o.command + ": output folder " + target;
  require(!target.empty(), o.command + ": the output folder name is empty");
  fs::path folder = fs::weakly_canonical(fs::absolute(target));
  if (folder.filename().empty()) folder = folder.parent_path();
  const fs::path cwd = fs::canonical(fs::current_path());
  require(!contains(folder, cwd), what + " is the current folder or contains it; give a new folder");
  for (const std::string& in : o.inputs) {
    const fs::path input_folder = fs::weakly_canonical(fs::absolute(in)).parent_path();
    require(!contains(folder, input_folder), what + " is the folder of the input " + in + " or contains it; give a new folder");
  }
  // The files are staged beside the folder, which is created with its missing parents: the nearest existing
  // parent must be a folder trivar may write into (checked here, or the failure comes after the computation).
  fs::path parent = folder.parent_path();
  while (!fs::exists(fs::status(parent)) && parent.has_relative_path()) parent = parent.parent_path();
  require(fs::is_directory(parent), what + ": " + parent.string() + " is not a folder");
  require(::access(parent.c_str(), W_OK) == 0,
          what + ": cannot write into " + parent.string() + " (" + std::strerror(errno) + ")");
  const fs::file_status st = fs::status(folder);
  if (fs::exists(st)) {
    require(fs::is_directory(st), what + " exists and is not a folder");
    const bool empty = fs::is_empty(folder), owned = fs::exists(folder / kOwnedFilesList);
    require(empty || owned || o.force,
            what + " is not empty and was not written by trivar; give --force to add trivar's files to it "
                   "(nothing else in it is touched) or choose a new folder");
  }
  return folder;
}

OutputFolder::OutputFolder(const std::string& target, const OutputFolderOptions& o)
    : target_(check_output_folder(target, o)) {
  fs::create_directories(target_.parent_path());
  staging_ = target_.parent_path() / (target_.filename().string() + ".partial-" + std::to_string(::getpid()));
  std::error_code ec;
  require(fs::create_directory(staging_, ec) && !ec,
          o.command + ": cannot create the staging folder " + staging_.string() +
              (ec ? ": " + ec.message() : ": it exists and is not trivar's"));
  guard_ = std::make_unique<TemporaryPath>(staging_.string());
}

OutputFolder::~OutputFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);  // everything in it was created by this object's owner
}

fs::path OutputFolder::path(const std::string& name) {
  require(plain_name(name), "output file name '" + name + "' is not a plain name");
  if (std::find(names_.begin(), names_.end(), name) == names_.end()) names_.push_back(name);
  return staging_ / name;
}

void OutputFolder::commit() {
  std::vector<std::string> written;
  for (const std::string& n : names_)
    if (fs::exists(fs::symlink_status(staging_ / n))) written.push_back(n);
  if (!fs::exists(target_) || fs::is_empty(target_)) {
    write_owned_names(staging_, written);
    std::error_code ec;
    fs::rename(staging_, target_, ec);  // atomic; replaces only an empty folder
    if (!ec) {
      committed_ = true;
      guard_->release();
      return;
    }
    fs::remove(staging_ / kOwnedFilesList);
  }
  merge(staging_, target_, written);
  fs::remove_all(staging_);  // only what was not moved: nothing, or trivar's own leftovers
  committed_ = true;
  guard_->release();
}

}  // namespace trivar
