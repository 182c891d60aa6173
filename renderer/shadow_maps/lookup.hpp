// lookup.hpp — a shadow-map lookup as a unit: what its depth pass draws, the GLSL its camera pass
// reads the map with, and what it declares in candidate.json, all from the same values.
//
// A lookup is data (one `MapLookup` per file: depth_compare.cpp, pcf.cpp, packed_rgba8.cpp, pcss.cpp,
// vsm.cpp) read by the one light-map code (light_map.cpp: views, cubes, cascades, atlas tiles,
// storage, the depth pass), the one camera pass (shaders.cpp assembles each lookup's program from
// its snippet) and the one declaration (declaration.cpp). The techniques are lookups over plain
// or cascaded fits (shadow_map_techniques.cpp). A correct variant of a lookup (a new bias, a new
// filter) is a field here, its use in one of those three places, and its option.
// Private to the renderer library.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "frame.hpp"

namespace shadowref::renderer {

// Slope-scaled and constant offset of the shadow maps' depth pass, in glPolygonOffset's units (the
// constant in steps of the 24-bit depth): large enough for the two-sided ground's self-comparison at
// grazing light, small enough not to detach shadows visibly at the catalogue's scale. The factor is
// what candidate.json declares as slope_bias_texels.
inline constexpr float kShadowMapOffsetFactor = 2.0f;
// The 3 x 3 PCF kernel compares the fragment's depth with texels up to one texel away on both axes:
// its diagonal tap stands two texels' slope off the fragment's own (|dz/ds| + |dz/dt|), and a texel
// centre half a texel more. A factor of 2 left one-tap acne on lit ground (8/9 fractions on 5 % of
// directional_light's pixels, seen in shaded.png and visibility.png, not in the mask); 3 covers it.
inline constexpr float kPcfOffsetFactor = 3.0f;
inline constexpr float kShadowMapOffsetUnits = 8.0f;
// RenderOptions::random_taps's PCF disk: its radius in texels, the 3 x 3 box's corner taps' reach,
// which PCF's slope factor (kPcfOffsetFactor) covers; what candidate.json declares as
// filter_radius_texels.
inline constexpr double kRandomPcfRadiusTexels = 1.41421356237309515;
// ShadowMapFaults::large_constant_offset: a constant offset of 2^17 depth steps, about 0.8 % of the
// 24-bit range (the size of constant bias that hides acne everywhere, grazing light included),
// which detaches shadows from their contacts.
inline constexpr float kPeterPanUnits = 131072.0f;
// One glPolygonOffset unit as window depth (0..1): one step of the 24-bit depth; what candidate.json
// declares as depth_bias per unit.
inline constexpr double kWindowDepthPerUnit = 1.0 / 16777216.0;

// What a map's layers hold, and how the camera pass reads them.
enum class MapStorage {
  ComparedDepth,       // a depth texture read through GL_COMPARE_REF_TO_TEXTURE (unit 0)
  PackedRgba8,         // RGBA8 colour the depth pass packs its depth into (unit 1); a depth
                       // renderbuffer beside it keeps the nearest surface
  RawDepth,            // a depth texture read raw: the blockers' depths themselves (unit 2)
  RawDepthAndMoments,  // the same, and an RG32F texture of the view depth's first two moments
                       // drawn by the same pass (unit 3)
};

// glPolygonOffset's model done by hand in the depth pass's fragment shader (the offset of a depth
// the rasteriser does not write: a packed colour, a moment), beside or instead of GL's own.
enum class ShaderOffset {
  None,          // GL's polygon offset alone
  Whole,         // factor and units in the shader, no GL offset (PackedRgba8)
  ConstantOnly,  // the units in the shader (the moments), GL's whole offset on the depth texture
};

struct MapLookup {
  std::string_view name;  // in RenderResult::drawn_maps and the program's name: "pcf", "vsm", ...
  // The surface program's snippet: its uniforms and
  //   float lookup_visibility(vec3 p, vec4 s, float layer)
  // p: the window coordinates in the layer (x, y in 0..1, depth clamped to the far plane), s: the
  // point's clip coordinates there, layer: the map layer. Returns the lit fraction, 1 lit.
  const char* glsl;
  bool needs_depth_packing;  // the snippet calls shaders::kDepthPacking's functions
  bool penumbra_search;      // the snippet calls kPenumbraSearchGlsl's functions

  // The depth pass.
  MapStorage storage;
  // glPolygonOffset's factor (the slope-scaled bias, in texels of depth slope) and units (steps of
  // the 24-bit depth, in every convention: a float depth map draws them by hand, light_map.cpp);
  // what candidate.json declares as slope_bias_texels and depth_bias.
  float offset_factor;
  float offset_units;
  ShaderOffset shader_offset;
  // Closed casters' first surfaces drawn (both faces, nothing culled), whatever
  // RenderOptions::depth_faces asks: a blocker search averages the depths of the surfaces nearest
  // the light, so its map must hold them.
  bool draws_first_surfaces;
  // A cube of this lookup may hold distances (RenderOptions::cube_depth; packed depth and the soft
  // lookups' view depths are window depth only).
  bool may_store_distance;

  // The camera pass.
  bool needs_area_light;    // a light without an area (point, spot, directional) is drawn by pcf
  bool filtered;            // writes the lit fraction (visibility.png)
  bool tests_light_points;  // tests every light point it filters over against the surface's own
                            // horizon: no attached-shadow rule on top (PCSS, VSM)
  bool normal_offset;       // moves its lookup by RenderOptions::normal_offset_texels
  // The filter's reach beyond the centre texel on its fixed grid, and whether RenderOptions::random_taps
  // turns it into a rotated Vogel disk (kRandomPcfRadiusTexels for PCF; PCSS's taps over the light).
  double filter_radius_texels;
  bool random_kernel;
  // The light's own uniforms (a soft lookup's rect and its fault switches), or null.
  void (*set_light_uniforms)(const Frame& frame, const Program& program, std::size_t light);
};

// The lookups, one per file, each defined `extern const` there and named where it is used: the
// technique table (shadow_map_techniques.cpp) names them all; PCF, which lights without an area fall
// back to, is named here too.
extern const MapLookup kPcfLookup;  // pcf.cpp

// What light `light` is drawn with under `lookup`: the lookup itself, or PCF for a light without an
// area under a lookup that needs one.
const MapLookup& lookup_for_light(const MapLookup& lookup, const scene::Light& light);

// PCSS's blocker search and penumbra estimate (pcss.cpp), which VSM filters over too, and the
// uniforms of their rect light.
extern const char* const kPenumbraSearchGlsl;
void set_rect_light_uniforms(const Frame& frame, const Program& program, std::size_t light);

}  // namespace shadowref::renderer
