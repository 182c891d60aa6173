// shadowref/scene/camera.hpp — the camera's view and projection matrices, from mathlib only.
//
// The one place that turns a scene camera into matrices: the reference renderer and the OpenGL
// renderer both call these, so each pixel sees the same surface in both (DESIGN.md "Images").
// Convention: OpenGL (right-handed view looking down −z, clip depth −1..1, canonical column
// vectors). The projection is perspective_infinite unless the camera has a `far`; `epsilon` is
// Lengyel's tweak for the infinite far plane (ignored with a finite far), 0 by default — x and y
// of clip space do not depend on it, so the pixel → surface mapping is the same for any epsilon.
//
// Pixel (x, y) of a W × H image (row 0 at the top) has its centre at
//   ndc.x = 2 (x + 0.5) / W − 1,   ndc.y = 1 − 2 (y + 0.5) / H.
//
// Errors: whatever look_at / perspective report (the loader has already refused such cameras,
// so for a loaded scene these always succeed).
#pragma once

#include <numbers>

#include "shadowref/projection.hpp"
#include "shadowref/result.hpp"
#include "shadowref/scene/scene.hpp"
#include "shadowref/view.hpp"

namespace shadowref::scene {

// World → view space: look_at(position, target, up), right-handed.
template <class T>
Result<Mat4<T>> view_matrix(const Camera& camera) {
  return look_at<T>(camera.position.cast<T>(), camera.target.cast<T>(), camera.up.cast<T>(),
                    Handedness::Right);
}

// View → clip space for a width × height image, OpenGL convention (RH, −1..1).
template <class T>
Result<Mat4<T>> projection_matrix(const Camera& camera, int width, int height, T epsilon = T(0)) {
  const T fovy = static_cast<T>(camera.fovy_deg * std::numbers::pi / 180.0);
  const T aspect = static_cast<T>(width) / static_cast<T>(height);
  if (camera.far) {
    return perspective<T>(fovy, aspect, static_cast<T>(camera.near), static_cast<T>(*camera.far), kOpenGL);
  }
  return perspective_infinite<T>(fovy, aspect, static_cast<T>(camera.near), kOpenGL, epsilon);
}

// The normalised device coordinates (x, y) of pixel (px, py)'s sample at sub-pixel offset
// (sx, sy) in [0, 1)²; (0.5, 0.5) is the pixel centre.
template <class T>
Vec2<T> pixel_to_ndc(int px, int py, T sx, T sy, int width, int height) {
  return Vec2<T>(T(2) * (static_cast<T>(px) + sx) / static_cast<T>(width) - T(1),
                 T(1) - T(2) * (static_cast<T>(py) + sy) / static_cast<T>(height));
}

}  // namespace shadowref::scene
