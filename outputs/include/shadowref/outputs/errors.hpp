// shadowref/outputs/errors.hpp — the two ways a file can be the user's problem, not ours.
//
//   InputError  something wrong with a file someone handed us (a mask, a reference folder, a
//               candidate folder): BadInput → exit 4, SizeMismatch → exit 3;
//   FileError   a file or folder we were told to write cannot be written (no permission, a
//               symbolic link in the way, a full disk, a read-only file system, an I/O error):
//               exit 4, "file error". The environment's doing, never reported as ours.
// Both carry one line naming the file. Everything else that escapes to the command line is an
// internal failure (exit 5): the user's input did not cause it (docs/output-contract.md).
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace shadowref::outputs {

class InputError : public std::runtime_error {
 public:
  enum class Kind { BadInput, SizeMismatch };
  InputError(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  // "<path>: cannot <doing>: <the system's reason for errno_value>", e.g.
  // "out/report.json: cannot write: No space left on device".
  FileError(const std::filesystem::path& path, const std::string& doing, int errno_value);
  // The errno that caused it, 0 when the reason is ours (a symbolic link refused).
  int errno_value() const { return errno_; }

 private:
  int errno_ = 0;
};

// Whether errno `e` says the environment cannot take our output — a full disk or quota (ENOSPC,
// EDQUOT, EFBIG), a read-only or unwritable place (EROFS, EACCES, EPERM), a failing device (EIO) —
// rather than that our own code misused a call (EBADF, EINVAL, EFAULT…).
bool is_environment_errno(int e);

}  // namespace shadowref::outputs
