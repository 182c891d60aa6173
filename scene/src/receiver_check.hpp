// receiver_check.hpp (private) — the receiver's planarity, checked alike for JSON and glTF scenes.
#pragma once

#include <algorithm>
#include <cmath>

#include "shadowref/scene/scene.hpp"

namespace shadowref::scene::detail {

// Planar shadows need a plane: true when the scene has no receiver, or when every vertex of its
// receiver lies within rounding of the receiver's plane (its first triangle's).
inline bool receiver_is_planar(const Scene& scene) {
  const auto index = scene.receiver_index();
  if (!index) return true;
  const auto plane = receiver_plane(scene);
  if (!plane) return false;
  const auto b = bounds(scene);
  const double tolerance = 1e-5 * std::max(1.0, (b[1] - b[0]).norm());  // float positions: ~1e-7 relative, with margin
  for (const auto& p : scene.objects[*index].mesh.positions)
    if (!(std::abs(signed_distance(*plane, Vec3<double>(p.cast<double>()))) <= tolerance)) return false;
  return true;
}

}  // namespace shadowref::scene::detail
