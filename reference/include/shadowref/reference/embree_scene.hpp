// shadowref/reference/embree_scene.hpp — a Scene's meshes in an Embree BVH, plus the scale that
// every ray epsilon of the reference derives from.
//
// One Embree device and one scene per EmbreeScene (RAII). Built with RTC_SCENE_FLAG_ROBUST (no
// misses through shared edges, docs/dependencies.md) and high build quality; geometry IDs equal object
// indices, so a hit's geomID indexes Scene::objects.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <stdexcept>

#include "shadowref/scene/scene.hpp"

namespace shadowref::reference {

// Ray offsets are this fraction of the scene's extent (its bounding-box diagonal). Vertices are
// floats, so Embree's hit distances carry errors of a few ulps of the coordinates, about 1e-7 of
// the extent; 1e-5 is 100 times that and still far below any feature of the catalogue's scenes.
inline constexpr double kRelativeEpsilon = 1e-5;

// Embree refused (no device, a failed build): an internal failure, never the user's input.
class EmbreeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class EmbreeScene {
 public:
  // Uploads every object's mesh and commits the BVH (in the calling TBB arena). Throws
  // EmbreeError when Embree refuses (the message carries Embree's error code).
  explicit EmbreeScene(const scene::Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene handle() const { return scene_; }
  const scene::Scene& source() const { return *source_; }
  // The bounding-box diagonal (> 0; a flat or point-like scene gets 1 so that epsilons stay > 0).
  double extent() const { return extent_; }
  // The ray offset: extent() · kRelativeEpsilon.
  double epsilon() const { return extent_ * kRelativeEpsilon; }


 private:
  const scene::Scene* source_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  double extent_ = 1;
};

}  // namespace shadowref::reference
