// shaders.cpp — GLSL 3.30 core sources, as C++ raw strings so that the renderer is one binary.
//
// The RGBA8 depth functions (quantize_depth, pack_depth_rgba8, unpack_depth_rgba8) mirror
// mathlib/include/shadowref/depth_packing.hpp operation for operation: one float multiply by
// 2^24 − 1, roundEven (= nearbyint under the default rounding mode), integer shifts. Change one,
// change both (depth_packing_test.cpp tests the C++ side).
#include "shaders.hpp"

namespace shadowref::renderer::shaders {

const char* const kSceneVertex = R"glsl(#version 330 core
layout(location = 0) in vec4 a_position;   // world space; w = 0: a point at infinity
layout(location = 1) in vec3 a_normal;     // the face normal (objects; unused by volumes)
uniform mat4 u_clip_from_world;            // P · V (· S for planar shadows)
uniform mat4 u_shadow_from_world;          // B · P_light · V_light (shadow maps), else anything
out vec3 v_world;
out vec4 v_shadow;
flat out vec3 v_normal;
invariant gl_Position;
void main() {
  gl_Position = u_clip_from_world * a_position;
  v_world = a_position.xyz;
  // Per vertex, interpolated perspective-correctly and divided per fragment: exact projective
  // texturing, the same as computing B · P · V · p per fragment.
  v_shadow = u_shadow_from_world * a_position;
  v_normal = a_normal;
}
)glsl";

const char* const kFlatFragment = R"glsl(#version 330 core
uniform vec4 u_colour;
out vec4 o_colour;
void main() { o_colour = u_colour; }
)glsl";

// vsm's light pass (Donnelly & Lauritzen 2006): the first two moments of the fragment's depth plus
// an offset done by hand as in the packed-depth pass (shadow_map.cpp passes only its constant part),
// as view depth along the light's axis: linear, so that averaging moments means something, and
// without the window depth's coarse float steps near 1.
const char* const kMomentsFragment = R"glsl(#version 330 core
uniform vec2 u_layer_inv_view_depth;  // 1 / view depth = x * window depth + y
uniform float u_offset_factor;        // glPolygonOffset's, with the convention's sign
uniform float u_offset_units;
out vec4 o_moments;
void main() {
  float z = gl_FragCoord.z;
  float m = max(abs(dFdx(z)), abs(dFdy(z)));
  z += u_offset_factor * m + u_offset_units / 16777215.0;
  float w = 1.0 / (u_layer_inv_view_depth.x * z + u_layer_inv_view_depth.y);
  o_moments = vec4(w, w * w, 0.0, 1.0);
}
)glsl";

// A distance cube's light pass (RenderOptions::cube_depth), as engines write point-light cubes
// (three.js MeshDistanceMaterial: (distance - near) / (far - near)): the distance from the light's
// centre over the range, written as the fragment's depth, so that the depth test keeps the nearest
// surface along each texel's ray (distance and the face's axis depth grow together along a ray). A
// polygon offset moves only the rasterised depth, not a written one, so its model is applied by hand
// as in the packed-depth pass: factor * m + units * 2^-24, m the distance's largest change per texel.
const char* const kDistanceFragment = R"glsl(#version 330 core
in vec3 v_world;
uniform vec3 u_light_position;
uniform float u_distance_range;
uniform float u_offset_factor;
uniform float u_offset_units;
void main() {
  float d = distance(v_world, u_light_position) / u_distance_range;
  float m = max(abs(dFdx(d)), abs(dFdy(d)));
  gl_FragDepth = clamp(d + u_offset_factor * m + u_offset_units / 16777215.0, 0.0, 1.0);
}
)glsl";

// The depth packing shared by the two shaders below (mirror of depth_packing.hpp); glShaderSource
// joins it between the version line and each body.
const char* const kDepthPacking = R"glsl(
const float kPackedDepthMax = 16777215.0;  // 2^24 - 1
uint quantize_depth(float d) {
  if (isnan(d)) return 16777215u;          // NaN -> far, as mathlib
  if (!(d > 0.0)) return 0u;
  if (!(d < 1.0)) return 16777215u;
  return uint(roundEven(d * kPackedDepthMax));
}
vec4 pack_depth_rgba8(float d) {
  uint q = quantize_depth(d);
  // b / 255 converts back to exactly b in the UNORM8 target (round(f * 255)).
  return vec4(float(q >> 16u), float((q >> 8u) & 255u), float(q & 255u), 255.0) / 255.0;
}
uint unpack_depth_rgba8(vec4 texel) {
  uvec4 b = uvec4(roundEven(texel * 255.0));
  return (b.r << 16u) | (b.g << 8u) | b.b;
}
)glsl";

