// engines/common/mask_output.hpp — what a harness writes: masks of the output contract (8-bit grey
// PNG, 255 lit, 0 shadowed, 128 no surface, row 0 at the top) made from a read-back frame, and the
// candidate.json that declares how they were made.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace engines {

// A frame read back with glReadPixels: rows bottom-up, as OpenGL returns them.
struct Frame {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // GL_RGB, GL_UNSIGNED_BYTE
  std::vector<float> depth;       // GL_DEPTH_COMPONENT, GL_FLOAT
};

// Reads the current read buffer's colour and depth (the caller's GL context must be current).
Frame read_frame(int width, int height);

// The mask, rows top-down. The harness draws every surface white and unlit, the engine darkens what
// it shadows, so a pixel is lit when its red channel is at least half (a filtered shadow map gives
// greys: lit when at least half its taps are). "No surface" is where the depth buffer still holds
// its clear value 1.0: coverage is decided by depth, never by colour, so an engine's shadow drawn
// over the background cannot turn it into a surface.
std::vector<std::uint8_t> mask_from_frame(const Frame& frame);

// Writes `pixels` (top-down) as an 8-bit grey PNG. Throws std::runtime_error.
void write_mask_png(const std::filesystem::path& file, int width, int height, const std::vector<std::uint8_t>& pixels);

// The declaration beside the masks (keys of the pack README's candidate.json).
struct Declaration {
  std::string producer, version, technique;
  int shadow_map_size = 0;          // 0: not a shadow map
  double filter_radius_texels = 0;
  double slope_bias_texels = 0;
  double constant_bias = 0;
  bool light_views_from_pack = false;
  int light_taps = 0;  // > 0: a kernel of light_taps^2 taps drawn at random per pixel ("sampling": "random")
  // Per light, in the pack's order, the view and projection matrices the engine drew its map with
  // (column-vector matrices in column-major order, gl clip space); a light without any keeps the
  // engine's own undeclared views. Any light with them makes light_views "declared".
  struct View {
    std::array<double, 16> view{}, projection{};
  };
  std::vector<std::vector<View>> light_matrices;
};

// Writes `dir`/candidate.json (convention gl). Shadow-map keys only for a shadow map.
void write_candidate_json(const std::filesystem::path& dir, const Declaration& d);

}  // namespace engines
