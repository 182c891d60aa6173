// reference_cache.cpp — the hashed reference cache (reference_cache.hpp).
#include "shadowref/conform/reference_cache.hpp"


#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <system_error>
#include <vector>

#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/staged_folder.hpp"
#include "shadowref/reference/render.hpp"
#include "shadowref/reference/write_images.hpp"
#include "shadowref/outputs/json_text.hpp"

namespace shadowref::conform {
namespace {

struct Fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 0x100000001b3ull;
    }
  }
  void add(const std::string& s) {
    const std::uint64_t n = s.size();
    add(&n, sizeof n);  // length first: "ab"+"c" and "a"+"bc" differ
    add(s.data(), s.size());
  }
};

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string() + " (for the reference cache key)");
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The running executable's hash, computed once per process.
std::uint64_t executable_hash() {
  static std::once_flag once;
  static std::uint64_t value = 0;
  std::call_once(once, [] {
    Fnv1a f;
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) f.add(read_bytes(exe));
    value = f.h;
  });
  return value;
}

// The hash of another executable's bytes, computed once per path and process.
std::uint64_t file_hash(const std::filesystem::path& file) {
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::uint64_t> known;
  const std::lock_guard<std::mutex> lock(mutex);
  const auto it = known.find(file);
  if (it != known.end()) return it->second;
  Fnv1a f;
  f.add(read_bytes(file));
  return known[file] = f.h;
}

// The files a scene file names, relative to it: a JSON scene's mesh files and masks
// (objects[].shape.file, objects[].alpha_texture), a .gltf scene's external buffers and images (a
// URI that is not a data: URI). A .glb is read as one file (its JSON chunk is not parsed here).
std::vector<std::filesystem::path> mesh_files(const std::filesystem::path& scene_file, const std::string& text) {
  std::vector<std::filesystem::path> out;
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object()) return out;
  if (j.contains("objects") && j["objects"].is_array())
    for (const auto& o : j["objects"]) {
      if (o.is_object() && o.contains("shape") && o["shape"].is_object() && o["shape"].contains("file") &&
          o["shape"]["file"].is_string())
        out.push_back(scene_file.parent_path() / o["shape"]["file"].get<std::string>());
      if (o.is_object() && o.contains("alpha_texture") && o["alpha_texture"].is_string())
        out.push_back(scene_file.parent_path() / o["alpha_texture"].get<std::string>());
    }
  for (const char* key : {"buffers", "images"})
    if (j.contains(key) && j[key].is_array())
      for (const auto& b : j[key])
        if (b.is_object() && b.contains("uri") && b["uri"].is_string() && b["uri"].get<std::string>().rfind("data:", 0) != 0) {
          // A percent-encoded URI names a file by another spelling: the loader found it, the key reads what it can.
          std::error_code ec;
          const std::filesystem::path file = scene_file.parent_path() / b["uri"].get<std::string>();
          if (std::filesystem::is_regular_file(file, ec)) out.push_back(file);
        }
  return out;
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// What key.json says an entry holds. 2: `files`, each file's FNV-1a 64 of its bytes, and
// `key_json_hash`, that of key.json's own text without that field (a flipped byte in key.json is
// caught too); an entry of another format (1: before the hashes) is recomputed, never read as if it
// were this one.
constexpr int kEntryFormat = 2;

std::string content_hash(const std::string& bytes) {
  Fnv1a f;
  f.add(bytes.data(), bytes.size());
  return hex(f.h);
}

// Why the entry folder `dir` cannot be used as the entry of `key`, or "" when every file it recorded
// is there with the bytes it recorded. Reads every file: a few megabytes at 1024², milliseconds.
std::string entry_problem(const std::filesystem::path& dir, const std::string& key) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path key_file = dir / "key.json";
  if (!fs::is_regular_file(key_file, ec)) return "key.json is missing";
  std::ifstream in(key_file, std::ios::binary);
  const nlohmann::json k = nlohmann::json::parse(in, nullptr, false);
  if (!k.is_object()) return "key.json does not parse";
  const auto format = k.find("format");
  if (format == k.end() || !format->is_number_integer())
    return "key.json has no format: written by an older shadowref, before entries recorded their files' hashes";
  if (format->get<int>() != kEntryFormat)
    return "key.json is of format " + format->dump() + ", this shadowref reads " + std::to_string(kEntryFormat);
  nlohmann::json rest = k;
  rest.erase("key_json_hash");
  if (!k.contains("key_json_hash") || k["key_json_hash"] != content_hash(outputs::json_text(rest, 2)))
    return "key.json: its text differs from the hash it recorded of itself (corrupted)";
  if (k.value("key", std::string()) != key) return "key.json names another key";
  const auto files = k.find("files");
  if (files == k.end() || !files->is_object() || files->empty()) return "key.json lists no files";
  for (const auto& [name, recorded] : files->items()) {
    // A plain file name of the folder: an entry never makes us read elsewhere.
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos || !recorded.is_string())
      return "key.json: files: '" + name + "' is not a file of the entry";
    const fs::path file = dir / name;
    if (!fs::is_regular_file(file, ec)) return name + " is missing";
    std::ifstream f(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(f)), {});
    if (!f && !f.eof()) return name + " cannot be read";
    if (content_hash(bytes) != recorded.get<std::string>())
      return name + ": its bytes differ from the hash key.json recorded (" + std::to_string(bytes.size()) +
             " bytes: truncated or corrupted)";
  }
  return "";
}

}  // namespace

