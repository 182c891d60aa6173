// engines/common/attached_shadow.hpp — which faces the harness paints black itself.
//
// The contract counts a face turned away from the light as shadowed (its attached shadow). That is
// shading, not a cast shadow, and neither engine's shadow technique is meant to produce it (a stencil
// volume leaves it to the lighting; a shadow map with front faces culled compares such a face with
// itself). So the harness colours each face from its own normal, as the reference does: the normal
// turned toward the camera (surfaces are two-sided), and the face is shadowed when that normal does
// not point toward the light (n · to_light <= 0; the tie counts as shadowed, as in the reference).
// Everything else the mask shows — which lit-facing surfaces are darkened — is the engine's.
#pragma once

#include <array>

namespace engines {

using Point = std::array<double, 3>;

// True when triangle (a, b, c), seen from `camera`, faces away from the homogeneous light `light`
// (xyz a position when w = 1, a direction toward the light when w = 0). The test is exact per face:
// n · (L - p) is the same for every point p of the triangle's plane.
inline bool turned_away_from_light(const Point& a, const Point& b, const Point& c, const Point& camera,
                                   const std::array<double, 4>& light) {
  const Point e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const Point e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  Point n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double toward_camera = n[0] * (camera[0] - a[0]) + n[1] * (camera[1] - a[1]) + n[2] * (camera[2] - a[2]);
  if (toward_camera < 0) n = {-n[0], -n[1], -n[2]};
  const double w = light[3];
  const Point to_light{light[0] - a[0] * w, light[1] - a[1] * w, light[2] - a[2] * w};
  return !(n[0] * to_light[0] + n[1] * to_light[1] + n[2] * to_light[2] > 0);
}

}  // namespace engines
