// outputs.cpp — the files a render leaves (DESIGN.md "Outputs"): mask.png or mask_<i>.png,
// shaded.png (OpenImageIO) and render.json (technique, backend, GL strings, frame time), written
// into a temporary sibling folder and renamed into place when complete.
#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "shadowref/renderer/renderer.hpp"

namespace shadowref::renderer {
namespace {

void write_png(const Image8& image, const std::filesystem::path& file) {
  auto out = OIIO::ImageOutput::create(file.string());
  if (!out) throw std::runtime_error("cannot create a PNG writer for " + file.string());
  const OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::UINT8);
  if (!out->open(file.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data()) ||
      !out->close())
    throw std::runtime_error("cannot write " + file.string() + ": " + out->geterror());
}

}  // namespace

void write_outputs(const RenderResult& result, const GlInfo& info, const scene::Scene& scene,
                   const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  const fs::path target = fs::absolute(dir);
  const fs::path parent = target.parent_path();
  fs::create_directories(parent);
  const fs::path tmp = parent / (target.filename().string() + ".tmp-" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);

  nlohmann::json masks = nlohmann::json::array();
  for (std::size_t i = 0; i < result.masks.size(); ++i) {
    const std::string name = result.masks.size() == 1 ? "mask.png" : "mask_" + std::to_string(i) + ".png";
    write_png(result.masks[i], tmp / name);
    masks.push_back(name);
  }
  write_png(result.shaded, tmp / "shaded.png");

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
  j["shaded"] = "shaded.png";
  j["frame_ms"] = result.median_frame_ms();
  j["frame_ms_all"] = result.frame_ms;
  j["frame_ms_note"] = "all passes of one frame to glFinish, mask read-backs included (median of frames)";
  j["notes"] = result.notes;
  {
    std::ofstream f(tmp / "render.json");
    f << j.dump(2) << "\n";
    if (!f) throw std::runtime_error("cannot write " + (tmp / "render.json").string());
  }
  std::error_code ec;
  fs::remove_all(target, ec);
  fs::rename(tmp, target);
}

}  // namespace shadowref::renderer