std::string reference_key(const scene::PreparedScene& prepared, const ReferenceSettings& settings) {
  const scene::Scene& scene = *prepared.scene;
  Fnv1a f;
  const std::string text = read_bytes(scene.file);
  f.add(text);
  for (const auto& m : mesh_files(scene.file, text)) {
    f.add(m.filename().string());
    f.add(read_bytes(m));
  }
  f.add("samples_per_axis=" + std::to_string(settings.samples_per_axis));
  f.add("convention=" + std::string(prepared.convention->name));
  // The resolution may be overridden (conform --resolution, --resolution-scale): not in the file.
  f.add("resolution=" + std::to_string(scene.width) + "x" + std::to_string(scene.height));
  const std::uint64_t exe = settings.key_executable.empty() ? executable_hash() : file_hash(settings.key_executable);
  f.add(&exe, sizeof exe);
  return hex(f.h);
}

namespace {

// Returns the names of the files written.
std::vector<std::string> render_into(const scene::PreparedScene& scene, const std::filesystem::path& dir,
                                     const ReferenceSettings& settings) {
  reference::Options options;
  options.samples_per_axis = settings.samples_per_axis;
  options.threads = settings.threads;
  options.embree_config = settings.embree_config;
  const reference::Images images = reference::render(scene, options);
  return reference::write_images(images, dir);
}

}  // namespace

void render_reference_to(const scene::PreparedScene& scene, const std::filesystem::path& dir, const ReferenceSettings& settings) {
  outputs::StagedFolder folder(dir);
  render_into(scene, folder.path(), settings);
  folder.commit();
}

CachedReference ensure_reference(const scene::PreparedScene& prepared, const std::filesystem::path& cache,
                                 const ReferenceSettings& settings) {
  // A forced Embree kernel may guess undecided pixels otherwise: such a reference is not the
  // entry the key names. (A programming error: the commands give such settings no cache.)
  if (!settings.embree_config.empty())
    throw std::invalid_argument("ensure_reference: a forced Embree configuration renders fresh, never into a cache");
  const scene::Scene& scene = *prepared.scene;
  const std::string key = reference_key(prepared, settings);
  CachedReference out;
  out.dir = std::filesystem::absolute(cache / (scene.name + "-" + key));
  std::error_code ec;
  if (std::filesystem::exists(out.dir, ec)) {
    out.recomputed_because = entry_problem(out.dir, key);
    if (out.recomputed_because.empty()) return out;
  }
  const auto start = std::chrono::steady_clock::now();
  outputs::StagedFolder folder(out.dir);
  const std::filesystem::path& tmp = folder.path();
  const std::vector<std::string> written = render_into(prepared, tmp, settings);
  {
    nlohmann::json k;
    k["format"] = kEntryFormat;
    nlohmann::json files = nlohmann::json::object();
    for (const std::string& name : written) files[name] = content_hash(read_bytes(tmp / name));
    k["files"] = files;
    k["files_hash"] = "FNV-1a 64 of each file's bytes, checked before every use: an entry that fails is recomputed";
    k["scene"] = scene.name;
    k["scene_file"] = std::filesystem::absolute(scene.file).string();
    k["samples_per_axis"] = settings.samples_per_axis;
    k["convention"] = prepared.convention->name;
    k["resolution"] = {scene.width, scene.height};
    k["key"] = key;
    k["key_inputs"] = "FNV-1a 64 of the scene file, its mesh files, the settings, the convention and the shadowref executable";
    k["key_json_hash"] = content_hash(outputs::json_text(k, 2));  // of the text above, this field left out
    outputs::write_file_atomically(tmp / "key.json", outputs::json_text(k, 2) + "\n");
  }
  // Another process may have finished the same key first: theirs is as good as ours. A damaged entry
  // is replaced (one atomic exchange: a run reading it meanwhile sees the old files or the new ones).
  folder.commit(out.recomputed_because.empty() ? outputs::StagedFolder::IfExists::KeepExisting
                                               : outputs::StagedFolder::IfExists::Replace);
  out.computed = true;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace shadowref::conform
