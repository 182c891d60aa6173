// shaders.hpp — the GLSL 3.30 sources of every renderer pass (defined in shaders.cpp).
#pragma once

namespace shadowref::renderer::shaders {

// Every scene pass: world-space homogeneous position in (w = 0 for points at infinity),
// `u_clip_from_world` out, `invariant` so that shadow-volume caps and the surfaces they lie on
// get bit-identical depths (the depth-pass / depth-fail tests rely on it).
extern const char* const kSceneVertex;
// A constant colour (depth pre-pass, stencil passes with colour writes off, planar black).
extern const char* const kFlatFragment;
// The two shaders below are three strings for glShaderSource: kVersion, kDepthPacking, body.
extern const char* const kVersion;
// quantize_depth, pack_depth_rgba8, unpack_depth_rgba8: mirror of mathlib/depth_packing.hpp.
extern const char* const kDepthPacking;
// Put between kVersion and kDepthPacking, compiles PCSS and VSM into the surface shader (u_shadow 4
// and 5). Only
// the soft program has it: llvmpipe does not specialise on uniforms, so PCSS's code in the shared
// shader cost every shadow-map frame about 15 % (renderer_bench, ground_sphere 512²: 98 → 115 ms).
extern const char* const kPcssDefine;
// Lambert surface: ambient, one light's contribution (optionally shadow-mapped), or a 0/1 mask.
extern const char* const kSurfaceFragmentBody;
// vsm's light pass: the fragment's depth along the light's view axis and its square (RG32F).
extern const char* const kMomentsFragment;
// A distance cube's light pass (RenderOptions::cube_depth): gl_FragDepth = the distance from the
// light over its range, plus glPolygonOffset's model done by hand.
extern const char* const kDistanceFragment;
// The depth of the light's view, packed into RGBA8.
extern const char* const kPackedDepthFragmentBody;

}  // namespace shadowref::renderer::shaders
