// shadowref/shadow_map.hpp — the math of shadow mapping: the bias matrix B that maps the light's
// clip space to texture space, so that a world point p is compared through B · P_light · V_light · p.
//
// B maps NDC x, y from [−1, 1] to texture [0, 1] and depth to the value the depth texture stores
// ([0, 1] in both APIs once the viewport transform has run):
//   NegOneToOne: x, y, z → 0.5 v + 0.5           (OpenGL: the classic "bias matrix")
//   ZeroToOne:   x, y → 0.5 v + 0.5, z unchanged  (Direct3D / Vulkan depth is already 0..1)
// TextureOrigin::TopLeft flips v (t = 0.5 − 0.5 y), for APIs whose texture row 0 is the top row
// (Direct3D); OpenGL's texture origin is BottomLeft. Canonical column-vector form; no failure mode.
#pragma once

#include "shadowref/conventions.hpp"

namespace shadowref {

enum class TextureOrigin { BottomLeft, TopLeft };

template <class T>
Mat4<T> shadow_bias_matrix(DepthRange depth, TextureOrigin origin = TextureOrigin::BottomLeft) {
  Mat4<T> b = Mat4<T>::Identity();
  const T half(0.5);
  b(0, 0) = half;
  b(0, 3) = half;
  b(1, 1) = origin == TextureOrigin::BottomLeft ? half : -half;
  b(1, 3) = half;
  if (depth == DepthRange::NegOneToOne) {
    b(2, 2) = half;
    b(2, 3) = half;
  }
  return b;
}

}  // namespace shadowref
