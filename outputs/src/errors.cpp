// errors.cpp — FileError's message from errno, and which errno values are the environment's (errors.hpp).
#include "shadowref/outputs/errors.hpp"

#include <cerrno>
#include <cstring>

namespace shadowref::outputs {

FileError::FileError(const std::filesystem::path& path, const std::string& doing, int errno_value)
    : std::runtime_error(path.string() + ": cannot " + doing + ": " + std::strerror(errno_value)), errno_(errno_value) {}

bool is_environment_errno(int e) {
  switch (e) {
    case ENOSPC:
    case EDQUOT:
    case EFBIG:
    case EROFS:
    case EACCES:
    case EPERM:
    case EIO:
    case ENOENT:   // a folder removed under us
    case ENOTDIR:  // a file where a folder was to be
    case EISDIR:
    case EEXIST:
    case ENOTEMPTY:
    case ELOOP:
    case ENAMETOOLONG:
    case EMFILE:
    case ENFILE:
    case EXDEV:
      return true;
    default:
      return false;
  }
}

}  // namespace shadowref::outputs
