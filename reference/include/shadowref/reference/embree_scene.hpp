// shadowref/reference/embree_scene.hpp — a Scene's meshes in an Embree BVH, plus the scale that
// every ray epsilon of the reference derives from.
//
// One Embree device and one scene per EmbreeScene (RAII). Built with RTC_SCENE_FLAG_ROBUST (no
// misses through shared edges, docs/dependencies.md) and high build quality; geometry IDs equal object
// indices, so a hit's geomID indexes Scene::objects.
#pragma once

#include <embree3/rtcore.h>

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

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

// Embree's names for its CPU kernels (rtcNewDevice's `isa=`), in Debian's build: "sse2", "sse4.2",
// "avx2", "avx512" (its Skylake kernel: AVX-512 F, BW, DQ and VL).
inline constexpr std::array<const char*, 4> kEmbreeKernels{"sse2", "sse4.2", "avx2", "avx512"};

// Whether this CPU can run Embree's kernel `name` (one of kEmbreeKernels; false for any other).
// One process runs one kernel: Embree selects part of its code once per process, so devices of two
// kernels in one process mix their code (assertions and crashes inside Embree).
bool cpu_runs_embree_kernel(std::string_view name);

class EmbreeScene {
 public:
  // Uploads every object's mesh and commits the BVH (in the calling TBB arena). Throws
  // EmbreeError when Embree refuses (the message carries Embree's error code). `device_config` is
  // Embree's device configuration string (rtcNewDevice): empty lets Embree pick its kernel for the
  // CPU, the production default; "isa=avx2" and the like force one (`goldens --check --embree-kernel`
  // renders with each and demands the same truth, reference/truth.hpp).
  explicit EmbreeScene(const scene::Scene& scene, const std::string& device_config = {});
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
  // The scene, its geometries and its BVH, into device_ (the constructor releases both if it throws).
  void build(const scene::Scene& scene);
  const scene::Scene* source_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  double extent_ = 1;
};

}  // namespace shadowref::reference
