// catalogue.cpp — where the data is (built or installed) and selecting scene files by glob (catalogue.hpp).
#include "shadowref/conform/catalogue.hpp"
#include "shadowref/scene/gltf_scene.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <system_error>

namespace shadowref::conform {
namespace {

bool tagged_large(const std::filesystem::path& file) {
  std::ifstream in(file);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("tags") || !j["tags"].is_array()) return false;
  for (const auto& t : j["tags"])
    if (t.is_string() && t.get<std::string>() == "large") return true;
  return false;
}

}  // namespace

std::filesystem::path data_dir() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return SHADOWREF_SOURCE_DIR;
  const fs::path installed = exe.parent_path().parent_path() / "share" / "shadowref";
  if (fs::is_directory(installed, ec)) return installed;
  const fs::path build = fs::weakly_canonical(SHADOWREF_BUILD_DIR, ec);
  if (!ec && std::mismatch(build.begin(), build.end(), exe.begin(), exe.end()).first == build.end())
    return SHADOWREF_SOURCE_DIR;
  return installed;
}

std::filesystem::path default_catalogue() { return data_dir() / "conformance" / "scenes"; }

std::filesystem::path default_golden_images() { return data_dir() / "goldens" / "images"; }

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : text + ",") {
    if (c == ',') {
      const auto b = cur.find_first_not_of(" \t");
      const auto e = cur.find_last_not_of(" \t");
      if (b != std::string::npos) out.push_back(cur.substr(b, e - b + 1));
      cur.clear();
    } else {
      cur += c;
    }
  }
  return out;
}

std::vector<std::filesystem::path> select_scenes(const std::filesystem::path& catalogue,
                                                 const std::vector<std::string>& patterns) {
  std::error_code ec;
  std::vector<std::filesystem::path> all;
  if (std::filesystem::is_directory(catalogue, ec))
    for (const auto& e : std::filesystem::directory_iterator(catalogue))
      if (e.is_regular_file() && (e.path().extension() == ".json" || scene::holds_camera_and_light(e.path()))) all.push_back(e.path());
  std::sort(all.begin(), all.end());
  std::set<std::filesystem::path> chosen;
  if (patterns.empty()) {
    if (all.empty()) throw std::invalid_argument("the catalogue " + catalogue.string() + " has no scene files");
    for (const auto& f : all)
      if (!tagged_large(f)) chosen.insert(f);
  }
  for (const std::string& p : patterns) {
    if (std::filesystem::is_regular_file(p, ec)) {
      chosen.insert(std::filesystem::path(p));
      continue;
    }
    bool any = false;
    for (const auto& f : all)
      if (fnmatch(p.c_str(), f.stem().c_str(), 0) == 0 || fnmatch(p.c_str(), f.filename().c_str(), 0) == 0) {
        chosen.insert(f);
        any = true;
      }
    if (!any)
      throw std::invalid_argument("--scenes '" + p + "' matches no scene in " + catalogue.string() +
                                  " (patterns match file names without .json, e.g. 'ground_*')");
  }
  std::vector<std::filesystem::path> out(chosen.begin(), chosen.end());
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.stem() < b.stem(); });
  return out;
}

}  // namespace shadowref::conform
