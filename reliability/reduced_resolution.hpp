// reduced_resolution.hpp — shrinks a loaded scene's resolution so that its longer side is at most
// `max_side` pixels, keeping the aspect ratio (to rounding): the camera's aspect is taken from the
// resolution at render time, so the picture is the same framing with fewer pixels. Keeps the
// reliability tests fast on the whole catalogue.
#pragma once

#include <algorithm>

#include "shadowref/scene/scene.hpp"

namespace shadowref::reliability {

inline void reduce_resolution(scene::Scene& s, int max_side) {
  const int longer = std::max(s.width, s.height);
  if (longer <= max_side) return;
  s.width = std::max(1, s.width * max_side / longer);
  s.height = std::max(1, s.height * max_side / longer);
}

}  // namespace shadowref::reliability
