// shadowref/scene/camera.hpp — a scene camera's view and projection matrices in a run convention,
// from mathlib only: the one place a scene camera becomes matrices.
//
// The reference and the OpenGL renderer both get their camera through the prepared scene, which
// calls these, so each pixel sees the same surface in both. The convention (convention.hpp: gl,
// gl-zo, reversed-z, d3d) decides handedness, clip depth and the d3d world mirror; x and y of clip
// space, hence the pixel → surface mapping, are the same in every convention. The projection is
// infinite unless the camera has a `far`; `epsilon` is Lengyel's tweak for the infinite far plane
// (ignored with a finite far).
//
// Pixel (x, y) of a W × H image (row 0 at the top) has its centre at
//   ndc.x = 2 (x + 0.5) / W − 1,   ndc.y = 1 − 2 (y + 0.5) / H.
//
// Errors: whatever look_at / perspective report (the loader has already refused such cameras,
// so for a loaded scene these always succeed).
#pragma once

#include <numbers>
#include <optional>

#include "shadowref/convention.hpp"
#include "shadowref/result.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::scene {

// Scene → view space: look_at(position, target, up) in the convention (view_from_scene).
template <class T>
Result<Mat4<T>> view_matrix(const Camera& camera, const RunConvention& conv = kDefaultConvention) {
  return view_from_scene<T>(conv, camera.position.cast<T>(), camera.target.cast<T>(), camera.up.cast<T>());
}

// View → clip space for a width × height image: vertical field of view fovy_deg, aspect
// width / height, near, and `far` (the camera's own when absent; still absent: infinite).
template <class T>
Result<Mat4<T>> projection_matrix(const Camera& camera, int width, int height,
                                  const RunConvention& conv = kDefaultConvention, T epsilon = T(0),
                                  std::optional<double> far_override = std::nullopt) {
  const T fovy = static_cast<T>(camera.fovy_deg * std::numbers::pi / 180.0);
  const T aspect = static_cast<T>(width) / static_cast<T>(height);
  const std::optional<double> far = far_override ? far_override : camera.far;
  return perspective_for<T>(conv, fovy, aspect, static_cast<T>(camera.near),
                            far ? std::optional<T>(static_cast<T>(*far)) : std::nullopt, epsilon);
}

// The normalised device coordinates (x, y) of pixel (px, py)'s sample at sub-pixel offset
// (sx, sy) in [0, 1)²; (0.5, 0.5) is the pixel centre.
template <class T>
Vec2<T> pixel_to_ndc(int px, int py, T sx, T sy, int width, int height) {
  return Vec2<T>(T(2) * (static_cast<T>(px) + sx) / static_cast<T>(width) - T(1),
                 T(1) - T(2) * (static_cast<T>(py) + sy) / static_cast<T>(height));
}

}  // namespace shadowref::scene
