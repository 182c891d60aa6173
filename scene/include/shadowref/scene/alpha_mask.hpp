// shadowref/scene/alpha_mask.hpp — the alpha test of masked casters (a leaf card, a chain-link
// fence: glTF's alphaMode MASK), defined once. The reference (its Embree filter functions), our
// renderer (every depth pass, the planar stencil pass, the camera pass) and the pack's glTF all
// apply exactly this rule; the renderer through alpha_rule_glsl() below, the same operations in
// GLSL, which renderer_test holds texel by texel against the C++ (docs/scene-format.md, "Alpha masks").
//
// The rule, at a surface point with interpolated texture coordinates (u, v) and vertex alpha a_v:
//   texel  (i, j) = (alpha_texel(u, W), alpha_texel(v, H)): NEAREST, the coordinate wrapped
//          (REPEAT, glTF's default sampler): f = t − floor(t) (exact in float), then
//          min(int(f · size), size − 1). v = 0 is the image's top row (glTF's convention), so
//          texel (i, j) is the PNG's pixel (i, j), row j from the top.
//   alpha  A = a8(i, j) · a_v in float, a8 the texel's 8-bit alpha (the PNG's alpha channel, or its
//          grey when it has none; 255 everywhere when the object has vertex alpha only).
//   opaque when A ≥ threshold, threshold = float(cutoff · 255) (glTF: "rendered fully opaque when
//          alpha >= alphaCutoff"): equality is opaque; below it the point lets light (and the
//          camera's ray) through. With a_v = 1 the comparison is of an integer against the
//          threshold, so the C++ and the GLSL agree exactly at every texel; with vertex alpha the
//          interpolated a_v differs between producers by rounding, near the line A = threshold only.
// Cost: a floor, a multiply, a min per axis, one texel read, one multiply and one compare.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "shadowref/conventions.hpp"

namespace shadowref::outputs {
struct Image8;  // outputs/image.hpp
}

namespace shadowref::scene {

// An object's 8-bit alpha texture, row 0 at the top (the PNG's own order).
struct AlphaTexture {
  std::filesystem::path file;   // the PNG it was read from (empty: vertex alpha only, 1 × 1 of 255)
  int width = 1;
  int height = 1;
  std::vector<std::uint8_t> alpha = {255};  // width · height texels
  std::uint8_t at(int i, int j) const {
    return alpha[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i)];
  }
};

// What makes an object masked: per-vertex texture coordinates and vertex alpha (one per position of
// the object's mesh), the texture and the cutoff in [0, 1].
struct AlphaMask {
  std::shared_ptr<const AlphaTexture> texture;  // never null
  std::vector<Vec2<float>> uvs;                 // one per mesh position
  std::vector<float> vertex_alpha;              // one per mesh position (1 where the scene gives none)
  double cutoff = 0.5;
  bool has_vertex_alpha = false;                // the scene gave vertex_alpha (the pack writes COLOR_0)
};

// The texel index of coordinate t on an axis of `size` texels (the rule above): NEAREST with REPEAT.
inline int alpha_texel(float t, int size) {
  const float f = t - std::floor(t);  // in [0, 1), exact
  const int i = static_cast<int>(f * static_cast<float>(size));
  return i < size - 1 ? i : size - 1;
}

// The threshold an 8-bit alpha times the vertex alpha is compared with: cutoff · 255, rounded once to float.
inline float alpha_threshold(double cutoff) { return static_cast<float>(cutoff * 255.0); }

// True when the texel's alpha `a8` times `vertex_alpha` makes the point opaque (A >= threshold).
inline bool alpha_opaque(std::uint8_t a8, float vertex_alpha, float threshold) {
  return static_cast<float>(a8) * vertex_alpha >= threshold;
}

// The rule at barycentric (b1, b2) of triangle `tri` of a masked mesh (the point
// (1 − b1 − b2)·p0 + b1·p1 + b2·p2, Embree's u and v): texture coordinates and vertex alpha
// interpolated in float, in this order, then the texel and the comparison. True: opaque.
inline bool alpha_opaque_at(const AlphaMask& mask, const std::array<std::uint32_t, 3>& tri, float b1, float b2) {
  const float b0 = (1.0f - b1) - b2;
  const Vec2<float>& t0 = mask.uvs[tri[0]];
  const Vec2<float>& t1 = mask.uvs[tri[1]];
  const Vec2<float>& t2 = mask.uvs[tri[2]];
  const float u = (b0 * t0.x() + b1 * t1.x()) + b2 * t2.x();
  const float v = (b0 * t0.y() + b1 * t1.y()) + b2 * t2.y();
  const float a = (b0 * mask.vertex_alpha[tri[0]] + b1 * mask.vertex_alpha[tri[1]]) + b2 * mask.vertex_alpha[tri[2]];
  const AlphaTexture& tex = *mask.texture;
  return alpha_opaque(tex.at(alpha_texel(u, tex.width), alpha_texel(v, tex.height)), a, alpha_threshold(mask.cutoff));
}

// How an image without an alpha channel reads as a mask: the one point where the two formats that
// give masks differ. A JSON scene's `alpha_texture` reads a grey image's grey (docs/scene-format.md,
// "Alpha masks"); glTF gives a texture without alpha the alpha 1 (its base colour's alpha is 1.0
// when absent), so only vertex alpha and the factor's alpha mask it.
enum class WithoutAlpha { Grey, Opaque };

// The mask texture of an 8-bit image (grey, grey + alpha, RGB or RGBA, row 0 at the top) that
// `file` names: the alpha channel's texels, or without one, per `rule`, the grey image's grey
// (Grey) or null (Opaque: alpha 1 everywhere). Throws std::invalid_argument, its message what is
// wrong for the caller to prefix with the file or key, for an RGB image under Grey (neither grey
// nor alpha) and for a side beyond kMaxAlphaTextureSize. Cost: one pass over the texels.
std::shared_ptr<const AlphaTexture> alpha_texture_of(const outputs::Image8& image, std::filesystem::path file,
                                                     WithoutAlpha rule);

// The same operations in GLSL 3.30: `int alpha_texel(float t, int size)` and
// `bool alpha_opaque(uint a8, float vertex_alpha, float threshold)`, for a shader that reads the
// texture as an unsigned-integer R8UI texture (texelFetch: the 8-bit value itself, no conversion).
const char* alpha_rule_glsl();

// The largest |u| or |v| a scene may give: the wrap's floor and subtraction stay exact in float and
// f · size keeps texel precision (2^23 / 64 / 16384 texels leaves 8 bits below a texel).
inline constexpr double kMaxAlphaUv = 64.0;
// The largest mask texture side: the renderer's R8UI texture, and f · size exact to well below a texel.
inline constexpr int kMaxAlphaTextureSize = 16384;

}  // namespace shadowref::scene
