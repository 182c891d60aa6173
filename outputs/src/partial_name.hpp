// partial_name.hpp — the one naming rule of a result not yet published (private to outputs/).
//
// A write goes first to a hidden sibling of its final name, `.<name>.partial-<pid>-<n>`, and is
// renamed into place when complete (StagedFolder for folders, write_file_atomically for files): the
// same folder, so the rename is atomic; hidden, so a person or a glob does not take it for a result;
// the pid and a per-process counter make two writers (processes, threads) of one name differ. After a
// SIGKILL or a power cut such a name may remain; nothing reads it, and deleting it is always safe.
#pragma once

#include <filesystem>

namespace shadowref::outputs {

std::filesystem::path partial_sibling(const std::filesystem::path& final_path);

// `path` with every partial name in it replaced by the final name it stands for: what an error
// message names, since the partial names are gone by the time a person reads it
// (out/.report.partial-12-3/img/a.png → out/report/img/a.png).
std::filesystem::path final_name_of(const std::filesystem::path& path);

}  // namespace shadowref::outputs
