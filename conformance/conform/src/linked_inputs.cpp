// linked_inputs.cpp — see linked_inputs.hpp.
#include "linked_inputs.hpp"

#include "shadowref/scene/path_within.hpp"

namespace shadowref::conform {

std::vector<LinkedInput> inputs_outside(const std::filesystem::path& root, const std::vector<std::filesystem::path>& files) {
  namespace fs = std::filesystem;
  std::vector<LinkedInput> out;
  for (const fs::path& f : files) {
    std::error_code ec;
    if (!fs::exists(f, ec) || scene::resolves_within(root, f)) continue;
    const fs::path real = fs::weakly_canonical(fs::absolute(f, ec), ec);
    if (!ec) out.push_back({f.string(), real.string()});
  }
  return out;
}

}  // namespace shadowref::conform
