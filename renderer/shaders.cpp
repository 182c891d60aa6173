// shaders.cpp — GLSL 3.30 core sources, as C++ raw strings so that the renderer is one binary, and
// the surface program assembled for each shadow-map lookup (its snippet lives with the lookup).
//
// The RGBA8 depth functions (quantize_depth, pack_depth_rgba8, unpack_depth_rgba8) mirror
// mathlib/include/shadowref/depth_packing.hpp operation for operation: one float multiply by
// 2^24 − 1, roundEven (= nearbyint under the default rounding mode), integer shifts. Change one,
// change both (depth_packing_test.cpp tests the C++ side).
#include "shaders.hpp"

#include <string>
#include <vector>

#include "shadow_maps/lookup.hpp"
#include "shadowref/renderer/faults.hpp"
#include "shadowref/scene/alpha_mask.hpp"

namespace shadowref::renderer::shaders {

const char* const kSceneVertex = R"glsl(#version 330 core
layout(location = 0) in vec4 a_position;   // world space; w = 0: a point at infinity
layout(location = 1) in vec3 a_normal;     // the face normal (objects; unused by volumes)
layout(location = 2) in vec4 a_alpha_test; // a masked object's u, v, threshold, vertex alpha (GpuMesh);
                                           // GL's default (0, 0, 0, 1) elsewhere: threshold 0, no test
layout(location = 3) in vec4 a_joints;     // a skinned object's four joint indices (GpuMesh)
layout(location = 4) in vec4 a_weights;    // and their weights
// The skinned object's joints at the pose, world_from_bind (scene/skin.hpp); u_skinned false for
// every other draw (the renderer's rigid block, bound between skinned draws): a_position as it is.
// A std140 bool is 4 bytes, as an int: the block's bytes hold 0 or 1 there (frame.hpp).
layout(std140) uniform Skin {
  mat4 u_joint_matrices[128];
  bool u_skinned;
};
uniform mat4 u_clip_from_world;            // P · V (· S for planar shadows)
uniform mat4 u_shadow_from_world;          // B · P_light · V_light (shadow maps), else anything
out vec3 v_world;
out vec4 v_shadow;
flat out vec3 v_normal;
out vec2 v_uv;
out float v_vertex_alpha;
flat out float v_alpha_threshold;
invariant gl_Position;
// glTF's linear blend skinning (glTF 2.0 §3.7.3): Σ weight_k · jointMatrix_k · p_bind, in world space.
vec4 posed_position() {
  if (!u_skinned) return a_position;
  return a_weights.x * (u_joint_matrices[int(a_joints.x)] * a_position) +
         a_weights.y * (u_joint_matrices[int(a_joints.y)] * a_position) +
         a_weights.z * (u_joint_matrices[int(a_joints.z)] * a_position) +
         a_weights.w * (u_joint_matrices[int(a_joints.w)] * a_position);
}
void main() {
  vec4 p = posed_position();
  gl_Position = u_clip_from_world * p;
  v_uv = a_alpha_test.xy;
  v_alpha_threshold = a_alpha_test.z;
  v_vertex_alpha = a_alpha_test.w;
  v_world = p.xyz;
  // Per vertex, interpolated perspective-correctly and divided per fragment: exact projective
  // texturing, the same as computing B · P · V · p per fragment.
  v_shadow = u_shadow_from_world * p;
  v_normal = a_normal;
}
)glsl";

const char* const kFlatFragment = R"glsl(
uniform vec4 u_colour;
out vec4 o_colour;
void main() {
  alpha_test();
  o_colour = u_colour;
}
)glsl";

// vsm's light pass (Donnelly & Lauritzen 2006): the first two moments of the fragment's depth plus
// the offset's constant done by hand as in the packed-depth pass (shadow_maps/vsm.cpp), as view
// depth along the light's axis: linear, so that averaging moments means something, and without the
// window depth's coarse float steps near 1. Built with SHADOWREF_DEPTH_BY_HAND (a float depth map),
// it also writes the map's depth with the whole offset by hand, as kOffsetDepthFragment.
const char* const kMomentsFragment = R"glsl(
uniform vec2 u_layer_inv_view_depth;  // 1 / view depth = x * window depth + y
uniform float u_offset_factor;        // glPolygonOffset's, with the convention's sign: the depth's only
uniform float u_offset_units;         // the depth's and the moments'
out vec4 o_moments;
void main() {
  alpha_test();
  float z = gl_FragCoord.z;
#ifdef SHADOWREF_DEPTH_BY_HAND
  float m = max(abs(dFdx(z)), abs(dFdy(z)));
  gl_FragDepth = clamp(z + u_offset_factor * m + u_offset_units / 16777216.0, 0.0, 1.0);
#endif
  z += u_offset_units / 16777215.0;
  float w = 1.0 / (u_layer_inv_view_depth.x * z + u_layer_inv_view_depth.y);
  o_moments = vec4(w, w * w, 0.0, 1.0);
}
)glsl";

