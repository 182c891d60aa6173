// shadowref/reference/pixel_surface.hpp — the surface seen through a point of a pixel, defined once:
// the reference's images (render.hpp) and the cause model (causes.hpp) both find it here, so the
// two can never disagree about which surface a pixel shows (at the camera's far plane, on a
// degenerate triangle, at a fold).
//
// The ray leaves the near plane (what a rasteriser clips at) through the pixel point's NDC
// (scene::pixel_to_ndc), unprojected through inverse(P · V) of the prepared camera in its run
// convention, toward the point halfway to the far plane in clip depth (finite even with an infinite
// far), and ends at the far plane when the camera has one. The surface is the first hit: its point
// (from the barycentrics, in double), its face normal turned toward the viewer (two-sided; a
// zero-area triangle's normal is the reversed ray), its object and albedo.
#pragma once

#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "shadowref/convention.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/scene/prepared_scene.hpp"

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
// no hit yet (geomID invalid): how every ray the reference and its cause model trace starts.
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

// The pixel point's camera ray for `scene` (pixel (x, y), row 0 at the top, at (sx, sy) inside it),
// written into `rh` as Embree wants it (geomID invalid: no hit yet); and the surface `rh` hit after
// tracing (hit false on a miss). Inline: the reference's tiles build and read millions of these,
// and a call across translation units cost 6 % of BM_ReferenceRender.
// Written straight into the stream slot `rh`, never returned by value: the 80-byte RTCRayHit
// assembled field by field (4- and 8-byte stores) and then copied 16 bytes at a time stalled on
// store forwarding (reference_bench, BM_ReferenceRender).
inline void pixel_ray(const scene::PreparedScene& scene, const Mat4<double>& inverse_clip, int x, int y, double sx, double sy,
               RTCRayHit& rh) {
  const scene::Scene& s = *scene.scene;
  const double near_ndc = near_ndc_z(*scene.convention), far_ndc = far_ndc_z(*scene.convention);
  const Vec2<double> ndc = scene::pixel_to_ndc<double>(x, y, sx, sy, s.width, s.height);
  const auto unproject = [&](double z) {
    const Vec4<double> h = inverse_clip * Vec4<double>(ndc.x(), ndc.y(), z, 1.0);
    return Vec3<double>(h.head<3>() / h[3]);
  };
  const Vec3<double> o = unproject(near_ndc);
  const Vec3<double> d = (unproject(0.5 * (near_ndc + far_ndc)) - o).normalized();
  const double tfar = s.camera.far ? (unproject(far_ndc) - o).norm() : std::numeric_limits<double>::infinity();
  start_ray(o, d, tfar, rh);
}

inline Surface surface_of(const scene::Scene& scene, const RTCRayHit& rh) {
  Surface s;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return s;
  const auto& obj = scene.objects[rh.hit.geomID];
  const auto& tri = obj.mesh.triangles[rh.hit.primID];
  const Vec3<double> v0 = obj.mesh.positions[tri[0]].cast<double>();
  const Vec3<double> v1 = obj.mesh.positions[tri[1]].cast<double>();
  const Vec3<double> v2 = obj.mesh.positions[tri[2]].cast<double>();
  const double u = rh.hit.u, v = rh.hit.v;
  s.hit = true;
  s.p = v0 + u * (v1 - v0) + v * (v2 - v0);
  const Vec3<double> dir(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
  Vec3<double> n = (v1 - v0).cross(v2 - v0);
  n = n.norm() > 0 ? Vec3<double>(n.normalized()) : Vec3<double>(-dir.normalized());
  s.n = n.dot(dir) > 0 ? Vec3<double>(-n) : n;  // two-sided: the side the camera sees
  s.albedo = obj.color;
  s.object = rh.hit.geomID;
  return s;
}


}  // namespace shadowref::reference
