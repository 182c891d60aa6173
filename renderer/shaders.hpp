// shaders.hpp — the GLSL 3.30 sources of every renderer pass (defined in shaders.cpp).
#pragma once

#include <string>
#include <vector>

namespace shadowref::renderer {
struct MapLookup;
}

namespace shadowref::renderer::shaders {

// Every scene pass: world-space homogeneous position in (w = 0 for points at infinity),
// `u_clip_from_world` out, `invariant` so that shadow-volume caps and the surfaces they lie on
// get bit-identical depths (the depth-pass / depth-fail tests rely on it). A skinned object's
// vertices are the bind pose, posed by the `Skin` uniform block's joint matrices (GpuMesh).
extern const char* const kSceneVertex;
// The joints kSceneVertex's `Skin` block holds (scene::kMaxSkinJoints, checked in renderer.cpp).
inline constexpr int kSceneVertexJoints = 128;
// Every fragment shader below is joined after kVersion and alpha_test() (with_alpha_test) and calls
// alpha_test() first.
// A constant colour (depth pre-pass, stencil passes with colour writes off, planar black).
extern const char* const kFlatFragment;
// The packed-depth pass is three strings for glShaderSource: kVersion, kDepthPacking, its body.
extern const char* const kVersion;
// quantize_depth, pack_depth_rgba8, unpack_depth_rgba8: mirror of mathlib/depth_packing.hpp.
extern const char* const kDepthPacking;
// vsm's light pass: the fragment's depth along the light's view axis and its square (RG32F); with
// kDepthByHand before it, the map's depth too, offset by hand.
extern const char* const kMomentsFragment;
// A float depth map's light pass: gl_FragDepth = the window depth plus glPolygonOffset's model done
// by hand with the 24-bit step the lookups declare (GL's own unit is relative on a float buffer).
extern const char* const kOffsetDepthFragment;
// The line that makes kMomentsFragment write the offset depth by hand.
extern const char* const kDepthByHand;
// A distance cube's light pass (RenderOptions::cube_depth): gl_FragDepth = the distance from the
// light over its range, plus glPolygonOffset's model done by hand.
extern const char* const kDistanceFragment;
// The depth of the light's view, packed into RGBA8.
extern const char* const kPackedDepthFragmentBody;

// Every fragment shader's alpha test, after its version line (with_alpha_test joins it). Tested:
// the AlphaFault constants, scene/alpha_mask.hpp's rule in GLSL and alpha_test(), which discards a
// masked object's fragment below its cutoff (the teeth's u_alpha_fault aside). Not tested: an empty
// alpha_test(), so that the program has no discard at all — a rasteriser tests depth before shading
// only in a shader that cannot discard (llvmpipe decides it from the shader's text), and unmasked
// objects, nearly all of them, keep that early test.
std::string alpha_test(bool tested);
// A fragment shader's strings with alpha_test(tested) inserted after the first (the version line, or
// the surface program's generated header).
std::vector<std::string> with_alpha_test(std::vector<std::string> fragment, bool tested);

// The surface program's fragment shader, as glShaderSource's strings: kVersion and the constants of
// the C++ enumerations it branches on (SurfaceMode, MapLayout, the lookup's flags), the inputs, and
// for a shadow-map lookup the maps' shared uniforms and functions and the lookup's own snippet
// (shadow_maps/lookup.hpp), then the visibility and the pass's outputs. Null: no map (the ambient
// pass, attached-shadow masks, the exact techniques' light passes).
std::vector<std::string> surface_fragment(const MapLookup* lookup);

}  // namespace shadowref::renderer::shaders
