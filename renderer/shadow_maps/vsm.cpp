// vsm.cpp — variance shadow maps (Donnelly & Lauritzen 2006) filtered over PCSS's penumbra
// (Lauritzen 2007, GPU Gems 3 ch. 8): the depth pass also stores the view depth and its square
// (shaders.cpp's kMomentsFragment, a second attachment with only the offset's constant, by hand);
// PCSS's blocker search and penumbra estimate (pcss.cpp), then the two moments averaged over the
// same 8 × 8 taps (the box a summed-area table returns) and Chebyshev's upper bound against the
// receiver's mean depth there. Bleeds light where two occluders overlap in the filter. Its filter
// stays a grid under RenderOptions::random_taps. Lights without an area: pcf.
#include "lookup.hpp"

namespace shadowref::renderer {
namespace {

const char* const kGlsl = R"glsl(
// The moments (view depth, its square) of the same layers; (0, 0) where nothing was drawn.
uniform sampler2DArray u_moment_map;  // unit 3
// VSM over PCSS's penumbra (Lauritzen 2007, GPU Gems 3 ch. 8): the same search and filter region,
// but the region's depth moments are averaged (what a summed-area table or a mip level returns,
// here by the same 8 x 8 taps) and the lit fraction is Chebyshev's one-tailed bound
// P(depth >= r) <= var / (var + (r - mean)^2) for r beyond the mean. r is the receiver's own mean
// depth over the taps (its plane at each tap's texel centre, where the map stored its depth): a
// planar receiver's moments then cancel exactly, the VSM form of the receiver-plane compare. The
// bound is exact for one occluder depth over a planar receiver (it gives 1 - the occluded share,
// the PCF answer) and too high where two occluders at different depths share the region: the
// technique's known light bleeding. As in pcss, the filter covers the light points above the
// receiver's horizon: their taps are averaged, and their share scales the bound.
// kVsmMinSigma: a floor on the standard deviation, relative to the depth (float moments of depths
// near d lose about d * 2^-12 of their deviation to cancellation in E[d^2] - E[d]^2).
const float kVsmMinSigma = 1e-3;
float vsm(float receiver_depth, int layer) {
  Filter f = filter_for(receiver_depth, layer);
  float above = 0.0;
  vec2 moments = vec2(0.0);
  float receiver = 0.0;
  for (int j = 0; j < kFilterTaps; ++j)
    for (int i = 0; i < kFilterTaps; ++i) {
      vec3 l = filter_light_point(i, j);
      if (dot(f.n, l - v_world) <= 0.0) continue;
      above += 1.0;
      // A tap in another cube face reads that face's moments and the receiver's depth there, both
      // along that face's axis (near the seam, where such taps lie, the two axes measure alike).
      Tap tap = tap_at(v_world + (l - v_world) * f.t, layer, f.plane, f.world_plane);
      float r = receiver_depth;
      if (tap.c.x >= 0.0) r = view_depth(clamp(receiver_z_at(tap), 0.0, 1.0), tap.layer);
      vec2 m = tap.c.x >= 0.0 ? texture(u_moment_map, vec3(tap.c, float(tap.layer))).rg : vec2(0.0);
      // Outside the map or nothing drawn there: no occluder, the receiver itself.
      if (!(m.x > 0.0)) m = vec2(r, r * r);
      moments += m;
      receiver += r;
    }
  float horizon = above / float(kFilterTaps * kFilterTaps);
  if (f.blockers == 0 || above == 0.0) return horizon;
  moments /= above;
  receiver /= above;
  float d = receiver - moments.x;
  if (d <= 0.0) return horizon;
  float variance = max(moments.y - moments.x * moments.x, kVsmMinSigma * kVsmMinSigma * receiver * receiver);
  return horizon * variance / (variance + d * d);
}

float lookup_visibility(vec3 p, vec4 s, float layer) { return vsm(s.w, int(layer)); }
)glsl";

}  // namespace

extern const MapLookup kVsmLookup{
    .name = "vsm",
    .glsl = kGlsl,
    .needs_depth_packing = false,
    .penumbra_search = true,
    .storage = MapStorage::RawDepthAndMoments,
    .offset_factor = kShadowMapOffsetFactor,
    .offset_units = kShadowMapOffsetUnits,
    .shader_offset = ShaderOffset::ConstantOnly,
    .draws_first_surfaces = true,
    .may_store_distance = false,
    .needs_area_light = true,
    .filtered = true,
    .tests_light_points = true,
    .normal_offset = false,
    .filter_radius_texels = 1.0,
    .random_kernel = false,
    .set_light_uniforms = set_rect_light_uniforms,
};

}  // namespace shadowref::renderer
