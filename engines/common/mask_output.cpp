#include "mask_output.hpp"

#include <GL/gl.h>

#include <OpenImageIO/imageio.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace engines {

Frame read_frame(int width, int height) {
  Frame f;
  f.width = width;
  f.height = height;
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  f.rgb.resize(3 * n);
  f.depth.resize(n);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, f.rgb.data());
  glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, f.depth.data());
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("glReadPixels failed");
  return f;
}

std::vector<std::uint8_t> mask_from_frame(const Frame& frame) {
  const std::size_t w = static_cast<std::size_t>(frame.width), h = static_cast<std::size_t>(frame.height);
  std::vector<std::uint8_t> mask(w * h);
  for (std::size_t y = 0; y < h; ++y) {
    const std::size_t src_row = h - 1 - y;  // GL rows are bottom-up
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t s = src_row * w + x;
      std::uint8_t v = 128;
      if (frame.depth[s] < 1.0f) v = frame.rgb[3 * s] >= 128 ? 255 : 0;
      mask[y * w + x] = v;
    }
  }
  return mask;
}

void write_mask_png(const std::filesystem::path& file, int width, int height, const std::vector<std::uint8_t>& pixels) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(file.string());
  if (!out) throw std::runtime_error(file.string() + ": no PNG writer");
  const OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::UINT8);
  if (!out->open(file.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !out->close())
    throw std::runtime_error(file.string() + ": " + out->geterror());
}

void write_candidate_json(const std::filesystem::path& dir, const Declaration& d) {
  nlohmann::json j;
  j["producer"] = d.producer;
  j["version"] = d.version;
  j["technique"] = d.technique;
  j["convention"] = "gl";
  if (d.shadow_map_size > 0) {
    j["shadow_map_size"] = d.shadow_map_size;
    j["filter_radius_texels"] = d.filter_radius_texels;
    j["slope_bias_texels"] = d.slope_bias_texels;
    j["constant_bias"] = d.constant_bias;
    j["light_views"] = d.light_views_from_pack ? "pack" : "own";
    bool declared = false;
    nlohmann::json lights = nlohmann::json::array();
    for (const std::vector<Declaration::View>& views : d.light_matrices) {
      nlohmann::json light = {{"light_views", "own"}};
      if (!views.empty()) {
        declared = true;
        light = {{"light_views", "declared"}, {"shadow_map_size", d.shadow_map_size}, {"views", nlohmann::json::array()}};
        for (const Declaration::View& v : views) light["views"].push_back({{"view", v.view}, {"projection", v.projection}});
      }
      lights.push_back(light);
    }
    if (declared) {
      j["light_views"] = "declared";
      j["lights"] = lights;
    }
    if (d.light_taps > 0) {
      j["sampling"] = "random";
      j["light_taps"] = d.light_taps;
    }
  }
  std::ofstream out(dir / "candidate.json");
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error((dir / "candidate.json").string() + ": cannot write");
}

}  // namespace engines