const char* const kVersion = "#version 330 core\n";

const char* const kPcssDefine = "#define SHADOWREF_PCSS\n";

const char* const kPackedDepthFragmentBody = R"glsl(
// glPolygonOffset done by hand (RGBA8 has no depth to offset): o = factor * m + units * r, with
// m = max(|dz/dx|, |dz/dy|) and r = 2^-24, the 24-bit step that the packing keeps.
uniform float u_offset_factor;
uniform float u_offset_units;
out vec4 o_colour;
void main() {
  float z = gl_FragCoord.z;
  float m = max(abs(dFdx(z)), abs(dFdy(z)));
  o_colour = pack_depth_rgba8(z + u_offset_factor * m + u_offset_units / kPackedDepthMax);
}
)glsl";

const char* const kSurfaceFragmentBody = R"glsl(
in vec3 v_world;
in vec4 v_shadow;
flat in vec3 v_normal;
uniform int u_mode;                  // 0 ambient, 1 one light's contribution (and o_mask), 2 the 0/1 mask
uniform int u_shadow;                // 0 none, 1 depth compare, 2 PCF 3x3, 3 RGBA8 packed depth, 4 PCSS, 5 VSM
uniform vec3 u_albedo;
uniform float u_ambient;
uniform vec4 u_light;                // homogeneous: w = 1 point / spot, w = 0 directional
uniform float u_light_intensity;
uniform vec4 u_spot;                 // xyz: the spot's axis (into the scene), w: cos(cone); w <= -1: no cone
uniform sampler2DArrayShadow u_shadow_map;  // unit 0: one layer, a cube's six faces, or the cascades
uniform sampler2DArray u_packed_map;        // unit 1 (RGBA8 variant), the same layers
uniform vec2 u_texel;                // 1 / shadow-map size
uniform int u_layout;                // 0: one map through v_shadow; 1: a cube's six faces; 2: cascades,
                                     // each picked per fragment (mathlib's light_view_of)
uniform mat4 u_layer_from_world[6];  // B · P · V per layer: the faces +x, -x, +y, -y, +z, -z, or the cascades
uniform vec4 u_cascade_depth;        // the camera depth of a world point: dot(u_cascade_depth, (p, 1))
uniform vec4 u_cascade_begin;        // cascade i decides depths in [begin[i], end[i]) (up to 4 cascades)
uniform vec4 u_cascade_end;
uniform int u_reversed;              // 1: reversed-Z maps (near 1, far 0)
uniform int u_lit_greater;           // the RGBA8 compare: 1 lit when here >= stored (GEQUAL), 0 when
                                     // here <= stored (LEQUAL); a depth texture has its own compare function
// PCSS (u_shadow 4): the map read raw, and the rect light it is soft for.
uniform sampler2DArray u_depth_map;  // unit 2: the depth texture without its compare
uniform mat4 u_world_from_layer[6];  // the inverses of u_layer_from_world
uniform vec2 u_inv_view_depth[6];    // per layer: 1 / (depth along the view axis) = x * window depth + y
uniform vec3 u_rect_u;               // the rect light's edges (world); u_light is its centre
uniform vec3 u_rect_v;
uniform int u_blocker_at_receiver;   // fault switches (renderer/faults.hpp, SoftShadowFaults)
uniform int u_taps_in_own_face;
uniform int u_random_taps;           // 0: each filter's fixed grid; N: N taps of a Vogel disk rotated per pixel
uniform float u_random_pcf_radius;   // PCF's disk radius in texels (frame.hpp, kRandomPcfRadiusTexels)
uniform float u_normal_offset_texels;  // hard maps: the lookup moved along the normal by this many texels
uniform float u_distance_range;      // > 0: a cube holding distance / this range (kDistanceFragment), 0: window depth
// VSM (u_shadow 5): the moments (view depth, its square) of the same layers; (0, 0) where nothing was drawn.
uniform sampler2DArray u_moment_map; // unit 3
layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_mask;    // mode 1: the lit fraction (red) and the 0/1 mask (green)

