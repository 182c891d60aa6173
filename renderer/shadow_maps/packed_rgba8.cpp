// packed_rgba8.cpp — the shadow map of hardware without depth textures: the depth pass packs its
// window depth into an RGBA8 colour target (shaders.cpp's kPackedDepthFragmentBody, the 24 bits of
// mathlib/depth_packing.hpp, with glPolygonOffset's model done by hand), and the camera pass
// unpacks it and compares 24-bit integers with the fragment's own quantised depth: exact, like a
// depth compare, in the convention's direction (u_lit_greater).
#include "lookup.hpp"

namespace shadowref::renderer {
namespace {

const char* const kGlsl = R"glsl(
uniform sampler2DArray u_packed_map;  // unit 1
float lookup_visibility(vec3 p, vec4 s, float layer) {
  uint stored = unpack_depth_rgba8(texture(u_packed_map, vec3(p.xy, layer)));
  uint here = quantize_depth(p.z);
  return (u_lit_greater ? here >= stored : here <= stored) ? 1.0 : 0.0;
}
)glsl";

}  // namespace

extern const MapLookup kPackedRgba8Lookup{
    .name = "packed-rgba8",
    .glsl = kGlsl,
    .needs_depth_packing = true,
    .penumbra_search = false,
    .storage = MapStorage::PackedRgba8,
    .offset_factor = kShadowMapOffsetFactor,
    .offset_units = kShadowMapOffsetUnits,
    .shader_offset = ShaderOffset::Whole,
    .draws_first_surfaces = false,
    .may_store_distance = false,
    .needs_area_light = false,
    .filtered = false,
    .tests_light_points = false,
    .normal_offset = true,
    .filter_radius_texels = 0.0,
    .random_kernel = false,
    .set_light_uniforms = nullptr,
};

}  // namespace shadowref::renderer
