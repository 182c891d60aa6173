// shadow_ray.cpp — light samples, the facing cosine and single-ray visibility (shadow_ray.hpp;
// the ray construction itself is inline there).
#include "shadowref/reference/shadow_ray.hpp"

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

bool lit(const EmbreeScene& scene, const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L, double offset) {
  RTCRay ray{};
  const ShadowRayKind kind = make_shadow_ray(p, n, L, offset, ray);
  if (kind != ShadowRayKind::Trace) return kind == ShadowRayKind::Touching;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcOccluded1(scene.handle(), &ctx, &ray);
  return !(ray.tfar < 0);  // Embree sets tfar to −inf on a hit
}

double lit_fraction(const EmbreeScene& scene, const Vec3<double>& p, const Vec3<double>& n, const scene::Light& light) {
  const auto samples = light_samples(light);
  int count = 0;
  for (const auto& L : samples) count += lit(scene, p, n, L, scene.epsilon()) ? 1 : 0;
  return static_cast<double>(count) / static_cast<double>(samples.size());
}

}  // namespace shadowref::reference