// The cube face a cube-map lookup picks for direction d from the light: the axis of its largest
// component (+x, -x, +y, -y, +z, -z).
int cube_face(vec3 d) {
  vec3 a = abs(d);
  return (a.x >= a.y && a.x >= a.z) ? (d.x >= 0.0 ? 0 : 1)
       : (a.y >= a.z)               ? (d.y >= 0.0 ? 2 : 3)
                                    : (d.z >= 0.0 ? 4 : 5);
}

// A randomized kernel (RenderOptions::random_taps): tap i of N of a Vogel disk (Vogel 1979: radius
// sqrt((i + 1/2) / N), angle i times the golden angle; evenly spread at any N), turned per pixel by
// interleaved gradient noise (Jimenez 2014, "Next generation post processing in Call of Duty:
// Advanced Warfare"), as engines take their PCF and PCSS taps. A point of the unit disk.
const float kPi = 3.14159265;
float pixel_rotation() {
  vec2 xy = floor(gl_FragCoord.xy);
  return 2.0 * kPi * fract(52.9829189 * fract(dot(xy, vec2(0.06711056, 0.00583715))));
}
vec2 vogel_tap(int i, int n, float rotation) {
  float r = sqrt((float(i) + 0.5) / float(n));
  float a = float(i) * 2.39996323 + rotation;
  return r * vec2(cos(a), sin(a));
}

