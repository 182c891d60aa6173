// pcss.cpp — percentage-closer soft shadows: Fernando 2005, "Percentage-closer soft shadows", for
// rect lights. A blocker search over the light's rect seen through the map's near plane and five
// planes nearer the receiver, its depth the mean of the blockers that lie between the receiver and
// the rect where it finds any (Fernando's search counts everything the near plane's slice sees
// nearer than the receiver: on real content, walls and columns beside a shadow), the penumbra estimated
// from the blockers' mean depth, and an 8 × 8 filter over the rect seen through
// that depth, every tap compared with the receiver's own plane (Isidoro 2006's receiver-plane depth
// bias, exact), a tap beyond a cube face's edge read from the neighbouring face. The map is read
// raw and holds the first surfaces (the blockers' depths). With RenderOptions::random_taps N, the
// filter takes N taps of a Vogel disk mapped onto the rect. Lights without an area: pcf.
#include <cstddef>

#include "lookup.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::renderer {

const char* const kPenumbraSearchGlsl = R"glsl(
// The soft lookups' map, read raw, and the rect light it is soft for.
uniform sampler2DArray u_depth_map;  // unit 2: the depth texture without its compare
uniform vec3 u_rect_u;               // the rect light's edges (world); u_light is its centre
uniform vec3 u_rect_v;
uniform bool u_blocker_at_receiver;  // fault switches (renderer/faults.hpp, SoftShadowFaults)
uniform bool u_taps_in_own_face;
uniform bool u_search_whole_cone;
// PCSS (Fernando 2005, "Percentage-closer soft shadows") for a rect light, in the map of its centre.
// receiver_depth: the fragment's depth along the view axis of its layer. The receiver is the
// fragment's own plane (its face normal), carried into texture space (planes stay planes under
// B * P * V), so every tap compares the map with the receiver's depth at
// that tap's texel centre, where the map was rasterised: no self-shadowing at kernel scale on planar
// receivers (Isidoro 2006's receiver-plane depth bias, exact instead of from derivatives).
// 1. Blocker search: 6 x 6 taps over the light's rect seen from p through the nearest plane a
//    blocker can lie on (the map's near plane, but at least a tenth of the way from the light),
//    and through five planes ever nearer p; the mean depth d_b of the blockers that truly lie
//    between p and the rect (penumbra_plane says why).
// 2. Filter: 8 x 8 taps over the light's rect seen from p through the plane at d_b (the penumbra
//    estimate (d_r - d_b) / d_b times the light, in the light's own shape); the unblocked fraction.
const int kSearchTaps = 6;
const int kFilterTaps = 8;
// The receiver's plane (world), or 0 when it is seen edge-on from the light's centre: a plane
// through (or within a hundredth of its distance of) the light's centre has an ill-conditioned
// depth across the map, so such a receiver is compared at its own depth and the polygon offset's
// slope term protects it (plane.z = 0 selects that in blocker_at).
vec4 receiver_world_plane() {
  vec3 to_light = u_light.xyz - v_world;
  if (abs(dot(v_normal, to_light)) < 0.01 * length(to_light)) return vec4(0.0);
  return vec4(v_normal, -dot(v_normal, v_world));
}
// A tap: the texel centre c of a world point in the layer that holds the point (for a cube, the
// face a cube-map lookup picks for its direction from the light: a filter reaching across a face's
// edge reads the neighbouring face, not nothing), that layer, and the receiver's plane carried into
// its texture space (planes stay planes under B * P * V); c.x < 0 outside the map.
struct Tap {
  vec2 c;
  int layer;
  vec4 plane;
};
Tap tap_at(vec3 x, int layer, vec4 plane_in_layer, vec4 world_plane) {
  Tap tap;
  tap.layer = layer;
  tap.plane = plane_in_layer;
  if (u_layout == kLayoutCube && !u_taps_in_own_face) {  // FAULT when set: the seam leaks
    int face = cube_face(x - u_light.xyz);
    if (face != layer) {
      tap.layer = face;
      tap.plane = transpose(u_world_from_layer[face]) * world_plane;
    }
  }
  tap.c = vec2(-1.0);
  vec4 t = u_layer_from_world[tap.layer] * vec4(x, 1.0);
  if (t.w <= 0.0) return tap;
  vec2 uv = t.xy / t.w;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return tap;
  tap.c = (floor(uv / u_texel) + 0.5) * u_texel;  // the texel centre
  return tap;
}
float view_depth(float window_depth, int layer) {
  return 1.0 / (u_inv_view_depth[layer].x * window_depth + u_inv_view_depth[layer].y);
}
// The receiver's window depth at the tap's texel centre, in the tap's layer (its own depth there
// when it is seen edge-on).
float receiver_z_at(Tap tap) {
  if (tap.plane.z != 0.0) return -(tap.plane.x * tap.c.x + tap.plane.y * tap.c.y + tap.plane.w) / tap.plane.z;
  vec4 s = u_layer_from_world[tap.layer] * vec4(v_world, 1.0);
  return s.z / s.w;
}
// The world point of the surface stored at the tap (window depth `stored`).
vec3 stored_point(Tap tap, float stored) {
  vec4 w = u_world_from_layer[tap.layer] * vec4(tap.c, stored, 1.0);
  return w.xyz / w.w;
}
// Whether a surface at world point b truly blocks a point of the light from the receiver: it lies
// between the receiver and the light's plane, and the ray from the receiver through it meets that
// plane inside the rect.
bool blocks_the_rect(vec3 b) {
  vec3 ln = cross(u_rect_u, u_rect_v);
  float dp = dot(ln, v_world - u_light.xyz), db = dot(ln, b - u_light.xyz);
  if (dp * db <= 0.0 || abs(db) >= abs(dp)) return false;
  vec3 h = v_world + (dp / (dp - db)) * (b - v_world) - u_light.xyz;
  vec2 ab = vec2(dot(h, u_rect_u) / dot(u_rect_u, u_rect_u), dot(h, u_rect_v) / dot(u_rect_v, u_rect_v));
  return all(lessThanEqual(abs(ab), vec2(0.5)));
}
// Whether a surface at world point b stands clear of the receiver's own plane, on the light's
// side: a true blocker of a light point above the receiver's horizon lies on the segment to it, so
// at that point's elevation above the horizon. Below sin 3° = 0.05 a texel read next to p may hold
// the receiver's own surface or its neighbour on a curved or grazing receiver (depth steps, the
// polygon offset), and counted at the receiver's depth it would collapse the filter onto p's own
// texel: speckled self-shadowing on faces the light grazes (the Cornell box's tall block). The
// blockers that only graze the horizon so dropped from the mean hide light points that matter
// least to the estimate.
bool clear_of_receiver(vec3 b) {
  vec3 d = b - v_world;
  vec3 n = gl_FrontFacing ? v_normal : -v_normal;
  return dot(n, d) > 0.05 * length(d);
}
// The stored window depth at the tap when it holds something nearer than the receiver's plane
// there (a blocker), else -1. `layer` is the fragment's. A tap read from another cube face counts
// only when what it holds truly blocks a point of the light from the receiver (blocks_the_rect):
// far from the fragment's own face the receiver's plane says nothing (near the light the search's
// taps reach any direction: the ceiling the light hangs under, the far walls), so there the
// geometry decides; near a seam, where a filter straddles two faces, both agree.
float blocker_at(Tap tap, int layer) {
  if (tap.c.x < 0.0) return -1.0;
  float z = receiver_z_at(tap);
  float stored = texture(u_depth_map, vec3(tap.c, float(tap.layer))).r;
  bool lit = u_lit_greater ? z >= stored : z <= stored;
  if (lit) return -1.0;
  if (tap.layer != layer && !blocks_the_rect(stored_point(tap, stored))) return -1.0;
  return stored;
}
// A blocker's depth along the view axis of `layer` (the fragment's): a blocker found in another
// cube face is carried back through its world point.
float blocker_depth_in(Tap tap, float stored, int layer) {
  if (tap.layer == layer) return view_depth(stored, layer);
  return (u_layer_from_world[layer] * vec4(stored_point(tap, stored), 1.0)).w;
}
// Steps 1 and 2's plane: the fraction of the way from p to the light at which the light's rect,
// seen from p, covers the filter's texels (0 when the search finds no blocker: `blockers` is 0).
float penumbra_plane(vec4 plane, vec4 world_plane, float receiver_depth, int layer, out int blockers) {
  // The nearest depth a blocker can have: the map's near plane (window depth 0, or 1 reversed).
  // Not nearer than a tenth of the receiver's depth: a cube face's near plane may touch the light,
  // where the rect's own image would fill the search.
  float near_depth = max(view_depth(u_reversed ? 1.0 : 0.0, layer), 0.1 * receiver_depth);
  float t_search = clamp(1.0 - near_depth / receiver_depth, 0.0, 1.0);
  // Slice k of the pyramid from p to the rect lies at t_search / 2^k (six slices: from the near
  // plane down to 3 % of its way, where contact blockers lie). The near plane's slice alone is the
  // textbook search: along the light centre's rays it takes in a cone far wider than the pyramid at
  // any deeper depth, and what it finds there nearer than the receiver's plane (a wall or a column
  // beside a long shadow, not between it and the light) is no blocker of p. So a blocker found by
  // that slice, or a tested one in any slice, says that there is one; the mean depth is that of
  // the blockers, in every slice, that truly block a point of the rect from p (blocks_the_rect)
  // and stand clear of its plane (clear_of_receiver), or, where none does (a blocker between the
  // taps' rays), the near slice's as in the textbook.
  float cone_sum = 0.0, pyramid_sum = 0.0;
  int cone = 0, pyramid = 0;
  int slices = u_search_whole_cone ? 1 : 6;  // FAULT when set: the textbook search
  for (int k = 0; k < slices; ++k) {
    float t_k = t_search * exp2(-float(k));
    for (int j = 0; j < kSearchTaps; ++j)
      for (int i = 0; i < kSearchTaps; ++i) {
        vec2 ab = (vec2(i, j) + 0.5) / float(kSearchTaps) - 0.5;
        vec3 l = u_light.xyz + ab.x * u_rect_u + ab.y * u_rect_v;
        Tap tap = tap_at(v_world + (l - v_world) * t_k, layer, plane, world_plane);
        float d = blocker_at(tap, layer);
        if (d < 0.0) continue;
        float depth = blocker_depth_in(tap, d, layer);
        bool near_slice = k == 0;
        if (near_slice) {
          cone_sum += depth;
          ++cone;
        }
        if (u_search_whole_cone) continue;
        vec3 b = stored_point(tap, d);
        if (blocks_the_rect(b) && clear_of_receiver(b)) {
          pyramid_sum += depth;
          ++pyramid;
        }
      }
  }
  blockers = cone + pyramid;
  float sum = pyramid > 0 ? pyramid_sum : cone_sum;
  int counted = pyramid > 0 ? pyramid : cone;
  float blocker_depth = blockers == 0 ? receiver_depth : sum / float(counted);
  if (u_blocker_at_receiver) blocker_depth = receiver_depth;  // FAULT: the receiver's own depth
  return clamp(1.0 - blocker_depth / receiver_depth, 0.0, 1.0);
}
// The filter tap (i, j) of kFilterTaps x kFilterTaps: its point on the light's rect.
vec3 filter_light_point(int i, int j) {
  vec2 ab = (vec2(i, j) + 0.5) / float(kFilterTaps) - 0.5;
  return u_light.xyz + ab.x * u_rect_u + ab.y * u_rect_v;
}
// Steps 1 and 2 for the fragment in `layer`: the receiver's plane (world and in the layer), the
// normal its horizon is tested with, and the filter's plane t (blockers: how many the search found).
struct Filter {
  vec4 world_plane;
  vec4 plane;
  vec3 n;
  int blockers;
  float t;
};
Filter filter_for(float receiver_depth, int layer) {
  Filter f;
  f.world_plane = receiver_world_plane();
  f.plane = transpose(u_world_from_layer[layer]) * f.world_plane;
  // A light point behind the receiver's own plane is hidden by the receiver itself: an area light
  // half below the horizon of a surface lights it by half (the soft terminator on a ball).
  f.n = gl_FrontFacing ? v_normal : -v_normal;
  f.t = penumbra_plane(f.plane, f.world_plane, receiver_depth, layer, f.blockers);
  return f;
}
)glsl";

