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
uniform int u_mode;                  // 0 ambient, 1 one light's contribution, 2 the 0/1 mask
uniform int u_shadow;                // 0 none, 1 depth compare, 2 PCF 3x3, 3 RGBA8 packed depth
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
out vec4 o_colour;

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
    vec3 d = v_world - u_light.xyz;
    vec3 a = abs(d);
    int face = (a.x >= a.y && a.x >= a.z) ? (d.x >= 0.0 ? 0 : 1)
             : (a.y >= a.z)               ? (d.y >= 0.0 ? 2 : 3)
                                          : (d.z >= 0.0 ? 4 : 5);
    s = u_layer_from_world[face] * vec4(v_world, 1.0);
    layer = float(face);
  }
  // Behind the light's centre of projection: outside the map, which knows of no occluder there
  // (only a spot's or directional light's single map has such points; a cube has none).
  if (s.w <= 0.0) return 1.0;
  vec3 p = s.xyz / s.w;                // = textureProj's divide
  if (any(lessThan(p.xy, vec2(0.0))) || any(greaterThan(p.xy, vec2(1.0)))) return 1.0;
  // Beyond the light's far plane: compare as at the far plane, where nothing occludes.
  p.z = u_reversed == 1 ? max(p.z, 0.0) : min(p.z, 1.0);
  if (u_shadow == 1) return texture(u_shadow_map, vec4(p.xy, layer, p.z));
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
  if ((u_shadow != 0 || u_mode == 2) && n_dot_l <= 0.0) visibility = 0.0;
  if (u_mode == 2) {
    float lit = visibility >= 0.5 ? 1.0 : 0.0;  // PCF: lit when at least half the taps are
    o_colour = vec4(lit, lit, lit, 1.0);
    return;
  }
  float cone = 1.0;
  if (u_spot.w > -1.0) cone = dot(-to_light, u_spot.xyz) >= u_spot.w ? 1.0 : 0.0;
  o_colour = vec4(u_albedo * (u_light_intensity * max(n_dot_l, 0.0) * visibility * cone), 1.0);
}
)glsl";

}  // namespace shadowref::renderer::shaders
