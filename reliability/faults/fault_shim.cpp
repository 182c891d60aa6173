// fault_shim.cpp — an LD_PRELOAD library that makes a fault happen at an exact, repeatable point of
// a `shadowref` run, for faults_test.cpp. Nothing of it is linked into shadowref.
//
// Points are counted, never timed, so that a test does not depend on the machine's speed: the n-th
// rename (a result being published: StagedFolder::commit, write_file_atomically) or the n-th write
// to a file under SHADOWREF_FAULT_UNDER (the run's --out; never stdout, stderr, Mesa's shader cache).
//
//   SHADOWREF_FAULT_UNDER=DIR        only files under DIR count (required; an absolute path)
//   SHADOWREF_FAULT_COUNT=FILE       at exit, writes "<renames> <writes>" (the run's points) to FILE,
//                                    then the same two counts when the fault happened (-1 -1: none)
//   SHADOWREF_FAULT_AT_RENAME=N      before the N-th rename (from 1) …
//   SHADOWREF_FAULT_IN_WRITE=N       in the N-th write, after half of its bytes …
//   SHADOWREF_FAULT_SIGNAL=S         … raise signal S (default 9, SIGKILL: a crash; 2 and 15 go to
//                                    shadowref's handlers, and the call then goes on)
//   SHADOWREF_FAULT_DISK_BYTES=B     writes fail with ENOSPC once B bytes were written under DIR (a
//                                    full disk where no size-limited file system can be mounted)
//   SHADOWREF_FAULT_SAY=1            says "fault shim: raising signal S" on stderr just before the
//                                    signal, so that a test can time what follows it
#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

std::atomic<long> g_renames{0};
std::atomic<long> g_writes{0};
std::atomic<long long> g_bytes{0};
std::atomic<long> g_renames_at_fault{-1};
std::atomic<long> g_writes_at_fault{-1};

long env_long(const char* name, long fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtol(v, nullptr, 10) : fallback;
}

// Whether `path` (absolute, or relative to the working folder) lies under SHADOWREF_FAULT_UNDER.
bool under(const char* path) {
  const char* dir = std::getenv("SHADOWREF_FAULT_UNDER");
  if (!dir || !*dir || !path) return false;
  char buf[4096];
  if (path[0] != '/') {
    if (!::getcwd(buf, sizeof buf)) return false;
    const std::size_t n = std::strlen(buf);
    std::snprintf(buf + n, sizeof buf - n, "/%s", path);
    path = buf;
  }
  return std::strncmp(path, dir, std::strlen(dir)) == 0;
}

bool fd_under(int fd) {
  if (fd <= 2) return false;
  char link[64], path[4096];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = ::readlink(link, path, sizeof path - 1);
  if (n <= 0) return false;
  path[n] = '\0';
  return under(path);
}

template <class F>
F next(const char* name) {
  return reinterpret_cast<F>(::dlsym(RTLD_NEXT, name));
}

void fault() {
  g_renames_at_fault = g_renames.load();
  g_writes_at_fault = g_writes.load();
  const int sig = static_cast<int>(env_long("SHADOWREF_FAULT_SIGNAL", SIGKILL));
  if (env_long("SHADOWREF_FAULT_SAY", 0)) {
    char line[64];
    const int n = std::snprintf(line, sizeof line, "fault shim: raising signal %d\n", sig);
    if (n > 0) next<ssize_t (*)(int, const void*, size_t)>("write")(2, line, static_cast<size_t>(n));
  }
  std::raise(sig);
}

void count_rename(const char* newpath) {
  if (!under(newpath)) return;
  if (++g_renames == env_long("SHADOWREF_FAULT_AT_RENAME", 0)) fault();
}

struct WriteCounts {
  ~WriteCounts() {
    const char* file = std::getenv("SHADOWREF_FAULT_COUNT");
    if (!file || !*file) return;
    if (FILE* f = std::fopen(file, "w")) {
      std::fprintf(f, "%ld %ld %ld %ld\n", g_renames.load(), g_writes.load(), g_renames_at_fault.load(), g_writes_at_fault.load());
      std::fclose(f);
    }
  }
} g_write_counts_at_exit;

}  // namespace

extern "C" {

int rename(const char* oldpath, const char* newpath) {
  count_rename(newpath);
  return next<int (*)(const char*, const char*)>("rename")(oldpath, newpath);
}

int renameat(int olddirfd, const char* oldpath, int newdirfd, const char* newpath) {
  count_rename(newpath);
  return next<int (*)(int, const char*, int, const char*)>("renameat")(olddirfd, oldpath, newdirfd, newpath);
}

int renameat2(int olddirfd, const char* oldpath, int newdirfd, const char* newpath, unsigned flags) {
  count_rename(newpath);
  return next<int (*)(int, const char*, int, const char*, unsigned)>("renameat2")(olddirfd, oldpath, newdirfd, newpath, flags);
}

ssize_t write(int fd, const void* data, size_t size) {
  using Write = ssize_t (*)(int, const void*, size_t);
  static const Write real = next<Write>("write");
  if (size == 0 || !fd_under(fd)) return real(fd, data, size);
  const long long budget = env_long("SHADOWREF_FAULT_DISK_BYTES", -1);
  if (budget >= 0) {
    // A full disk: what fits is written (a short write), then ENOSPC, as the kernel does.
    const long long left = budget - g_bytes.load();
    if (left <= 0) {
      errno = ENOSPC;
      return -1;
    }
    if (static_cast<long long>(size) > left) size = static_cast<size_t>(left);
  }
  if (++g_writes == env_long("SHADOWREF_FAULT_IN_WRITE", 0)) {
    const ssize_t half = real(fd, data, size / 2 + 1);
    fault();
    if (half > 0) g_bytes += half;
    return half;
  }
  const ssize_t n = real(fd, data, size);
  if (n > 0) g_bytes += n;
  return n;
}

}  // extern "C"
