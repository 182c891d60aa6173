// engines/common/harness_args.hpp — the command line both harnesses share:
//   <harness> --pack DIR --out DIR [--scenes a,b] [--variant NAME]
// (--variant: the engine's technique switch, e.g. zfail | zpass). Small on purpose: the harnesses
// stand outside the project and use nothing of its command-line code.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace engines {

struct HarnessArgs {
  std::filesystem::path pack, out;
  std::string scenes;   // empty: every scene of the pack
  std::string variant;
};

inline HarnessArgs parse_harness_args(int argc, char** argv) {
  HarnessArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string key = argv[i];
    if (i + 1 >= argc) throw std::runtime_error("argument " + key + " needs a value");
    const std::string value = argv[++i];
    if (key == "--pack") a.pack = value;
    else if (key == "--out") a.out = value;
    else if (key == "--scenes") a.scenes = value;
    else if (key == "--variant") a.variant = value;
    else throw std::runtime_error("unknown argument " + key);
  }
  if (a.pack.empty() || a.out.empty()) throw std::runtime_error("usage: --pack DIR --out DIR [--scenes a,b] [--variant NAME]");
  return a;
}

}  // namespace engines
