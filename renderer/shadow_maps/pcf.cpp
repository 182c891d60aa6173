// pcf.cpp — percentage-closer filtering: Reeves, Salesin & Cook 1987, "Rendering antialiased
// shadows with depth maps". A 3 × 3 box of nearest depth compares one texel apart, equal weights;
// the mask calls a pixel lit when at least half the taps are (visibility.png keeps the fraction).
// With RenderOptions::random_taps N, N taps of a Vogel disk of kRandomPcfRadiusTexels turned per
// pixel (shaders.cpp's vogel_tap), as engines take theirs. The kernel's diagonal tap reads a texel
// two texels' slope off the fragment's own, so the depth pass's slope factor is kPcfOffsetFactor.
#include "lookup.hpp"

namespace shadowref::renderer {
namespace {

const char* const kGlsl = R"glsl(
uniform sampler2DArrayShadow u_shadow_map;  // unit 0
float lookup_visibility(vec3 p, vec4 s, float layer) {
  if (u_random_taps > 0) {
    // The Vogel disk's taps out to u_random_pcf_radius texels.
    float rotation = pixel_rotation(), sum = 0.0;
    for (int i = 0; i < u_random_taps; ++i)
      sum += texture(u_shadow_map, vec4(p.xy + u_random_pcf_radius * vogel_tap(i, u_random_taps, rotation) * u_texel, layer, p.z));
    return sum / float(u_random_taps);
  }
  // A 3x3 box of depth compares one texel apart, equal weights (GL_NEAREST taps).
  float sum = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      sum += texture(u_shadow_map, vec4(p.xy + vec2(dx, dy) * u_texel, layer, p.z));
  return sum / 9.0;
}
)glsl";

}  // namespace

extern const MapLookup kPcfLookup{
    .name = "pcf",
    .glsl = kGlsl,
    .needs_depth_packing = false,
    .penumbra_search = false,
    .storage = MapStorage::ComparedDepth,
    .offset_factor = kPcfOffsetFactor,
    .offset_units = kShadowMapOffsetUnits,
    .shader_offset = ShaderOffset::None,
    .draws_first_surfaces = false,
    .may_store_distance = true,
    .needs_area_light = false,
    .filtered = true,
    .tests_light_points = false,
    .normal_offset = true,
    .filter_radius_texels = 1.0,
    .random_kernel = true,
    .set_light_uniforms = nullptr,
};

}  // namespace shadowref::renderer
