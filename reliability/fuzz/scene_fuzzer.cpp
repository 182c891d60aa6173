// scene_fuzzer.cpp — libFuzzer target: scene::parse_scene on arbitrary bytes. Every refusal must
// be a SceneError; any other exception, a crash, a sanitizer report, a hang or an allocation past
// the run's -rss_limit_mb is a finding. Mesh paths resolve against a folder that does not exist
// (a relative "file" is a missing mesh); the OBJ and glTF loaders have their own targets.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "shadowref/scene/load_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)shadowref::scene::parse_scene(std::string_view(reinterpret_cast<const char*>(data), size),
                                        "/nonexistent-shadowref-fuzz/scene.json");
  } catch (const shadowref::scene::SceneError&) {
  }
  return 0;
}
