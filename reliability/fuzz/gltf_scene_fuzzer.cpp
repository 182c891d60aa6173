// gltf_scene_fuzzer.cpp — libFuzzer target: scene::load_scene on arbitrary bytes saved as a .gltf
// file, an engine team's own glTF scene (scene/gltf_scene.hpp: camera, KHR_lights_punctual lights,
// meshes, alpha masks with their PNGs, extras). Every refusal must be a SceneError; a loaded scene
// must hold a light and objects whose vertices are finite and whose indices, uvs and vertex alphas
// match their meshes — anything else, a crash, a sanitizer report or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_files.hpp"
#include "shadowref/scene/load_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = shadowref::fuzz::scratch_dir() / "input.gltf";
  shadowref::fuzz::write_file(file, data, size);
  shadowref::scene::Scene s;
  try {
    s = shadowref::scene::load_scene(file);
  } catch (const shadowref::scene::SceneError&) {
    return 0;
  }
  if (s.lights.empty() || s.objects.empty()) std::abort();  // promised: at least one of each
  for (const auto& o : s.objects) {
    for (const auto& p : o.mesh.positions)
      if (!p.allFinite()) std::abort();
    for (const auto& t : o.mesh.triangles)
      for (const auto i : t)
        if (i >= o.mesh.positions.size()) std::abort();
    if (o.alpha && (o.alpha->uvs.size() != o.mesh.positions.size() || o.alpha->vertex_alpha.size() != o.mesh.positions.size() ||
                    o.alpha->texture->alpha.size() != static_cast<std::size_t>(o.alpha->texture->width) *
                                                          static_cast<std::size_t>(o.alpha->texture->height)))
      std::abort();
  }
  return 0;
}
