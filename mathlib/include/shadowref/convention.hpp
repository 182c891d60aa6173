// shadowref/convention.hpp — the depth conventions a whole run is rendered in, chosen in one place.
//
// A run convention fixes everything about depth that a renderer, the reference and an exported pack
// must agree on. The scene's world is always right-handed with y up (scene files are written so);
// a convention says how that world is seen:
//
//   name        view / projection           clip depth        depth buffer   depth test   clear
//   gl          RH look_at, RH perspective   −1..1 (near −1)   24-bit fixed   LESS         1
//   gl-zo       RH, glClipControl 0..1        0..1 (near 0)    24-bit fixed   LESS         1
//   reversed-z  RH, reversed 0..1             1..0 (near 1)    32-bit float   GREATER      0
//   d3d         LH look_at, LH perspective    0..1 (near 0)    24-bit fixed   LESS         1
//
// `d3d` is truly left-handed, not a transposed right-handed matrix: the right-handed world is first
// imported into a left-handed one by mirroring z (world_from_scene = diag(1, 1, −1, 1), what
// Direct3D exporters do), then seen through XMMatrixLookAtLH and XMMatrixPerspectiveFovLH. The two
// mirrors cancel on screen: every convention puts every scene point on the same pixel, and the
// same triangle keeps its screen-space winding, so the same scene gives the same masks.
// reversed-z keeps the scene's far plane when it has one and is infinite otherwise (as every
// convention is); with 32-bit float depth the precision it buys is near the far end.
//
// Everything a technique needs that depends on the convention is a function below: the depth test
// that means "nearer", the depth clear value, the shadow-map compare that means "lit", the sign of
// polygon offset, the bias matrix, the world mirror. No other file spells a convention constant.
// Canonical column-vector matrices throughout (conventions.hpp).
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "shadowref/conventions.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/result.hpp"
#include "shadowref/shadow_map.hpp"
#include "shadowref/view.hpp"

