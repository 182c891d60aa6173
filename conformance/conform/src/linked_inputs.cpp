// linked_inputs.cpp — see linked_inputs.hpp.
#include "linked_inputs.hpp"

#include <algorithm>

namespace shadowref::conform {

std::vector<LinkedInput> inputs_outside(const std::filesystem::path& root, const std::vector<std::filesystem::path>& files) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path real_root = fs::weakly_canonical(fs::absolute(root, ec), ec);
  std::vector<LinkedInput> out;
  for (const fs::path& f : files) {
    if (!fs::exists(f, ec)) continue;
    const fs::path real = fs::weakly_canonical(fs::absolute(f, ec), ec);
    if (ec) continue;
    // Component-wise: /a/bc is not under /a/b.
    const auto [r, p] = std::mismatch(real_root.begin(), real_root.end(), real.begin(), real.end());
    if (r != real_root.end()) out.push_back({f.string(), real.string()});
  }
  return out;
}

}  // namespace shadowref::conform
