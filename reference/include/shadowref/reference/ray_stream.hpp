// shadowref/reference/ray_stream.hpp — a stream of rays (and their hits) in structure-of-arrays
// layout, as Embree's rtcIntersectNp / rtcOccludedNp take it.
//
// Why SoA: the reference builds its rays 8 (AVX2) or 4 (SSE) at a time in plain loops over these
// arrays (camera_rays.hpp, shadow_ray.hpp), and Embree's Np interface loads its packets straight
// from them, where the array-of-structures RTCRayHit stream (rtcIntersect1M) cost a scalar store
// per field on our side and a transposition on Embree's.
//
// resize() keeps the fields no ray ever varies (time 0, mask all ones, id 0, flags 0) filled, so
// that a builder writes only origin, direction, tnear and tfar; hits need geomID reset before each
// intersect (reset_hits()). Every array is 64-byte aligned (Embree asks for 16).
#pragma once

#include <embree3/rtcore.h>

#include <cstddef>
#include <cstdint>
#include <memory>

namespace shadowref::reference {

class RayStream {
 public:
  RayStream() = default;
  RayStream(const RayStream&) = delete;
  RayStream& operator=(const RayStream&) = delete;
  RayStream(RayStream&&) = default;
  RayStream& operator=(RayStream&&) = default;

  // `n` rays; grows the arrays when needed (never shrinks them). The ray fields of rays that were
  // already there are kept; new ones are unset (origin, direction, tnear, tfar).
  void resize(std::size_t n);
  std::size_t size() const { return size_; }

  // Every hit's geomID set to RTC_INVALID_GEOMETRY_ID (before rtcIntersectNp).
  void reset_hits();

  // Inactive in Embree's sense (tnear > tfar: never traced, tfar kept). `lit` chooses what the
  // ray's answer reads as afterwards (lit(i): tfar >= 0): a shadow ray decided without tracing.
  void set_inactive(std::size_t i, bool lit) {
    tnear[i] = kInactiveNear;
    tfar[i] = lit ? 0.0f : -kInactiveNear;
  }
  // An occlusion ray's answer after rtcOccludedNp: Embree sets tfar to −inf on a hit.
  bool lit(std::size_t i) const { return !(tfar[i] < 0); }

  RTCRayNp rays();
  RTCRayHitNp ray_hits();

  // The arrays (size() elements each).
  float *org_x = nullptr, *org_y = nullptr, *org_z = nullptr, *tnear = nullptr;
  float *dir_x = nullptr, *dir_y = nullptr, *dir_z = nullptr, *tfar = nullptr;
  float *ng_x = nullptr, *ng_y = nullptr, *ng_z = nullptr, *u = nullptr, *v = nullptr;
  std::uint32_t *prim_id = nullptr, *geom_id = nullptr, *inst_id = nullptr;

  static constexpr float kInactiveNear = 3.0e38f;

 private:
  struct Free {
    void operator()(void* p) const;
  };
  std::unique_ptr<unsigned char, Free> block_;
  float *time_ = nullptr;
  std::uint32_t *mask_ = nullptr, *id_ = nullptr, *flags_ = nullptr;
  std::size_t size_ = 0, capacity_ = 0;
};

}  // namespace shadowref::reference
