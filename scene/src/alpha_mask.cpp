// alpha_mask.cpp — the alpha rule's GLSL (alpha_mask.hpp), beside the C++ it mirrors operation for
// operation: change one, change both (renderer_test's texel-by-texel check holds them together);
// and the one reader of a mask texture's alpha, for both scene formats.
#include "shadowref/scene/alpha_mask.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "shadowref/outputs/image.hpp"

namespace shadowref::scene {

std::shared_ptr<const AlphaTexture> alpha_texture_of(const outputs::Image8& image, std::filesystem::path file,
                                                     WithoutAlpha rule) {
  const bool has_alpha = image.channels == 2 || image.channels == 4;
  if (!has_alpha && rule == WithoutAlpha::Opaque) return nullptr;
  if (image.channels == 3) throw std::invalid_argument("an RGB image without alpha (expected grey, grey + alpha or RGBA)");
  if (image.width > kMaxAlphaTextureSize || image.height > kMaxAlphaTextureSize)
    throw std::invalid_argument("larger than " + std::to_string(kMaxAlphaTextureSize) + " texels on a side");
  auto texture = std::make_shared<AlphaTexture>();
  texture->file = std::move(file);
  texture->width = image.width;
  texture->height = image.height;
  texture->alpha.resize(image.pixel_count());
  // The last channel: the alpha, or a grey image's only one.
  const std::size_t c = static_cast<std::size_t>(image.channels);
  for (std::size_t i = 0; i < texture->alpha.size(); ++i) texture->alpha[i] = image.pixels[i * c + c - 1];
  return texture;
}

const char* alpha_rule_glsl() {
  return R"glsl(
// The alpha rule (scene/alpha_mask.hpp): NEAREST texel with REPEAT, opaque when a8 * a_v >= threshold.
int alpha_texel(float t, int size) {
  float f = t - floor(t);
  return min(int(f * float(size)), size - 1);
}
bool alpha_opaque(uint a8, float vertex_alpha, float threshold) {
  return float(a8) * vertex_alpha >= threshold;
}
)glsl";
}

}  // namespace shadowref::scene
