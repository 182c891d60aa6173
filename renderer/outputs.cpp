// outputs.cpp — the files a render leaves (docs/output-contract.md): mask.png or mask_<i>.png,
// visibility.png or visibility_<i>.png (filtered techniques),
// shaded.png and render.json (technique, backend, GL strings, frame time), written through the
// output contract's writers into a staged folder that is renamed into place when complete.
#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>

#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/staged_folder.hpp"
#include "shadowref/renderer/renderer.hpp"
#include "shadowref/outputs/json_text.hpp"

namespace shadowref::renderer {

void write_outputs(const RenderResult& result, const GlInfo& info, const scene::Scene& scene,
                   const std::filesystem::path& dir) {
  outputs::StagedFolder folder(dir);
  const std::filesystem::path& tmp = folder.path();
  nlohmann::json masks = nlohmann::json::array();
  for (std::size_t i = 0; i < result.masks.size(); ++i) {
    const std::string name = outputs::mask_name(i, result.masks.size());
    outputs::write_png(result.masks[i], tmp / name);
    masks.push_back(name);
  }
  nlohmann::json visibility = nlohmann::json::array();
  for (std::size_t i = 0; i < result.visibility.size(); ++i) {
    const std::string name = outputs::visibility_name(i, result.visibility.size());
    outputs::write_png(result.visibility[i], tmp / name);
    visibility.push_back(name);
  }
  outputs::write_png(result.shaded, tmp / "shaded.png");
  outputs::write_declaration(result.declaration, tmp);

  nlohmann::json j;
  j["producer"] = "shadowref renderer (OpenGL)";
  j["scene"] = scene.name;
  j["scene_file"] = scene.file.string();
  j["technique"] = result.technique;
  j["backend"] = to_string(info.driver);
  j["gl"] = to_string(info.api);
  j["gl_vendor"] = info.vendor;
  j["gl_renderer"] = info.renderer;
  j["gl_version"] = info.version;
  j["resolution"] = {scene.width, scene.height};
  j["lights"] = scene.lights.size();
  j["masks"] = masks;
  if (!visibility.empty()) j["visibility"] = visibility;
  j["shaded"] = "shaded.png";
  j["frame_ms"] = result.median_frame_ms();
  j["frame_ms_all"] = result.frame_ms;
  j["frame_ms_note"] = "all passes of one frame to glFinish, mask read-backs included (median of frames)";
  j["notes"] = result.notes;
  if (!result.faults.empty()) j["faults"] = result.faults;  // a deliberately wrong render (faults.hpp)
  outputs::write_file_atomically(tmp / "render.json", outputs::json_text(j, 2) + "\n");
  folder.commit();
}

}  // namespace shadowref::renderer
