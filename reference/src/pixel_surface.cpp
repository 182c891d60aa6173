// pixel_surface.cpp — the camera ray of a pixel point and the surface it sees (pixel_surface.hpp).
#include "shadowref/reference/pixel_surface.hpp"

#include <cmath>
#include <limits>

#include "shadowref/convention.hpp"
#include "shadowref/scene/camera.hpp"

namespace shadowref::reference {

bool same_smooth_surface(const Surface& c, const Surface& h, double epsilon) {
  const Vec3<double> d = h.p - c.p;
  return h.object == c.object && std::abs(c.n.dot(d)) <= kCreaseSine * d.norm() + epsilon && c.n.dot(h.n) >= kCreaseCosine;
}

// Written straight into the stream slot `rh`, never returned by value: the 80-byte RTCRayHit
// assembled field by field (4- and 8-byte stores) and then copied 16 bytes at a time stalled on
// store forwarding (reference_bench, BM_ReferenceRender).
void pixel_ray(const scene::PreparedScene& scene, const Mat4<double>& inverse_clip, int x, int y, double sx, double sy,
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

Surface surface_of(const scene::Scene& scene, const RTCRayHit& rh) {
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
