// shadowref/outputs/staged_folder.hpp — the one all-or-nothing folder write of the project.
//
// A StagedFolder for `final_dir` is a hidden sibling, `.<name>.partial-<pid>-<n>`, into which the
// caller writes every file; commit() then replaces `final_dir` by it with one rename (an atomic
// exchange when `final_dir` exists), so that a reader (a person, CTest, a concurrent run) sees either
// the old folder or the complete new one, never half a result under the final name. Destroyed
// without commit() (an exception, a failed write, an interruption), it removes the staging folder and
// leaves `final_dir` as it was. Single files outside a staged folder: atomic_file.hpp.
// Symlinks: the staging folder is created fresh (never through an existing link), and commit()
// refuses to replace a `final_dir` that is a symbolic link (it would write through it).
#pragma once

#include <filesystem>

namespace shadowref::outputs {

class StagedFolder {
 public:
  // Creates final_dir's parent if needed and an empty staging folder beside final_dir.
  // Throws std::filesystem::filesystem_error or std::runtime_error (one line naming the folder).
  explicit StagedFolder(const std::filesystem::path& final_dir);
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  // Where to write now.
  const std::filesystem::path& path() const { return staging_; }
  // The folder that commit() fills (what an error about a file being staged names).
  const std::filesystem::path& final_path() const { return final_; }
  // What commit() does when final_dir exists already.
  enum class IfExists {
    Replace,       // remove it and put ours in its place
    KeepExisting,  // keep it and drop ours (a cache entry that a concurrent run finished first)
  };
  // Moves the staging folder to final_dir. Returns false only for KeepExisting when final_dir was
  // there. Throws like the constructor, or Interrupted (interruption.hpp) before publishing anything
  // when a signal arrived.
  bool commit(IfExists if_exists = IfExists::Replace);

 private:
  std::filesystem::path final_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

}  // namespace shadowref::outputs
