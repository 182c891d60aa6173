// staged_folder.cpp — write into a hidden sibling, rename into place (staged_folder.hpp).
#include "shadowref/outputs/staged_folder.hpp"

#include <fcntl.h>
#include <stdio.h>

#include <cerrno>
#include <stdexcept>
#include <string>
#include <system_error>

#include "partial_name.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/interruption.hpp"

namespace shadowref::outputs {

namespace fs = std::filesystem;

StagedFolder::StagedFolder(const fs::path& final_dir) : final_(fs::absolute(final_dir).lexically_normal()) {
  if (final_.filename().empty()) final_ = final_.parent_path();
  std::error_code ec;
  fs::create_directories(final_.parent_path(), ec);
  if (ec) throw FileError(final_.parent_path(), "create the folder", ec.value());
  staging_ = partial_sibling(final_);
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec) throw FileError(final_, "create its staging folder", ec ? ec.value() : EEXIST);
}

StagedFolder::~StagedFolder() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

bool StagedFolder::commit(IfExists if_exists) {
  throw_if_interrupted();  // the destructor removes what was staged
  std::error_code ec;
  if (fs::is_symlink(final_, ec))
    throw FileError(final_.string() + ": is a symbolic link; refusing to replace it (nothing is written through links)");
  const bool exists = fs::exists(final_, ec);
  if (if_exists == IfExists::KeepExisting && exists) return false;  // the destructor drops ours
  if (exists) {
    // One atomic exchange: a concurrent reader sees the old folder or the new one, never neither
    // (a damaged cache entry is replaced while other runs may be reading it).
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) == 0) {
      committed_ = true;
      fs::remove_all(staging_, ec);  // now the old folder; a failure leaves only a hidden partial name
      return true;
    }
    // A file system without the exchange (EINVAL): remove, then rename.
    if (errno != EINVAL && errno != ENOSYS) throw FileError(final_, "replace the old folder", errno);
    fs::remove_all(final_, ec);
    if (ec) throw FileError(final_, "remove the old folder", ec.value());
  }
  fs::rename(staging_, final_, ec);
  if (ec) {
    // A concurrent run may have put the same entry in place between our check and our rename.
    if (if_exists == IfExists::KeepExisting && fs::exists(final_)) return false;
    throw FileError(final_, "move the finished folder into place", ec.value());
  }
  committed_ = true;
  return true;
}

}  // namespace shadowref::outputs
