// ray_stream.cpp — RayStream: one aligned block carved into the SoA arrays Embree's Np calls read.
#include "shadowref/reference/ray_stream.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>

namespace shadowref::reference {
namespace {
constexpr std::size_t kAlign = 64;
constexpr std::size_t kArrays = 20;  // 9 ray floats and 5 hit floats, 3 ray uints and 3 hit uints
std::size_t padded(std::size_t n) { return (n * 4 + kAlign - 1) / kAlign * kAlign; }
}  // namespace

void RayStream::Free::operator()(void* p) const { std::free(p); }

void RayStream::resize(std::size_t n) {
  if (n > capacity_) {
    // Grow by half again, so that a tile loop settles on its largest tile after a few resizes.
    const std::size_t cap = std::max(n, capacity_ + capacity_ / 2);
    const std::size_t bytes = padded(cap);
    auto* raw = static_cast<unsigned char*>(std::aligned_alloc(kAlign, kArrays * bytes));
    if (!raw) throw std::bad_alloc();
    std::unique_ptr<unsigned char, Free> block(raw);
    // Zeroed once, so that no field is ever read uninitialised (Embree leaves a miss's hit fields
    // alone, and hit_surfaces reads them before masking them out).
    std::memset(raw, 0, kArrays * bytes);
    // 14 float arrays, then 6 uint arrays, each `bytes` long.
    const auto floats = [&](std::size_t a) { return reinterpret_cast<float*>(raw + a * bytes); };
    const auto uints = [&](std::size_t a) { return reinterpret_cast<std::uint32_t*>(raw + (14 + a) * bytes); };
    float* const old[] = {org_x, org_y, org_z, tnear, dir_x, dir_y, dir_z, tfar};
    float* const now[] = {floats(0), floats(1), floats(2), floats(3), floats(4), floats(5), floats(6), floats(7)};
    for (std::size_t a = 0; a < 8; ++a)
      if (size_) std::memcpy(now[a], old[a], size_ * sizeof(float));
    org_x = now[0], org_y = now[1], org_z = now[2], tnear = now[3];
    dir_x = now[4], dir_y = now[5], dir_z = now[6], tfar = now[7];
    time_ = floats(8);
    ng_x = floats(9), ng_y = floats(10), ng_z = floats(11), u = floats(12), v = floats(13);
    mask_ = uints(0), id_ = uints(1), flags_ = uints(2), prim_id = uints(3), geom_id = uints(4), inst_id = uints(5);
    std::fill(time_, time_ + cap, 0.0f);
    std::fill(mask_, mask_ + cap, 0xFFFFFFFFu);
    std::fill(id_, id_ + cap, 0u);
    std::fill(flags_, flags_ + cap, 0u);
    std::fill(inst_id, inst_id + cap, RTC_INVALID_GEOMETRY_ID);
    block_ = std::move(block);
    capacity_ = cap;
  }
  size_ = n;
}

void RayStream::reset_hits() { std::fill(geom_id, geom_id + size_, RTC_INVALID_GEOMETRY_ID); }

RTCRayNp RayStream::rays() {
  RTCRayNp r;
  r.org_x = org_x, r.org_y = org_y, r.org_z = org_z, r.tnear = tnear;
  r.dir_x = dir_x, r.dir_y = dir_y, r.dir_z = dir_z, r.time = time_;
  r.tfar = tfar, r.mask = mask_, r.id = id_, r.flags = flags_;
  return r;
}

RTCRayHitNp RayStream::ray_hits() {
  RTCRayHitNp rh;
  rh.ray = rays();
  rh.hit.Ng_x = ng_x, rh.hit.Ng_y = ng_y, rh.hit.Ng_z = ng_z, rh.hit.u = u, rh.hit.v = v;
  rh.hit.primID = prim_id, rh.hit.geomID = geom_id;
  rh.hit.instID[0] = inst_id;
  return rh;
}

}  // namespace shadowref::reference
