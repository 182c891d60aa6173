// atomic_file.cpp — write a hidden sibling, rename it into place (atomic_file.hpp).
#include "shadowref/outputs/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <string>

#include "partial_name.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/interruption.hpp"

namespace shadowref::outputs {
namespace {

namespace fs = std::filesystem;

// The temporary file, removed unless it was renamed into place.
class TemporaryFile {
 public:
  explicit TemporaryFile(const fs::path& final_path)
      : final_(final_path), shown_(final_name_of(final_path)), path_(partial_sibling(final_path)) {
    // 0666 less the umask, as an ordinary file of the user's (mkstemp's 0600 would not be).
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ < 0) throw FileError(shown_, "write", errno);
  }
  ~TemporaryFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!published_) ::unlink(path_.c_str());
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  void write(std::string_view bytes) {
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
      const ssize_t n = ::write(fd_, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        throw FileError(shown_, "write", errno);
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
  }

  void publish() {
    // close() reports what a network file system deferred (a full disk, a quota).
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) throw FileError(shown_, "write", errno);
    throw_if_interrupted();
    if (::rename(path_.c_str(), final_.c_str()) != 0) throw FileError(shown_, "move the written file into place", errno);
    published_ = true;
  }

 private:
  fs::path final_;
  fs::path shown_;  // in messages: the name the file would have had once its folder is published
  fs::path path_;
  int fd_ = -1;
  bool published_ = false;
};

std::string read_all(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw FileError(file, "read", errno);
  std::string bytes;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      ::close(fd);
      throw FileError(file, "read", e);
    }
    if (n == 0) break;
    bytes.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return bytes;
}

}  // namespace

void write_file_atomically(const fs::path& file, std::string_view bytes) {
  TemporaryFile tmp(file);
  tmp.write(bytes);
  tmp.publish();
}

void copy_file_atomically(const fs::path& from, const fs::path& to) { write_file_atomically(to, read_all(from)); }

}  // namespace shadowref::outputs
