// shadowref/reference/pixel_surface.hpp — the surface seen through a point of a pixel, defined once:
// the reference's images (render.hpp) and the cause model (causes.hpp) both find it here, so the
// two can never disagree about which surface a pixel shows (at the camera's far plane, on a
// degenerate triangle, at a fold).
//
// The ray leaves the near plane (what a rasteriser clips at) through the pixel point's NDC
// (scene::pixel_to_ndc), unprojected through inverse(P · V) of the prepared camera in its run
// convention, toward the point halfway to the far plane in clip depth (finite even with an infinite
// far), and ends at the far plane when the camera has one: camera_rays.hpp defines it, in float,
// bit for bit. The surface is the first hit, in float, in this order (hit_surfaces below):
//   p = org + tfar·dir                                  per component, tfar Embree's hit distance
//   n = Ng / sqrt((Ng.x·Ng.x + Ng.y·Ng.y) + Ng.z·Ng.z)  Embree's geometric normal, made unit;
//       −dir where |Ng| is 0 (a zero-area triangle)
//   n = −n where (n.x·dir.x + n.y·dir.y) + n.z·dir.z > 0  (two-sided: the side the camera sees)
// and its object (Embree's geomID) and albedo. p and n go on, as they are, into the shadow rays
// (shadow_ray.hpp) and, widened to double, into the decided rule below. Like the rays, built 8 or
// 4 at a time with the same bits on every variant (pixel_surface.cpp: -ffp-contract=off). Embree's
// own outputs (tfar, Ng) are what its kernel for this CPU computes.
#pragma once

#include <embree3/rtcore.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "shadowref/reference/ray_stream.hpp"
#include "shadowref/reference/simd_path.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::reference {

struct Surface {
  bool hit = false;
  Vec3<double> p = Vec3<double>::Zero();
  Vec3<double> n = Vec3<double>::Zero();  // unit face normal, toward the viewer
  Vec3<float> albedo = Vec3<float>::Zero();
  std::uint32_t object = 0;  // the scene object hit (Embree's geomID)
};

// Sub-samples of one pixel see one smooth surface only when each lies on the centre's object, no
// farther from the centre's tangent plane than kCreaseSine times its distance from the centre, and
// with a normal within asin(kCreaseSine) = 30° of the centre's: boxes, stairs and walls fold by 90°,
// while the catalogue's tessellated spheres and tori (≥ 24 segments) bend by at most 15° per facet.
// The normal test catches a fold whose other face lies almost in the centre's plane near the edge
// (a plate's top face seen a hair below its front edge: millimetres behind the front plane, yet
// another face that a rasteriser snapping vertices to 1/16 px may show at the centre).
inline constexpr double kCreaseSine = 0.5;
inline constexpr double kCreaseCosine = 0.86602540378443865;  // sqrt(1 - kCreaseSine²)
inline bool same_smooth_surface(const Surface& centre, const Surface& sample, double epsilon) {
  if (sample.object != centre.object || centre.n.dot(sample.n) < kCreaseCosine) return false;
  const Vec3<double> d = sample.p - centre.p;
  return std::abs(centre.n.dot(d)) <= kCreaseSine * d.norm() + epsilon;
}

// `rh` set to the ray from `o` along the unit `d` up to `tfar`, in float as Embree takes it, with
// no hit yet (geomID invalid): how the cause model's light-view probes start.
inline void start_ray(const Vec3<double>& o, const Vec3<double>& d, double tfar, RTCRayHit& rh) {
  rh = RTCRayHit{};
  rh.ray.org_x = static_cast<float>(o.x());
  rh.ray.org_y = static_cast<float>(o.y());
  rh.ray.org_z = static_cast<float>(o.z());
  rh.ray.dir_x = static_cast<float>(d.x());
  rh.ray.dir_y = static_cast<float>(d.y());
  rh.ray.dir_z = static_cast<float>(d.z());
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = static_cast<float>(tfar);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// The surfaces of traced camera rays in structure-of-arrays float: what the shadow rays take
// (shadow_ray.hpp's SurfacePoints reads the same arrays). A miss has zero point and normal.
struct SurfaceArrays {
  float *px, *py, *pz;
  float *nx, *ny, *nz;
};
// The surfaces of rays [first, first + count) of `rays` (traced with rtcIntersectNp), written to
// `out` at 0 .. count − 1. Cost: about 25 float operations, a square root and a division a ray.
void hit_surfaces(const RayStream& rays, std::size_t first, std::size_t count, const SurfaceArrays& out,
                  SimdPath path = best_simd_path());

// Sample `i` of hit_surfaces()' output for ray `ray` of `rays`, widened to double, with its object
// and albedo: what the decided rule and the shading read.
inline Surface surface_of(const scene::Scene& scene, const RayStream& rays, std::size_t ray, const SurfaceArrays& a,
                          std::size_t i) {
  Surface s;
  const unsigned geom = rays.geom_id[ray];
  if (geom == RTC_INVALID_GEOMETRY_ID) return s;
  s.hit = true;
  s.p = Vec3<double>(a.px[i], a.py[i], a.pz[i]);
  s.n = Vec3<double>(a.nx[i], a.ny[i], a.nz[i]);
  s.albedo = scene.objects[geom].color;
  s.object = geom;
  return s;
}

}  // namespace shadowref::reference