// A float depth map's pass (reversed-Z's GL_DEPTH_COMPONENT32F): glPolygonOffset's unit on a float
// depth buffer is a step relative to the depth (the GL specification: 2^(e - 23), e the exponent of
// the primitive's largest depth), not the 24-bit step the lookups declare (lookup.hpp), and under
// reversed-Z depth falls toward 0 away from the light. Measured on level_cut's walls behind the
// arcade, 2.5 m from the lantern (window depth about 0.27), front faces stored: GL's 8 units left
// 256 px of self-shadowing where 4 steps of 2^-24 by hand leave 2 and 6 or 8 none, as in the 24-bit
// conventions. So the whole offset is written by hand, glPolygonOffset's model with the 24-bit step:
// factor * m + units * 2^-24, m the depth's largest change per texel.
const char* const kOffsetDepthFragment = R"glsl(
uniform float u_offset_factor;  // glPolygonOffset's, with the convention's sign
uniform float u_offset_units;
void main() {
  alpha_test();
  float z = gl_FragCoord.z;
  float m = max(abs(dFdx(z)), abs(dFdy(z)));
  gl_FragDepth = clamp(z + u_offset_factor * m + u_offset_units / 16777216.0, 0.0, 1.0);
}
)glsl";

// A distance cube's light pass (RenderOptions::cube_depth), as engines write point-light cubes
// (three.js MeshDistanceMaterial: (distance - near) / (far - near)): the distance from the light's
// centre over the range, written as the fragment's depth, so that the depth test keeps the nearest
// surface along each texel's ray (distance and the face's axis depth grow together along a ray). A
// polygon offset moves only the rasterised depth, not a written one, so its model is applied by hand
// as in the packed-depth pass: factor * m + units * 2^-24, m the distance's largest change per texel.
const char* const kDistanceFragment = R"glsl(
in vec3 v_world;
uniform vec3 u_light_position;
uniform float u_distance_range;
uniform float u_offset_factor;
uniform float u_offset_units;
void main() {
  alpha_test();
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
const char* const kDepthByHand = "#define SHADOWREF_DEPTH_BY_HAND\n";

const char* const kPackedDepthFragmentBody = R"glsl(
// glPolygonOffset done by hand (RGBA8 has no depth to offset): o = factor * m + units * r, with
// m = max(|dz/dx|, |dz/dy|) and r = 2^-24, the 24-bit step that the packing keeps.
uniform float u_offset_factor;
uniform float u_offset_units;
out vec4 o_colour;
void main() {
  alpha_test();
  float z = gl_FragCoord.z;
  float m = max(abs(dFdx(z)), abs(dFdy(z)));
  o_colour = pack_depth_rgba8(z + u_offset_factor * m + u_offset_units / kPackedDepthMax);
}
)glsl";

// Every surface program: the inputs, the light, the outputs.
const char* const kSurfaceInputs = R"glsl(
in vec3 v_world;
in vec4 v_shadow;
flat in vec3 v_normal;
uniform int u_mode;                  // SurfaceMode: kModeAmbient, kModeLight (and o_mask), kModeMask
uniform vec3 u_albedo;
uniform float u_ambient;
uniform vec4 u_light;                // homogeneous: w = 1 point / spot, w = 0 directional
uniform float u_light_intensity;
uniform vec4 u_spot;                 // xyz: the spot's axis (into the scene), w: cos(cone); w <= -1: no cone
layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_mask;    // kModeLight: the lit fraction (red) and the 0/1 mask (green)
)glsl";

