// partial_name.cpp — `.<name>.partial-<pid>-<n>` (partial_name.hpp).
#include "partial_name.hpp"

#include <unistd.h>

#include <atomic>
#include <string>

namespace shadowref::outputs {

std::filesystem::path partial_sibling(const std::filesystem::path& final_path) {
  static std::atomic<unsigned> counter{0};
  return final_path.parent_path() / ("." + final_path.filename().string() + ".partial-" + std::to_string(::getpid()) + "-" +
                                     std::to_string(counter.fetch_add(1)));
}

std::filesystem::path final_name_of(const std::filesystem::path& path) {
  std::filesystem::path out;
  for (const std::filesystem::path& part : path) {
    const std::string s = part.string();
    const auto at = s.rfind(".partial-");
    out /= s.size() > 1 && s[0] == '.' && at != std::string::npos && at > 1 ? std::filesystem::path(s.substr(1, at - 1)) : part;
  }
  return out;
}

}  // namespace shadowref::outputs
