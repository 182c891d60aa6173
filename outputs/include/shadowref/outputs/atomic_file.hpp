// shadowref/outputs/atomic_file.hpp — the one all-or-nothing file write of the project.
//
// A file is written under a hidden sibling name (partial_name.hpp, as StagedFolder does for folders)
// and renamed over its final name when every byte is written: a reader (a person, CTest, a concurrent
// run, the next run after a crash) sees the old file or the complete new one, never a truncated file
// under the final name. On any failure the temporary file is removed and FileError names the final
// path with the system's reason ("out/report.json: cannot write: No space left on device").
// A final name that is a symbolic link is replaced, never written through.
//
// What it guarantees is against the process dying (an exception, a signal, SIGKILL, a full disk), not
// against a power cut: there is no fsync, which would cost every small file a disk flush. The
// reference cache, the one output read back by later runs, verifies its files' hashes instead
// (conformance/conform/include/shadowref/conform/reference_cache.hpp).
#pragma once

#include <filesystem>
#include <string_view>

namespace shadowref::outputs {

// Writes `bytes` as `file` (its folder must exist). Throws FileError; Interrupted (interruption.hpp)
// when a signal arrived, before anything is published.
void write_file_atomically(const std::filesystem::path& file, std::string_view bytes);

// Copies `from` to `to` the same way. Throws FileError (naming `from` when it cannot be read).
void copy_file_atomically(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace shadowref::outputs