// Every program with a map: where a world point lies in it (one view, a cube's faces, cascades),
// and the functions more than one lookup calls.
const char* const kMapCommon = R"glsl(
uniform vec2 u_texel;                // 1 / shadow-map size
uniform int u_layout;                // MapLayout: kLayoutSingle (one map through v_shadow), kLayoutCube
                                     // (a cube's six faces), kLayoutCascades (each picked per fragment,
                                     // mathlib's light_view_of)
uniform mat4 u_layer_from_world[6];  // B · P · V per layer: the faces +x, -x, +y, -y, +z, -z, or the cascades
uniform mat4 u_world_from_layer[6];  // their inverses
uniform vec2 u_inv_view_depth[6];    // per layer: 1 / (depth along the view axis) = x * window depth + y
uniform vec4 u_cascade_depth;        // the camera depth of a world point: dot(u_cascade_depth, (p, 1))
uniform vec4 u_cascade_begin;        // cascade i decides depths in [begin[i], end[i]) (up to 4 cascades)
uniform vec4 u_cascade_end;
uniform bool u_reversed;             // reversed-Z maps (near 1, far 0)
uniform bool u_lit_greater;          // a compare done in the shader: lit when here >= stored (GEQUAL),
                                     // else when here <= stored (LEQUAL); a depth texture has its own
uniform int u_random_taps;           // 0: each filter's fixed grid; N: N taps of a Vogel disk rotated per pixel
uniform float u_random_pcf_radius;   // PCF's disk radius in texels (shadow_maps/lookup.hpp, kRandomPcfRadiusTexels)
uniform float u_normal_offset_texels;  // the lookup moved along the normal by this many texels
uniform float u_distance_range;      // > 0: a cube holding distance / this range (kDistanceFragment), 0: window depth

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
)glsl";