#ifdef SHADOWREF_PCSS  // only in the soft program (kPcssDefine): llvmpipe pays for dead branches
// PCSS (Fernando 2005, "Percentage-closer soft shadows") for a rect light, in the map of its centre.
// receiver_depth: the fragment's depth along the view axis of its layer. The receiver is the
// fragment's own plane (its face normal), carried into texture space (planes stay planes under
// B * P * V), so every tap compares the map with the receiver's depth at
// that tap's texel centre, where the map was rasterised: no self-shadowing at kernel scale on planar
// receivers (Isidoro 2006's receiver-plane depth bias, exact instead of from derivatives).
// 1. Blocker search: 6 x 6 taps over the light's rect seen from p through the nearest plane a
//    blocker can lie on (the map's near plane, but at least a tenth of the way from the light);
//    the blockers' mean depth d_b.
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
  if (u_layout == 1 && u_taps_in_own_face == 0) {  // FAULT when set: the seam leaks
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
// The stored window depth at the tap when it holds something nearer than the receiver's plane
// there (a blocker), else -1. `layer` is the fragment's. A tap read from another cube face counts
// only when what it holds truly blocks a point of the light from the receiver: it lies between the
// receiver and the light's plane, and the ray from the receiver through it meets that plane inside
// the rect. Far from the fragment's own face the receiver's plane says nothing (near the light the
// search's taps reach any direction: the ceiling the light hangs under, the far walls), so there
// the geometry decides; near a seam, where a filter straddles two faces, both agree.
float blocker_at(Tap tap, int layer) {
  if (tap.c.x < 0.0) return -1.0;
  float z = receiver_z_at(tap);
  float stored = texture(u_depth_map, vec3(tap.c, float(tap.layer))).r;
  bool lit = u_lit_greater == 1 ? z >= stored : z <= stored;
  if (lit) return -1.0;
  if (tap.layer != layer) {
    vec4 w = u_world_from_layer[tap.layer] * vec4(tap.c, stored, 1.0);
    vec3 b = w.xyz / w.w;
    vec3 ln = cross(u_rect_u, u_rect_v);
    float dp = dot(ln, v_world - u_light.xyz), db = dot(ln, b - u_light.xyz);
    if (dp * db <= 0.0 || abs(db) >= abs(dp)) return -1.0;
    vec3 h = v_world + (dp / (dp - db)) * (b - v_world) - u_light.xyz;
    vec2 ab = vec2(dot(h, u_rect_u) / dot(u_rect_u, u_rect_u), dot(h, u_rect_v) / dot(u_rect_v, u_rect_v));
    if (any(greaterThan(abs(ab), vec2(0.5)))) return -1.0;
  }
  return stored;
}
// A blocker's depth along the view axis of `layer` (the fragment's): a blocker found in another
// cube face is carried back through its world point.
float blocker_depth_in(Tap tap, float stored, int layer) {
  if (tap.layer == layer) return view_depth(stored, layer);
  vec4 w = u_world_from_layer[tap.layer] * vec4(tap.c, stored, 1.0);
  return (u_layer_from_world[layer] * vec4(w.xyz / w.w, 1.0)).w;
}
// Steps 1 and 2's plane: the fraction of the way from p to the light at which the light's rect,
// seen from p, covers the filter's texels (0 when the search finds no blocker: `blockers` is 0).
float penumbra_plane(vec4 plane, vec4 world_plane, float receiver_depth, int layer, out int blockers) {
  // The nearest depth a blocker can have: the map's near plane (window depth 0, or 1 reversed).
  // Not nearer than a tenth of the receiver's depth: a cube face's near plane may touch the light,
  // where the rect's own image would fill the search.
  float near_depth = max(view_depth(u_reversed == 1 ? 1.0 : 0.0, layer), 0.1 * receiver_depth);
  float t_search = clamp(1.0 - near_depth / receiver_depth, 0.0, 1.0);
  float sum = 0.0;
  blockers = 0;
  for (int j = 0; j < kSearchTaps; ++j)
    for (int i = 0; i < kSearchTaps; ++i) {
      vec2 ab = (vec2(i, j) + 0.5) / float(kSearchTaps) - 0.5;
      vec3 l = u_light.xyz + ab.x * u_rect_u + ab.y * u_rect_v;
      Tap tap = tap_at(v_world + (l - v_world) * t_search, layer, plane, world_plane);
      float d = blocker_at(tap, layer);
      if (d >= 0.0) {
        sum += blocker_depth_in(tap, d, layer);
        ++blockers;
      }
    }
  float blocker_depth = blockers == 0 ? receiver_depth : sum / float(blockers);
  if (u_blocker_at_receiver == 1) blocker_depth = receiver_depth;  // FAULT: the receiver's own depth
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

#endif

// Light visibility from the shadow map: 1 lit, 0 shadowed (fractions with PCF).
float shadow_visibility() {
  if (u_shadow == 0) return 1.0;
  vec4 s = v_shadow;
  float layer = 0.0;
  if (u_layout == 2) {
    // The first cascade whose range ends beyond the fragment's camera depth (the first and the last
    // open-ended); none (a gap between them): no map decides, lit.
    float depth = dot(u_cascade_depth, vec4(v_world, 1.0));
    int c = -1;
    for (int i = 3; i >= 0; --i)
      if (depth < u_cascade_end[i]) c = i;
    if (c < 0 || depth < u_cascade_begin[c]) return 1.0;
    s = u_layer_from_world[c] * vec4(v_world, 1.0);
    layer = float(c);
  }
  if (u_layout == 1) {
    // The face whose axis is the largest component of the direction from the light (that of a
    // cube-map lookup); each face's map reaches a few texels beyond 90 degrees, so the PCF taps
    // of a fragment on a face's edge stay in that face.
    int face = cube_face(v_world - u_light.xyz);
    s = u_layer_from_world[face] * vec4(v_world, 1.0);
    layer = float(face);
  }
  // A normal offset (RenderOptions::normal_offset_texels; the hard maps only): the point looked up
  // moves along the surface normal, turned toward the light, by that many of the map's texels as
  // wide as they are at the point (one texel along the map's x at the point's own depth).
  vec3 at = v_world;  // the point looked up
  if (u_normal_offset_texels > 0.0 && u_shadow != 4 && u_shadow != 5) {
    int l = int(layer);
    vec4 c = u_layer_from_world[l] * vec4(v_world, 1.0);
    vec4 a = u_world_from_layer[l] * vec4(c.xy / c.w + vec2(u_texel.x, 0.0), c.z / c.w, 1.0);
    float texel_world = distance(a.xyz / a.w, v_world);
    vec3 to_light = u_light.w == 0.0 ? u_light.xyz : u_light.xyz - v_world;
    vec3 n = dot(v_normal, to_light) < 0.0 ? -v_normal : v_normal;
    at = v_world + u_normal_offset_texels * texel_world * normalize(n);
    s = u_layer_from_world[l] * vec4(at, 1.0);
  }
  // Behind the light's centre of projection: outside the map, which knows of no occluder there
  // (only a spot's or directional light's single map has such points; a cube has none).
  if (s.w <= 0.0) return 1.0;
  vec3 p = s.xyz / s.w;                // = textureProj's divide
  if (any(lessThan(p.xy, vec2(0.0))) || any(greaterThan(p.xy, vec2(1.0)))) return 1.0;
  // Beyond the light's far plane: compare as at the far plane, where nothing occludes.
  p.z = u_reversed == 1 ? max(p.z, 0.0) : min(p.z, 1.0);
  // A distance cube: the looked-up point's own distance over the range, compared (GL_LEQUAL, in
  // every convention) with the nearest distance stored along the texel's ray.
  if (u_layout == 1 && u_distance_range > 0.0) p.z = min(distance(at, u_light.xyz) / u_distance_range, 1.0);
#ifdef SHADOWREF_PCSS
  if (u_shadow == 4) return pcss(s.w, int(layer));
  if (u_shadow == 5) return vsm(s.w, int(layer));
#endif
  if (u_shadow == 1) return texture(u_shadow_map, vec4(p.xy, layer, p.z));
  if (u_shadow == 2 && u_random_taps > 0) {
    // PCF on a randomized kernel: the Vogel disk's taps out to u_random_pcf_radius texels.
    float rotation = pixel_rotation(), sum = 0.0;
    for (int i = 0; i < u_random_taps; ++i)
      sum += texture(u_shadow_map, vec4(p.xy + u_random_pcf_radius * vogel_tap(i, u_random_taps, rotation) * u_texel, layer, p.z));
    return sum / float(u_random_taps);
  }
  if (u_shadow == 2) {
    // PCF: a 3x3 box of depth compares one texel apart, equal weights (GL_NEAREST taps).
    float sum = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        sum += texture(u_shadow_map, vec4(p.xy + vec2(dx, dy) * u_texel, layer, p.z));
    return sum / 9.0;
  }
  // RGBA8: unpack the stored 24-bit depth and compare integers (exact, like a depth compare).
  uint stored = unpack_depth_rgba8(texture(u_packed_map, vec3(p.xy, layer)));
  uint here = quantize_depth(p.z);
  return (u_lit_greater == 1 ? here >= stored : here <= stored) ? 1.0 : 0.0;
}

void main() {
  // The face normal turned toward the camera (as the reference does), so one-sided planes work
  // from below.
  vec3 n = gl_FrontFacing ? v_normal : -v_normal;
  vec3 to_light = normalize(u_light.xyz - v_world * u_light.w);
  float n_dot_l = dot(n, to_light);
  if (u_mode == 0) {
    o_colour = vec4(u_albedo * u_ambient, 1.0);
    return;
  }
  float visibility = shadow_visibility();
  // A shadow map tests occlusion only; a surface that faces away from the light is in its own
  // shadow (what a stencil volume gives it, and the reference's ray finds). The mask mode without
  // a map (u_shadow 0) is that facing test alone: planar shadows' attached-shadow mask.
  // (PCSS and VSM test every light point they filter over themselves.)
  if ((u_shadow != 0 || u_mode == 2) && u_shadow < 4 && n_dot_l <= 0.0) visibility = 0.0;
  float lit = visibility >= 0.5 ? 1.0 : 0.0;  // PCF: lit when at least half the taps are
  if (u_mode == 2) {
    o_colour = vec4(lit, lit, lit, 1.0);
    return;
  }
  // The lit fraction itself (visibility.png, rounded to 8 bits by the target) and the mask decided
  // from the same unrounded fraction, beside the light's contribution: a filter's taps are paid once.
  o_mask = vec4(visibility, lit, 0.0, 1.0);
  float cone = 1.0;
  if (u_spot.w > -1.0) cone = dot(-to_light, u_spot.xyz) >= u_spot.w ? 1.0 : 0.0;
  o_colour = vec4(u_albedo * (u_light_intensity * max(n_dot_l, 0.0) * visibility * cone), 1.0);
}
)glsl";

}  // namespace shadowref::renderer::shaders
