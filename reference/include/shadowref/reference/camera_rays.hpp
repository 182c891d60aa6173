// shadowref/reference/camera_rays.hpp — the reference's camera rays, defined in float so that
// they are built 8 (AVX2) or 4 (SSE) at a time, bit for bit the same whatever the batch, the
// thread, the tile order or the vector width.
//
// The ray of image point (u, v), in pixel units (pixel (x, y) covers [x, x + 1) × [y, y + 1), row
// 0 at the top; its centre is (x + 0.5, y + 0.5)), in the prepared scene's camera and run
// convention (pixel_surface.hpp says why it leaves the near plane and where it ends). With
// C = inverse(P · V) of the prepared camera, the unprojected near-plane point
// h = C · (ndc_x, ndc_y, z_near, 1) is affine in (u, v) because the NDC are (scene::pixel_to_ndc):
// h = H0 + u·Hu + v·Hv. Moving along the pixel in clip depth by δ = z_mid − z_near (z_mid halfway
// to the far plane) moves the point by δ (Cz.xyz h.w − h.xyz Cz.w) / (h.w h'.w) with
// Cz = C · (0, 0, 1, 0) and h.w, h'.w > 0 in front of the camera: the direction before
// normalisation, sign(δ)(Cz.xyz h.w − h.xyz Cz.w), is affine in (u, v) too: D0 + u·Du + v·Dv. No
// difference of two nearby points is ever taken in float.
//
// The coefficients are computed once, in double, and rounded to float. Each ray is then, in float,
// in exactly this order (every operation an IEEE-rounded +, −, ×, ÷ or square root, never fused,
// with denormals flushed to zero as Embree runs):
//   h    = (H0 + u·Hu) + v·Hv                       per component x, y, z, w
//   org  = h.xyz / h.w
//   e    = (D0 + u·Du) + v·Dv,  dir = e / sqrt((e.x·e.x + e.y·e.y) + e.z·e.z)
//   tnear = 0
//   tfar = +inf without a far plane; with one, |f.xyz / f.w − org| with f = (F0 + u·Hu) + v·Hv,
//          F0 = H0 + (z_far − z_near)·Cz (the same ordered sum of squares, then sqrt)
// camera_rays.cpp is compiled with -ffp-contract=off, so that a compiler allowed FMA (its AVX2 + FMA
// variant, simd_path.hpp, or a -march=native build) fuses nothing: ray_bits_test demands the same
// bits from both variants.
#pragma once

#include <embree3/rtcore.h>

#include <cstddef>

#include "shadowref/reference/ray_stream.hpp"
#include "shadowref/reference/simd_path.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::reference {

class CameraRays {
 public:
  // The coefficients of the prepared scene's camera (its clip_from_scene, its convention's near,
  // middle and far clip depths, its image size). Cost: one 4 × 4 inverse.
  explicit CameraRays(const scene::PreparedScene& scene);

  // The rays of the image points (u[i], v[i]), i < count, written into `out` at first + i: origin,
  // direction, tnear, tfar (the hit fields are the caller's: reset_hits()). `out` must hold
  // first + count rays. Cost: about 40 float operations, 4 divisions and 1 or 2 square roots a ray,
  // 8 rays at a time where the build has AVX2, 4 with SSE.
  void build(const float* u, const float* v, std::size_t count, RayStream& out, std::size_t first) const;
  // The same with the variant chosen (simd_path.hpp; the CPU must run it): the same bits.
  void build(const float* u, const float* v, std::size_t count, RayStream& out, std::size_t first, SimdPath path) const;

  // One ray into an RTCRayHit (geomID invalid: no hit yet): build() on a stream of one, so the same
  // bits. For single queries (the cause model).
  void build(float u, float v, RTCRayHit& rh) const;

  // The image point of pixel (x, y)'s sub-pixel position (sx, sy) in [0, 1)²: x + float(sx), the
  // way render() and the cause model both place their samples (exact for the power-of-two grids
  // of the catalogue).
  static float image_point(int x, double sx) { return static_cast<float>(x) + static_cast<float>(sx); }

 private:
  float h0_[4], hu_[4], hv_[4], f0_[4];
  float d0_[3], du_[3], dv_[3];
  bool far_ = false;
};

}  // namespace shadowref::reference