// Every surface program: the light's visibility (1 without a map) and the pass's output.
const char* const kSurfaceMain = R"glsl(
// Light visibility from the shadow map: 1 lit, 0 shadowed (fractions when filtered).
float shadow_visibility() {
#ifndef SHADOWREF_MAP
  return 1.0;
#else
  vec4 s = v_shadow;
  float layer = 0.0;
  if (u_layout == kLayoutCascades) {
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
  if (u_layout == kLayoutCube) {
    // The face whose axis is the largest component of the direction from the light (that of a
    // cube-map lookup); each face's map reaches a few texels beyond 90 degrees, so the PCF taps
    // of a fragment on a face's edge stay in that face.
    int face = cube_face(v_world - u_light.xyz);
    s = u_layer_from_world[face] * vec4(v_world, 1.0);
    layer = float(face);
  }
  // A normal offset (RenderOptions::normal_offset_texels; the lookups that move by it): the point
  // looked up moves along the surface normal, turned toward the light, by that many of the map's
  // texels as wide as they are at the point (one texel along the map's x at the point's own depth).
  vec3 at = v_world;  // the point looked up
  if (kLookupNormalOffset && u_normal_offset_texels > 0.0) {
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
  p.z = u_reversed ? max(p.z, 0.0) : min(p.z, 1.0);
  // A distance cube: the looked-up point's own distance over the range, compared (GL_LEQUAL, in
  // every convention) with the nearest distance stored along the texel's ray.
  if (u_layout == kLayoutCube && u_distance_range > 0.0) p.z = min(distance(at, u_light.xyz) / u_distance_range, 1.0);
  return lookup_visibility(p, s, layer);
#endif
}

void main() {
  alpha_test();  // a masked object's holes show what lies behind them, in every camera pass
  // The face normal turned toward the camera (as the reference does), so one-sided planes work
  // from below.
  vec3 n = gl_FrontFacing ? v_normal : -v_normal;
  vec3 to_light = normalize(u_light.xyz - v_world * u_light.w);
  float n_dot_l = dot(n, to_light);
  if (u_mode == kModeAmbient) {
    o_colour = vec4(u_albedo * u_ambient, 1.0);
    return;
  }
  float visibility = shadow_visibility();
  // A shadow map tests occlusion only; a surface that faces away from the light is in its own
  // shadow (what a stencil volume gives it, and the reference's ray finds). The mask mode without
  // a map is that facing test alone: planar shadows' attached-shadow mask. (A lookup that tests
  // every light point it filters over, PCSS and VSM, has done it itself.)
  if ((kHasMap || u_mode == kModeMask) && !kLookupTestsLightPoints && n_dot_l <= 0.0) visibility = 0.0;
  float lit = visibility >= 0.5 ? 1.0 : 0.0;  // PCF: lit when at least half the taps are
  if (u_mode == kModeMask) {
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

// Every fragment shader's alpha test of masked objects: scene/alpha_mask.hpp's rule (its GLSL,
// alpha_rule_glsl(), joined before this), with the teeth's AlphaFault (faults.hpp) as a uniform that
// only a depth pass of a faulted render sets.
const char* const kAlphaTest = R"glsl(
in vec2 v_uv;
in float v_vertex_alpha;
flat in float v_alpha_threshold;
uniform usampler2D u_alpha_mask;     // R8UI, on kAlphaMaskUnit
uniform int u_alpha_fault;           // AlphaFault; kAlphaFaultNone in production
void alpha_test() {
  float threshold = v_alpha_threshold;
  if (threshold <= 0.0 || u_alpha_fault == kAlphaFaultIgnored) return;  // FAULT: solid quads
  if (u_alpha_fault == kAlphaFaultCutoffHalf) threshold = 127.5;       // FAULT: the cutoff taken as 0.5
  float a = u_alpha_fault == kAlphaFaultVertexAlphaIgnored ? 1.0 : v_vertex_alpha;  // FAULT: vertex alpha ignored
  ivec2 size = textureSize(u_alpha_mask, 0);
  uint a8 = texelFetch(u_alpha_mask, ivec2(alpha_texel(v_uv.x, size.x), alpha_texel(v_uv.y, size.y)), 0).r;
  if (!alpha_opaque(a8, a, threshold)) discard;
}
)glsl";

namespace {

std::string constant(const char* name, int value) {
  return "const int " + std::string(name) + " = " + std::to_string(value) + ";\n";
}
std::string flag(const char* name, bool value) {
  return "const bool " + std::string(name) + " = " + (value ? "true" : "false") + ";\n";
}

}  // namespace

std::string alpha_test(bool tested) {
  if (!tested) return "void alpha_test() {}\n";
  std::string out = constant("kAlphaFaultNone", static_cast<int>(AlphaFault::None));
  out += constant("kAlphaFaultIgnored", static_cast<int>(AlphaFault::Ignored));
  out += constant("kAlphaFaultCutoffHalf", static_cast<int>(AlphaFault::CutoffHalf));
  out += constant("kAlphaFaultVertexAlphaIgnored", static_cast<int>(AlphaFault::VertexAlphaIgnored));
  return out + scene::alpha_rule_glsl() + kAlphaTest;
}

std::vector<std::string> with_alpha_test(std::vector<std::string> fragment, bool tested) {
  fragment.insert(fragment.begin() + 1, alpha_test(tested));
  return fragment;
}

std::vector<std::string> surface_fragment(const MapLookup* lookup) {
  // The C++ enumerations the GLSL branches on, generated from their values here, not written twice.
  std::string header = kVersion;
  if (lookup) header += "#define SHADOWREF_MAP\n";
  header += constant("kModeAmbient", static_cast<int>(SurfaceMode::Ambient));
  header += constant("kModeLight", static_cast<int>(SurfaceMode::Light));
  header += constant("kModeMask", static_cast<int>(SurfaceMode::Mask));
  header += constant("kLayoutSingle", static_cast<int>(MapLayout::Single));
  header += constant("kLayoutCube", static_cast<int>(MapLayout::Cube));
  header += constant("kLayoutCascades", static_cast<int>(MapLayout::Cascades));
  header += flag("kHasMap", lookup != nullptr);
  header += flag("kLookupTestsLightPoints", lookup && lookup->tests_light_points);
  header += flag("kLookupNormalOffset", lookup && lookup->normal_offset);
  std::vector<std::string> sources{header};
  if (lookup && lookup->needs_depth_packing) sources.emplace_back(kDepthPacking);
  sources.emplace_back(kSurfaceInputs);
  if (lookup) {
    sources.emplace_back(kMapCommon);
    if (lookup->penumbra_search) sources.emplace_back(kPenumbraSearchGlsl);
    sources.emplace_back(lookup->glsl);
  }
  sources.emplace_back(kSurfaceMain);
  return sources;
}

}  // namespace shadowref::renderer::shaders
