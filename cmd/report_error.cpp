// report_error.cpp — which escaped exception is the user's input and which is ours (command.hpp).
#include <filesystem>
#include <new>
#include <system_error>

#include "command.hpp"
#include "shadowref/outputs/errors.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/mesh_file.hpp"

namespace shadowref::cli {

ErrorReport report_error(const std::exception& e) {
  if (dynamic_cast<const BadInput*>(&e) || dynamic_cast<const scene::SceneError*>(&e) ||
      dynamic_cast<const scene::MeshFileError*>(&e) || dynamic_cast<const outputs::FileError*>(&e) ||
      dynamic_cast<const std::invalid_argument*>(&e))
    return {kExitBadInput, e.what()};
  if (const auto* f = dynamic_cast<const std::filesystem::filesystem_error*>(&e))
    return {kExitBadInput, f->path1().string() + ": " + f->code().message()};
  // The environment refusing a system call (a full disk, a read-only file system, an I/O error),
  // wherever it was raised: the user's machine to fix, not a bug to report.
  if (const auto* s = dynamic_cast<const std::system_error*>(&e)) {
    const std::error_category& c = s->code().category();
    if ((c == std::generic_category() || c == std::system_category()) && outputs::is_environment_errno(s->code().value()))
      return {kExitBadInput, e.what()};
  }
  if (const auto* in = dynamic_cast<const outputs::InputError*>(&e))
    return {in->kind() == outputs::InputError::Kind::SizeMismatch ? kExitSizeMismatch : kExitBadInput, e.what()};
  // A GL context that cannot be made, an Embree error, a broken invariant (std::logic_error),
  // memory: not the user's input, and never reported as if it were.
  return {kExitInternal, std::string("internal error (not caused by your input; please report it): ") + e.what()};
}

}  // namespace shadowref::cli