namespace {

const char* const kGlsl = R"glsl(
// Shirley & Chiu 1997's concentric map inverted: a point of the unit disk to the square [-1, 1]²,
// area-preserving, so that a disk kernel's taps stay uniform over the rect light.
vec2 disk_to_square(vec2 d) {
  float r = length(d);
  if (r == 0.0) return vec2(0.0);
  float phi = atan(d.y, d.x);
  if (phi < -0.25 * kPi) phi += 2.0 * kPi;  // [-pi/4, 7pi/4): the four wedges in order
  float w = phi / (0.25 * kPi);
  if (w < 1.0) return vec2(r, r * w);
  if (w < 3.0) return vec2(-r * (w - 2.0), r);
  if (w < 5.0) return vec2(-r, -r * (w - 4.0));
  return vec2(r * (w - 6.0), -r);
}
// Whether light point l lights the fragment: above its horizon, and no blocker at the filter's tap.
bool filter_tap_lit(Filter f, vec3 l, int layer) {
  if (dot(f.n, l - v_world) <= 0.0) return false;
  return f.blockers == 0 || blocker_at(tap_at(v_world + (l - v_world) * f.t, layer, f.plane, f.world_plane), layer) < 0.0;
}
float pcss(float receiver_depth, int layer) {
  Filter f = filter_for(receiver_depth, layer);
  float lit = 0.0;
  if (u_random_taps > 0) {
    float rotation = pixel_rotation();
    for (int i = 0; i < u_random_taps; ++i) {
      vec2 ab = 0.5 * disk_to_square(vogel_tap(i, u_random_taps, rotation));
      if (filter_tap_lit(f, u_light.xyz + ab.x * u_rect_u + ab.y * u_rect_v, layer)) lit += 1.0;
    }
    return lit / float(u_random_taps);
  }
  for (int j = 0; j < kFilterTaps; ++j)
    for (int i = 0; i < kFilterTaps; ++i)
      if (filter_tap_lit(f, filter_light_point(i, j), layer)) lit += 1.0;
  return lit / float(kFilterTaps * kFilterTaps);
}
float lookup_visibility(vec3 p, vec4 s, float layer) { return pcss(s.w, int(layer)); }
)glsl";

}  // namespace

