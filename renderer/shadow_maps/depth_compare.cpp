// depth_compare.cpp — the plain shadow-map lookup: Williams 1978, "Casting curved shadows on curved
// surfaces". One nearest tap of a depth texture through GL_COMPARE_REF_TO_TEXTURE (a
// sampler2DArrayShadow: one layer, a cube's six faces or the cascades), the convention's "lit"
// compare function set on the texture (light_map.cpp). Drawn with front faces of closed casters
// culled (RenderOptions::depth_faces may say otherwise) and glPolygonOffset(2, 8).
#include "lookup.hpp"

namespace shadowref::renderer {
namespace {

const char* const kGlsl = R"glsl(
uniform sampler2DArrayShadow u_shadow_map;  // unit 0
float lookup_visibility(vec3 p, vec4 s, float layer) {
  return texture(u_shadow_map, vec4(p.xy, layer, p.z));
}
)glsl";

}  // namespace

extern const MapLookup kDepthCompareLookup{
    .name = "depth-compare",
    .glsl = kGlsl,
    .needs_depth_packing = false,
    .penumbra_search = false,
    .storage = MapStorage::ComparedDepth,
    .offset_factor = kShadowMapOffsetFactor,
    .offset_units = kShadowMapOffsetUnits,
    .shader_offset = ShaderOffset::None,
    .draws_first_surfaces = false,
    .may_store_distance = true,
    .needs_area_light = false,
    .filtered = false,
    .tests_light_points = false,
    .normal_offset = true,
    .filter_radius_texels = 0.0,
    .random_kernel = false,
    .set_light_uniforms = nullptr,
};

}  // namespace shadowref::renderer
