// shadowref/renderer/faults.hpp — fault switches: bugs that engines have shipped, built into the
// real techniques so that the conformance suite can show it catches them (its "teeth",
// conformance/tests/teeth_table.cpp). Each switch is one `if` in the technique's own code, where
// the bug would be; everything else a faulty render does is the production code. All switches
// off (a default-constructed Faults) is the production renderer, and nothing but the suite's
// tests turns one on (the `shadowref` command has no way to).
//
// One small struct per technique family; a switch of another family is ignored (a planar render
// never reads VolumeFaults). CameraFaults apply to every technique.
#pragma once

#include <string>

namespace shadowref::renderer {

// The camera every technique renders through (Frame::camera_clip_double).
struct CameraFaults {
  // The image shifted by half a pixel right and down: Direct3D 9's pixel centres (at integer
  // coordinates) assumed by an API whose centres are at +0.5 (OpenGL, Direct3D 10 and later).
  bool half_pixel_offset = false;
};

// planar.cpp
struct PlanarFaults {
  // The shadow matrix transposed: D3DXMatrixShadow's row-vector layout (docs/conventions.md) used
  // as a column-vector matrix.
  bool matrix_transposed = false;
  // A directional light (w = 0) projected as a point light at its direction vector (w taken as 1).
  bool directional_as_point = false;
  // No once-per-pixel stencil rule: every projected fragment on the receiver blends, so where the
  // projection overlaps itself (any closed caster: its near and far sides) the shadow is darkened
  // twice. The stencil then counts the fragments, and the mask — "darkened exactly once" — loses
  // every pixel darkened more than once.
  bool darken_every_fragment = false;
};

// stencil_volumes.cpp
struct VolumeFaults {
  // Depth-fail counting without the light and dark caps (open volumes).
  bool no_caps = false;
  // volume-robust: the near-plane clip-volume test skipped, z-pass everywhere (the eye may be inside
  // a volume, where depth-pass counts start from the wrong value).
  bool robust_always_zpass = false;
  // Faces classified as lit with the point light's position used as a direction, plane · (x, y, z, 0)
  // instead of plane · (x, y, z, 1), while the volume is still extruded from the point: Irrlicht 1.8's
  // CShadowVolumeSceneNode passes the light position to isFrontFacing, which expects a direction.
  bool light_position_as_direction = false;
  // GL_INCR / GL_DECR (saturating at 0 and 255) instead of GL_INCR_WRAP / GL_DECR_WRAP: right in two
  // passes (every increment first), wrong with two-sided stencil, where a decrement may come first.
  bool saturating_stencil = false;
  // Casters whose bounding sphere lies outside the camera's frustum are culled from the volume pass,
  // as from the camera pass: a caster out of view casts no shadow into it.
  bool cull_casters_outside_view = false;
};

// The shadow-map compare (lit when the fragment's depth is not beyond the stored one).
enum class CompareFault {
  None,
  Reversed,           // the opposite of the convention's compare: lit and shadowed swap
  ConventionIgnored,  // GL_LEQUAL whatever the convention: under reversed-Z, not flipped to GL_GEQUAL
};

// Where each light view's depth range ends (mathlib/light_fit.hpp fits it to every vertex).
enum class FitFault {
  None,
  NearTooTight,  // the near plane moved to the middle of the range: casters near the light are clipped
  FarTooTight,   // the far plane moved to the middle of the range: casters far from the light are clipped
};

// A point light's cube of six maps.
enum class CubeFault {
  None,
  ZFacesSwapped,     // +z and −z exchanged when sampling: a left-handed cube's face order in a right-handed world
  YFacesUpsideDown,  // the ±y faces sampled rotated by 180 degrees: their up vector taken wrong in the face table
};

// How a depth pass treats a masked caster (scene/alpha_mask.hpp; the GLSL's alpha_test, shaders.cpp).
enum class AlphaFault {
  None,
  Ignored,             // no alpha test: every masked card casts its whole quad (three.js before r132)
  CutoffHalf,          // the scene's cutoff replaced by 0.5 (an engine's fixed alpha-scissor threshold)
  VertexAlphaIgnored,  // the texture's alpha alone, the vertex alpha taken as 1 (PlayCanvas #5115)
};

// shadow_maps/light_map.cpp
struct ShadowMapFaults {
  // The alpha test in the depth pass (every lookup, every layout), not in the camera's passes.
  AlphaFault alpha = AlphaFault::None;
  // Open casters (a single-sided card, a leaf) drawn with front faces culled, as closed ones: a card
  // whose front faces the light casts nothing.
  bool cull_open_front_faces = false;
  CompareFault compare = CompareFault::None;
  // The map (depth, and the packed colour of shadowmap-rgba8) cleared to 1 whatever the convention:
  // under reversed-Z, 1 is the near plane, so nothing is ever drawn into it.
  bool clear_to_one = false;
  // Polygon offset with the +1 sign whatever the convention: under reversed-Z it pulls depth toward
  // the light instead of pushing it away.
  bool offset_sign_ignored = false;
  // The camera fragment mapped through P_light · V_light without the bias matrix B: clip −1..1 read
  // as texture coordinates.
  bool no_bias_matrix = false;
  // The −1..1 bias matrix (z → 0.5 z + 0.5) applied to 0..1 clip depth (Direct3D, Vulkan, gl-zo, reversed-Z).
  bool neg_one_to_one_bias = false;
  // No polygon offset at all (factor 0, units 0): shadow acne where a surface compares against itself.
  bool no_polygon_offset = false;
  // A constant offset far larger than needed (kPeterPanUnits): peter-panning, shadows detached from
  // their casters at the contact.
  bool large_constant_offset = false;
  // A constant offset of this many world units along the light's view axis (0: off), for
  // directional lights in a fixed-point depth convention: a measured peter-panning, declared as
  // candidate.json's constant_bias.
  double constant_offset_world = 0.0;
  // Casters whose bounding sphere lies outside the camera's frustum left out of the depth pass.
  bool cull_casters_outside_view = false;
  // Skinned casters drawn into the map in their bind pose (the skin not applied in the depth pass's
  // vertex shader), while the camera's passes draw them posed: the shadow of the bind pose.
  bool skin_bind_pose = false;
  FitFault fit = FitFault::None;
  CubeFault cube = CubeFault::None;
  // Half a texel added to the map coordinates (Direct3D 9's texel-centre correction where none
  // belongs): the whole map sampled half a texel off.
  bool half_texel_offset = false;
  // The map's t read as 1 − t: a texture drawn with OpenGL's bottom-left origin looked up as if its
  // origin were the top left (WebGPU, Direct3D, Vulkan), or a WebGPU backend's y flip of the shadow
  // coordinate applied where the map was not flipped. Every shadow mirrored in the light's view.
  bool lookup_y_flipped = false;
  // A directional light's view fitted to its direction mirrored in x (its map drawn and looked up
  // from there; the camera's lighting keeps the true direction): shadows fall the mirrored way, as
  // WebGPU backends that take a light direction's x with the other sign draw them. Not cascaded.
  bool light_direction_mirrored_x = false;
};

// Cascaded shadow maps (csm, csm-pcf; mathlib/cascades.hpp), directional lights only.
struct CascadeFaults {
  // Each cascade but the last selected only up to kCascadeGapFraction of its slice (the split the
  // selection uses and the one the fit uses disagree): depths in between fall in no cascade and
  // come out lit.
  bool gap = false;
  // Each cascade's depth range fitted to its slice's bounding sphere alone: a caster between the
  // light and the slice that lies outside the sphere (a tree behind the camera, a cliff far to the
  // side) is clipped from that cascade, and its shadow goes missing there.
  bool slice_depth_range = false;
  // The windows not snapped to whole texels: every camera move shifts the texel grid over the
  // world, and static shadow edges crawl (shimmer). Right in any one frame.
  bool no_snapping = false;
  // The cascades fitted to the frustum behind the camera: its corners built with the other
  // handedness's viewing axis (+z for −z), while the selection still uses the true view depth.
  // Every window then holds the slice behind the eye; what the camera sees falls outside them
  // (lit), except near the eye, where the first cascade's sphere reaches in front of it.
  bool frustum_behind_camera = false;
};

// CascadeFaults::gap: the part of each slice its cascade is selected for.
inline constexpr double kCascadeGapFraction = 0.85;

// Percentage-closer soft shadows (pcss) and vsm over its penumbra, rect lights only.
struct SoftShadowFaults {
  // The blocker search averages the receiver's own depth instead of the blockers' (the search
  // compares nothing, or reads the wrong value): the penumbra estimate (d_receiver - d_blocker) /
  // d_blocker is 0 everywhere, and every soft shadow comes out hard.
  bool blocker_depth_from_receiver = false;
  // The light size the penumbra is estimated with, as a multiple of the true one (1: right): a
  // light's half-size used for its size, or a unit mix-up.
  double light_size_scale = 1.0;
  // A cube map's filter taps read only the fragment's own face: a tap across the face's edge falls
  // outside its map and reads as unblocked, so a penumbra that straddles a seam leaks light along it.
  bool taps_stay_in_face = false;
  // The textbook blocker search (Fernando 2005): every surface the map holds nearer than the
  // receiver's plane across the near plane's slice of the pyramid from the receiver to the rect
  // counts, at its depth, though along the light centre's rays that slice takes in a cone far
  // wider than the pyramid at the blocker's depth. A wall or column beside a long shadow then
  // pulls the blockers' mean depth towards the receiver, and the penumbra comes out too hard.
  bool search_whole_cone = false;
};

struct Faults {
  CameraFaults camera;
  PlanarFaults planar;
  VolumeFaults volume;
  ShadowMapFaults shadow_map;
  CascadeFaults cascade;
  SoftShadowFaults soft;
};

// The switches that are on, as "family.switch[=value]" joined by ", "; "" for production.
std::string describe(const Faults& faults);

}  // namespace shadowref::renderer
