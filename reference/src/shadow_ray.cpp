// shadow_ray.cpp — light samples and shadow-ray construction (shadow_ray.hpp).
#include "shadowref/reference/shadow_ray.hpp"

#include <limits>

#include "shadowref/reference/embree_scene.hpp"

namespace shadowref::reference {

std::vector<Vec4<double>> light_samples(const scene::Light& light) {
  if (light.type != scene::LightType::Rect) return {scene::homogeneous(light)};
  std::vector<Vec4<double>> out;
  const int n = light.samples;
  out.reserve(static_cast<std::size_t>(n * n));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Vec3<double> q = light.corner + (i + 0.5) / n * light.edge_u + (j + 0.5) / n * light.edge_v;
      out.emplace_back(q.x(), q.y(), q.z(), 1.0);
    }
  }
  return out;
}

double facing(const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L) {
  const Vec3<double> d = L[3] == 0 ? Vec3<double>(L.head<3>()) : Vec3<double>(L.head<3>() - p);
  const double len = d.norm();
  return len > 0 ? n.dot(d) / len : 0.0;
}

ShadowRay make_shadow_ray(const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L, double offset) {
  ShadowRay out;
  if (!(facing(p, n, L) > 0)) return out;
  const Vec3<double> o = p + offset * n;
  Vec3<double> d;
  double tfar = std::numeric_limits<double>::infinity();
  if (L[3] == 0) {
    d = L.head<3>().normalized();
  } else {
    d = L.head<3>() - o;
    const double len = d.norm();
    if (len <= 2 * offset) {
      out.kind = ShadowRayKind::Touching;
      return out;
    }
    d /= len;
    tfar = len - offset;
  }
  out.kind = ShadowRayKind::Trace;
  RTCRay& r = out.ray;
  r.org_x = static_cast<float>(o.x());
  r.org_y = static_cast<float>(o.y());
  r.org_z = static_cast<float>(o.z());
  r.dir_x = static_cast<float>(d.x());
  r.dir_y = static_cast<float>(d.y());
  r.dir_z = static_cast<float>(d.z());
  r.tnear = 0.0f;
  r.tfar = static_cast<float>(tfar);
  r.mask = 0xFFFFFFFFu;
  r.flags = 0;
  return out;
}

bool lit(const EmbreeScene& scene, const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L, double offset) {
  ShadowRay s = make_shadow_ray(p, n, L, offset);
  if (s.kind != ShadowRayKind::Trace) return s.kind == ShadowRayKind::Touching;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcOccluded1(scene.handle(), &ctx, &s.ray);
  return !(s.ray.tfar < 0);  // Embree sets tfar to −inf on a hit
}

double lit_fraction(const EmbreeScene& scene, const Vec3<double>& p, const Vec3<double>& n, const scene::Light& light) {
  const auto samples = light_samples(light);
  int count = 0;
  for (const auto& L : samples) count += lit(scene, p, n, L, scene.epsilon()) ? 1 : 0;
  return static_cast<double>(count) / static_cast<double>(samples.size());
}

}  // namespace shadowref::reference