namespace shadowref {

struct RunConvention {
  std::string_view name;         // "gl", "gl-zo", "reversed-z", "d3d"
  ClipConvention clip;           // handedness, clip depth range, depth order
  bool float_depth = false;      // 32-bit float depth buffers (camera and shadow maps)
  bool mirror_world_z = false;   // the right-handed world is imported mirrored in z (left-handed engines)
  std::string_view summary;      // one line for --help and the pack
};

// clang-format off
inline constexpr std::array<RunConvention, 4> kRunConventions{{
    {"gl", {Handedness::Right, DepthRange::NegOneToOne, DepthOrder::Standard}, false, false,
     "OpenGL: right-handed view, clip depth -1..1, 24-bit depth, GL_LESS, cleared to 1 (the default)"},
    {"gl-zo", {Handedness::Right, DepthRange::ZeroToOne, DepthOrder::Standard}, false, false,
     "OpenGL with glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE): right-handed, clip depth 0..1"},
    {"reversed-z", {Handedness::Right, DepthRange::ZeroToOne, DepthOrder::Reversed}, true, false,
     "reversed-Z: right-handed, depth 1 at the near plane and 0 at infinity, 32-bit float depth, GL_GREATER, cleared to 0"},
    {"d3d", {Handedness::Left, DepthRange::ZeroToOne, DepthOrder::Standard}, false, true,
     "Direct3D: the world mirrored in z into a left-handed one, LH look-at and projection, clip depth 0..1"},
}};
// clang-format on

inline constexpr const RunConvention& kDefaultConvention = kRunConventions[0];

// The convention called `name`, or nullptr.
constexpr const RunConvention* find_run_convention(std::string_view name) {
  for (const RunConvention& c : kRunConventions)
    if (c.name == name) return &c;
  return nullptr;
}

// A depth comparison, named as the fragment's value against the stored one (a GL compare function).
enum class DepthCompare { Less, LessEqual, Greater, GreaterEqual, Equal, Always };

// The depth test that keeps the nearer fragment: LESS, or GREATER under reversed-Z.
constexpr DepthCompare nearer(const RunConvention& c) {
  return c.clip.order == DepthOrder::Reversed ? DepthCompare::Greater : DepthCompare::Less;
}
// The same, ties passing (a second pass over the very same surfaces, planar's receiver marking).
constexpr DepthCompare nearer_or_equal(const RunConvention& c) {
  return c.clip.order == DepthOrder::Reversed ? DepthCompare::GreaterEqual : DepthCompare::LessEqual;
}
// The window-space depth of the far plane (and of "nothing drawn"): the depth buffer's clear value.
constexpr double far_depth(const RunConvention& c) { return c.clip.order == DepthOrder::Reversed ? 0.0 : 1.0; }
// The window-space depth of the near plane.
constexpr double near_depth(const RunConvention& c) { return c.clip.order == DepthOrder::Reversed ? 1.0 : 0.0; }
// The clip-space (NDC) z of the near plane: −1 (−1..1), 0 (0..1) or 1 (reversed).
constexpr double near_ndc_z(const RunConvention& c) {
  if (c.clip.order == DepthOrder::Reversed) return 1.0;
  return c.clip.depth == DepthRange::NegOneToOne ? -1.0 : 0.0;
}
// The clip-space (NDC) z of the far plane: 1, or 0 under reversed-Z.
constexpr double far_ndc_z(const RunConvention& c) { return c.clip.order == DepthOrder::Reversed ? 0.0 : 1.0; }
// The shadow-map compare that means "lit": the receiver's depth in the light's map is not beyond
// the stored occluder depth. LEQUAL, or GEQUAL under reversed-Z.
constexpr DepthCompare lit_when(const RunConvention& c) {
  return c.clip.order == DepthOrder::Reversed ? DepthCompare::GreaterEqual : DepthCompare::LessEqual;
}
// Polygon offset pushes depth away from the light: +1, or −1 under reversed-Z (farther is smaller).
constexpr float polygon_offset_sign(const RunConvention& c) {
  return c.clip.order == DepthOrder::Reversed ? -1.0f : 1.0f;
}

// The matrix that takes scene (right-handed) coordinates into the convention's world: identity, or
// the z mirror diag(1, 1, −1, 1) for a left-handed engine.
template <class T>
Mat4<T> world_from_scene(const RunConvention& c) {
  Mat4<T> m = Mat4<T>::Identity();
  if (c.mirror_world_z) m(2, 2) = T(-1);
  return m;
}

// The bias matrix B of shadow_map.hpp for the convention's clip depth, texture origin bottom-left
// (OpenGL textures; a Direct3D engine flips v itself, see shadow_map.hpp's TextureOrigin).
// Reversed-Z needs nothing more: its depth already is the 0..1 value the texture stores.
template <class T>
Mat4<T> shadow_bias(const RunConvention& c) {
  return shadow_bias_matrix<T>(c.clip.depth);
}

// Scene → view space of a camera at `eye` looking at `target`: look_at in the convention's
// handedness applied to the convention's world, i.e. look_at(F eye, F target, F up) · F with
// F = world_from_scene. Errors: those of look_at.
template <class T>
Result<Mat4<T>> view_from_scene(const RunConvention& c, const Vec3<T>& eye, const Vec3<T>& target, const Vec3<T>& up) {
  if (!c.mirror_world_z) return look_at<T>(eye, target, up, c.clip.hand);
  const Mat4<T> f = world_from_scene<T>(c);
  const Mat3<T> f3 = f.template topLeftCorner<3, 3>();
  const Result<Mat4<T>> v = look_at<T>(f3 * eye, f3 * target, f3 * up, c.clip.hand);
  if (!v) return v.error();
  return Mat4<T>(*v * f);
}

// The convention's perspective from the vertical field of view (radians), finite when `far` is
// given, else infinite with Lengyel's `epsilon`. Errors: those of perspective / perspective_infinite.
template <class T>
Result<Mat4<T>> perspective_for(const RunConvention& c, T fovy, T aspect, T near, std::optional<T> far, T epsilon = T(0)) {
  if (far) return perspective<T>(fovy, aspect, near, *far, c.clip);
  return perspective_infinite<T>(fovy, aspect, near, c.clip, epsilon);
}

// The convention's orthographic projection of the view-space box (directional-light maps).
template <class T>
Result<Mat4<T>> ortho_for(const RunConvention& c, T l, T r, T b, T t, T near, T far) {
  return ortho<T>(l, r, b, t, near, far, c.clip);
}

}  // namespace shadowref
