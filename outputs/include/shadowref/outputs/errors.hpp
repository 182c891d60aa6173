// shadowref/outputs/errors.hpp — the two ways a file can be the user's problem, not ours.
//
//   InputError  something wrong with a file someone handed us (a mask, a reference folder, a
//               candidate folder): BadInput → exit 4, SizeMismatch → exit 3;
//   FileError   a file or folder we were told to write cannot be written (no permission, a
//               symbolic link in the way, a full disk): exit 4, "file error".
// Both carry one line naming the file. Everything else that escapes to the command line is an
// internal failure (exit 5): the user's input did not cause it (docs/output-contract.md).
#pragma once

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
};

}  // namespace shadowref::outputs