void set_rect_light_uniforms(const Frame& frame, const Program& p, std::size_t i) {
  const GlFunctions& gl = frame.gl;
  const scene::Light& light = frame.scene.lights[i];
  const SoftShadowFaults& f = frame.faults().soft;
  const Vec3<float> u = (f.light_size_scale * light.edge_u).cast<float>();  // FAULT when the scale is not 1
  const Vec3<float> v = (f.light_size_scale * light.edge_v).cast<float>();
  gl.Uniform3f(p.at(gl, "u_rect_u"), u.x(), u.y(), u.z());
  gl.Uniform3f(p.at(gl, "u_rect_v"), v.x(), v.y(), v.z());
  gl.Uniform1i(p.at(gl, "u_blocker_at_receiver"), f.blocker_depth_from_receiver ? 1 : 0);
  gl.Uniform1i(p.at(gl, "u_taps_in_own_face"), f.taps_stay_in_face ? 1 : 0);
  gl.Uniform1i(p.at(gl, "u_search_whole_cone"), f.search_whole_cone ? 1 : 0);
}

extern const MapLookup kPcssLookup{
    .name = "pcss",
    .glsl = kGlsl,
    .needs_depth_packing = false,
    .penumbra_search = true,
    .storage = MapStorage::RawDepth,
    .offset_factor = kShadowMapOffsetFactor,
    .offset_units = kShadowMapOffsetUnits,
    .shader_offset = ShaderOffset::None,
    .draws_first_surfaces = true,
    .may_store_distance = false,
    .needs_area_light = true,
    .filtered = true,
    .tests_light_points = true,
    .normal_offset = false,
    .filter_radius_texels = 1.0,
    .random_kernel = true,
    .set_light_uniforms = set_rect_light_uniforms,
};

}  // namespace shadowref::renderer
