// staged_folder.cpp — write into a hidden sibling, rename into place (staged_folder.hpp).
#include "shadowref/outputs/staged_folder.hpp"

#include <unistd.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <system_error>

#include "shadowref/outputs/errors.hpp"

namespace shadowref::outputs {
namespace {

namespace fs = std::filesystem;

// Unique per process and per staging: two stagings of one folder in one process (threads) differ.
std::string staging_suffix() {
  static std::atomic<unsigned> counter{0};
  return ".partial-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
}

}  // namespace

StagedFolder::StagedFolder(const fs::path& final_dir) : final_(fs::absolute(final_dir).lexically_normal()) {
  if (final_.filename().empty()) final_ = final_.parent_path();
  std::error_code ec;
  fs::create_directories(final_.parent_path(), ec);
  if (ec) throw FileError(final_.parent_path().string() + ": cannot create the folder: " + ec.message());
  staging_ = final_.parent_path() / ("." + final_.filename().string() + staging_suffix());
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec)
    throw FileError(staging_.string() + ": cannot create the staging folder: " +
                             (ec ? ec.message() : std::string("it already exists")));
}

StagedFolder::~StagedFolder() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

bool StagedFolder::commit(IfExists if_exists) {
  std::error_code ec;
  if (fs::is_symlink(final_, ec))
    throw FileError(final_.string() + ": is a symbolic link; refusing to replace it (nothing is written through links)");
  if (if_exists == IfExists::KeepExisting && fs::exists(final_, ec)) return false;  // the destructor drops ours
  fs::remove_all(final_, ec);
  if (ec) throw FileError(final_.string() + ": cannot remove the old folder: " + ec.message());
  fs::rename(staging_, final_, ec);
  if (ec) {
    // A concurrent run may have put the same entry in place between our check and our rename.
    if (if_exists == IfExists::KeepExisting && fs::exists(final_)) return false;
    throw FileError(final_.string() + ": cannot move the finished folder into place: " + ec.message());
  }
  committed_ = true;
  return true;
}

}  // namespace shadowref::outputs
