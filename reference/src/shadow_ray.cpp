// shadow_ray.cpp — light samples, the facing cosine, the shadow rays in float (one body, vectorised
// in each variant of simd_path.hpp) and single-ray visibility (shadow_ray.hpp). Compiled with
// -ffp-contract=off (reference/CMakeLists.txt): the ray definition forbids fused multiply-adds.
#include "shadowref/reference/shadow_ray.hpp"

#include <cmath>

#include "shadowref/reference/flush_denormals.hpp"
#include "shadowref/reference/embree_scene.hpp"

namespace shadowref::reference {
namespace {

struct LightPoint {
  float x, y, z;      // the position, or the unit direction toward the light
  bool directional;
  float offset, twice_offset;
};

[[gnu::always_inline]] inline void shadow_kernel(const SurfacePoints& sp, std::size_t count, const LightPoint& l,
                                                 float* __restrict ox, float* __restrict oy, float* __restrict oz,
                                                 float* __restrict dx, float* __restrict dy, float* __restrict dz,
                                                 float* __restrict tn, float* __restrict tf) {
  const float* __restrict px = sp.px;
  const float* __restrict py = sp.py;
  const float* __restrict pz = sp.pz;
  const float* __restrict nx = sp.nx;
  const float* __restrict ny = sp.ny;
  const float* __restrict nz = sp.nz;
  const float lx = l.x, ly = l.y, lz = l.z, off = l.offset, off2 = l.twice_offset;
  constexpr float kInactive = RayStream::kInactiveNear;
  if (l.directional) {
    for (std::size_t i = 0; i < count; ++i) {
      const bool faces = (nx[i] * lx + ny[i] * ly) + nz[i] * lz > 0.0f;
      ox[i] = px[i] + off * nx[i];
      oy[i] = py[i] + off * ny[i];
      oz[i] = pz[i] + off * nz[i];
      dx[i] = lx;
      dy[i] = ly;
      dz[i] = lz;
      tn[i] = faces ? 0.0f : kInactive;
      tf[i] = faces ? std::numeric_limits<float>::infinity() : -kInactive;
    }
    return;
  }
  for (std::size_t i = 0; i < count; ++i) {
    const float tx = lx - px[i], ty = ly - py[i], tz = lz - pz[i];
    const bool faces = (nx[i] * tx + ny[i] * ty) + nz[i] * tz > 0.0f;
    const float x = px[i] + off * nx[i], y = py[i] + off * ny[i], z = pz[i] + off * nz[i];
    const float gx = lx - x, gy = ly - y, gz = lz - z;
    const float len = std::sqrt((gx * gx + gy * gy) + gz * gz);
    const bool touching = len <= off2;
    ox[i] = x;
    oy[i] = y;
    oz[i] = z;
    dx[i] = gx / len;
    dy[i] = gy / len;
    dz[i] = gz / len;
    // Attached: inactive, reads shadowed; Touching: inactive, reads lit (RayStream::set_inactive).
    // Selects, not branches, so that the loop vectorises.
    const bool traced = faces & !touching;
    const float untraced = faces ? 0.0f : -kInactive;
    tn[i] = traced ? 0.0f : kInactive;
    tf[i] = traced ? len - off : untraced;
  }
}

[[gnu::always_inline]] inline void accumulate_kernel(const SurfacePoints& sp, std::size_t count, const LightPoint& l,
                                                    const std::uint8_t* __restrict lit, double* __restrict direct,
                                                    std::uint32_t* __restrict lit_count) {
  const float* __restrict px = sp.px;
  const float* __restrict py = sp.py;
  const float* __restrict pz = sp.pz;
  const float* __restrict nx = sp.nx;
  const float* __restrict ny = sp.ny;
  const float* __restrict nz = sp.nz;
  const float lx = l.x, ly = l.y, lz = l.z;
  const float w = l.directional ? 0.0f : 1.0f;  // L.xyz − w·p: the direction toward the light
  for (std::size_t i = 0; i < count; ++i) {
    const float tx = lx - w * px[i], ty = ly - w * py[i], tz = lz - w * pz[i];
    const float len = std::sqrt((tx * tx + ty * ty) + tz * tz);
    const float f = ((nx[i] * tx + ny[i] * ty) + nz[i] * tz) / len;
    const bool on = lit[i] != 0 && f > 0.0f;  // f is NaN at the light itself: adds nothing
    direct[i] += on ? static_cast<double>(f) : 0.0;
    lit_count[i] += lit[i] != 0 ? 1u : 0u;
  }
}

using AccumulateKernel = void (*)(const SurfacePoints&, std::size_t, const LightPoint&, const std::uint8_t*, double*,
                                  std::uint32_t*);

void accumulate_baseline(const SurfacePoints& sp, std::size_t n, const LightPoint& l, const std::uint8_t* lit,
                         double* direct, std::uint32_t* lit_count) {
  accumulate_kernel(sp, n, l, lit, direct, lit_count);
}

[[gnu::target("avx2,fma")]] void accumulate_avx2_fma(const SurfacePoints& sp, std::size_t n, const LightPoint& l,
                                                      const std::uint8_t* lit, double* direct, std::uint32_t* lit_count) {
  accumulate_kernel(sp, n, l, lit, direct, lit_count);
}

using Kernel = void (*)(const SurfacePoints&, std::size_t, const LightPoint&, float*, float*, float*, float*, float*,
                        float*, float*, float*);

void shadow_baseline(const SurfacePoints& sp, std::size_t n, const LightPoint& l, float* ox, float* oy, float* oz,
                     float* dx, float* dy, float* dz, float* tn, float* tf) {
  shadow_kernel(sp, n, l, ox, oy, oz, dx, dy, dz, tn, tf);
}

[[gnu::target("avx2,fma")]] void shadow_avx2_fma(const SurfacePoints& sp, std::size_t n, const LightPoint& l,
                                                  float* ox, float* oy, float* oz, float* dx, float* dy, float* dz,
                                                  float* tn, float* tf) {
  shadow_kernel(sp, n, l, ox, oy, oz, dx, dy, dz, tn, tf);
}

LightPoint light_point(const Vec4<double>& L, double offset) {
  LightPoint l{};
  l.directional = L[3] == 0;
  const Vec3<double> at = l.directional ? Vec3<double>(L.head<3>().normalized()) : Vec3<double>(L.head<3>());
  l.x = static_cast<float>(at.x());
  l.y = static_cast<float>(at.y());
  l.z = static_cast<float>(at.z());
  l.offset = static_cast<float>(offset);
  l.twice_offset = static_cast<float>(2 * offset);
  return l;
}

}  // namespace

void accumulate_lit(const SurfacePoints& points, std::size_t count, const Vec4<double>& L, const std::uint8_t* lit,
                    double* direct, std::uint32_t* lit_count, SimdPath path) {
  const FlushDenormalsGuard ftz;  // as the rays: the same bits whoever calls
  const AccumulateKernel kernel = path == SimdPath::Avx2Fma ? accumulate_avx2_fma : accumulate_baseline;
  kernel(points, count, light_point(L, 0.0), lit, direct, lit_count);
}

void build_shadow_rays(const SurfacePoints& points, std::size_t count, const Vec4<double>& L, double offset,
                       RayStream& out, std::size_t first, SimdPath path) {
  const FlushDenormalsGuard ftz;  // the rays are defined with denormals flushed, as Embree traces them
  const LightPoint l = light_point(L, offset);
  const Kernel kernel = path == SimdPath::Avx2Fma ? shadow_avx2_fma : shadow_baseline;
  kernel(points, count, l, out.org_x + first, out.org_y + first, out.org_z + first, out.dir_x + first,
         out.dir_y + first, out.dir_z + first, out.tnear + first, out.tfar + first);
}

void occlude_shadow_rays(const EmbreeScene& scene, RayStream& rays, std::size_t count, std::uint8_t* lit) {
  const FlushDenormalsGuard ftz;  // as Embree asks (docs/dependencies.md)
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  const RTCRayNp np = rays.rays();
  rtcOccludedNp(scene.handle(), &ctx, &np, static_cast<unsigned>(count));
  const float* __restrict tfar = rays.tfar;
  for (std::size_t i = 0; i < count; ++i) lit[i] = !(tfar[i] < 0);  // Embree sets tfar to −inf on a hit
}

ShadowRayKind make_shadow_ray(const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L, double offset,
                              RTCRay& ray) {
  const float px = static_cast<float>(p.x()), py = static_cast<float>(p.y()), pz = static_cast<float>(p.z());
  const float nx = static_cast<float>(n.x()), ny = static_cast<float>(n.y()), nz = static_cast<float>(n.z());
  thread_local RayStream one;
  one.resize(1);
  build_shadow_rays(SurfacePoints{&px, &py, &pz, &nx, &ny, &nz}, 1, L, offset, one, 0);
  if (one.tnear[0] > one.tfar[0]) return one.lit(0) ? ShadowRayKind::Touching : ShadowRayKind::Attached;
  ray.org_x = one.org_x[0];
  ray.org_y = one.org_y[0];
  ray.org_z = one.org_z[0];
  ray.dir_x = one.dir_x[0];
  ray.dir_y = one.dir_y[0];
  ray.dir_z = one.dir_z[0];
  ray.tnear = one.tnear[0];
  ray.tfar = one.tfar[0];
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  return ShadowRayKind::Trace;
}

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
