// camera_rays.cpp — CameraRays (camera_rays.hpp): coefficients in double, rays in float, in plain
// loops over structure-of-arrays that the compiler vectorises. Compiled with -ffp-contract=off
// (reference/CMakeLists.txt): the ray definition forbids fused multiply-adds.
#include "shadowref/reference/camera_rays.hpp"

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "shadowref/convention.hpp"
#include "shadowref/reference/simd_path.hpp"
#include "shadowref/reference/flush_denormals.hpp"

namespace shadowref::reference {

CameraRays::CameraRays(const scene::PreparedScene& scene) {
  const scene::Scene& s = *scene.scene;
  const Mat4<double> c = scene.camera.clip_from_scene.inverse();
  const double zn = near_ndc_z(*scene.convention), zf = far_ndc_z(*scene.convention);
  const double zm = 0.5 * (zn + zf);
  // ndc_x = 2u/W − 1, ndc_y = 1 − 2v/H (scene::pixel_to_ndc): h = C (ndc_x, ndc_y, zn, 1).
  const Vec4<double> h0 = c * Vec4<double>(-1.0, 1.0, zn, 1.0);
  const Vec4<double> hu = c.col(0) * (2.0 / s.width);
  const Vec4<double> hv = c.col(1) * (-2.0 / s.height);
  const Vec4<double> cz = c.col(2);
  const Vec4<double> f0 = h0 + (zf - zn) * cz;
  const double sign = zm > zn ? 1.0 : -1.0;
  // sign (Cz.xyz h.w − h.xyz Cz.w), linear in h: the same map applied to each coefficient.
  const auto direction = [&](const Vec4<double>& h) -> Vec3<double> {
    return sign * (cz.head<3>() * h.w() - h.head<3>() * cz.w());
  };
  const Vec3<double> d0 = direction(h0), du = direction(hu), dv = direction(hv);
  for (int k = 0; k < 4; ++k) {
    h0_[k] = static_cast<float>(h0[k]);
    hu_[k] = static_cast<float>(hu[k]);
    hv_[k] = static_cast<float>(hv[k]);
    f0_[k] = static_cast<float>(f0[k]);
  }
  for (int k = 0; k < 3; ++k) {
    d0_[k] = static_cast<float>(d0[k]);
    du_[k] = static_cast<float>(du[k]);
    dv_[k] = static_cast<float>(dv[k]);
  }
  far_ = s.camera.far.has_value();
}

namespace {

// The ray definition of camera_rays.hpp over `count` points: one body, inlined into each variant
// below and vectorised there at that variant's width.
struct Coefficients {
  const float *h0, *hu, *hv, *f0, *d0, *du, *dv;
  bool far;
};

[[gnu::always_inline]] inline void camera_kernel(const Coefficients& c, const float* __restrict u,
                                                 const float* __restrict v, std::size_t count, float* __restrict ox,
                                                 float* __restrict oy, float* __restrict oz, float* __restrict dx,
                                                 float* __restrict dy, float* __restrict dz, float* __restrict tn,
                                                 float* __restrict tf) {
  // Locals, so that the loop reads no coefficient through a pointer the outputs could alias.
  const float h0x = c.h0[0], h0y = c.h0[1], h0z = c.h0[2], h0w = c.h0[3];
  const float hux = c.hu[0], huy = c.hu[1], huz = c.hu[2], huw = c.hu[3];
  const float hvx = c.hv[0], hvy = c.hv[1], hvz = c.hv[2], hvw = c.hv[3];
  const float d0x = c.d0[0], d0y = c.d0[1], d0z = c.d0[2];
  const float dux = c.du[0], duy = c.du[1], duz = c.du[2];
  const float dvx = c.dv[0], dvy = c.dv[1], dvz = c.dv[2];
  for (std::size_t i = 0; i < count; ++i) {
    const float hx = (h0x + u[i] * hux) + v[i] * hvx;
    const float hy = (h0y + u[i] * huy) + v[i] * hvy;
    const float hz = (h0z + u[i] * huz) + v[i] * hvz;
    const float hw = (h0w + u[i] * huw) + v[i] * hvw;
    ox[i] = hx / hw;
    oy[i] = hy / hw;
    oz[i] = hz / hw;
    const float ex = (d0x + u[i] * dux) + v[i] * dvx;
    const float ey = (d0y + u[i] * duy) + v[i] * dvy;
    const float ez = (d0z + u[i] * duz) + v[i] * dvz;
    const float len = std::sqrt((ex * ex + ey * ey) + ez * ez);
    dx[i] = ex / len;
    dy[i] = ey / len;
    dz[i] = ez / len;
    tn[i] = 0.0f;
    tf[i] = std::numeric_limits<float>::infinity();
  }
  if (!c.far) return;
  const float f0x = c.f0[0], f0y = c.f0[1], f0z = c.f0[2], f0w = c.f0[3];
  for (std::size_t i = 0; i < count; ++i) {
    const float fw = (f0w + u[i] * huw) + v[i] * hvw;
    const float gx = ((f0x + u[i] * hux) + v[i] * hvx) / fw - ox[i];
    const float gy = ((f0y + u[i] * huy) + v[i] * hvy) / fw - oy[i];
    const float gz = ((f0z + u[i] * huz) + v[i] * hvz) / fw - oz[i];
    tf[i] = std::sqrt((gx * gx + gy * gy) + gz * gz);
  }
}

using Kernel = void (*)(const Coefficients&, const float*, const float*, std::size_t, float*, float*, float*, float*,
                        float*, float*, float*, float*);

void camera_baseline(const Coefficients& c, const float* u, const float* v, std::size_t n, float* ox, float* oy,
                     float* oz, float* dx, float* dy, float* dz, float* tn, float* tf) {
  camera_kernel(c, u, v, n, ox, oy, oz, dx, dy, dz, tn, tf);
}

[[gnu::target("avx2,fma")]] void camera_avx2_fma(const Coefficients& c, const float* u, const float* v, std::size_t n,
                                                  float* ox, float* oy, float* oz, float* dx, float* dy, float* dz,
                                                  float* tn, float* tf) {
  camera_kernel(c, u, v, n, ox, oy, oz, dx, dy, dz, tn, tf);
}

}  // namespace

void CameraRays::build(const float* u, const float* v, std::size_t count, RayStream& out, std::size_t first) const {
  build(u, v, count, out, first, best_simd_path());
}

void CameraRays::build(const float* u, const float* v, std::size_t count, RayStream& out, std::size_t first,
                       SimdPath path) const {
  const FlushDenormalsGuard ftz;  // the rays are defined with denormals flushed, as Embree traces them
  const Coefficients c{h0_, hu_, hv_, f0_, d0_, du_, dv_, far_};
  const Kernel kernel = path == SimdPath::Avx2Fma ? camera_avx2_fma : camera_baseline;
  kernel(c, u, v, count, out.org_x + first, out.org_y + first, out.org_z + first, out.dir_x + first,
         out.dir_y + first, out.dir_z + first, out.tnear + first, out.tfar + first);
}

void CameraRays::build(float u, float v, RTCRayHit& rh) const {
  thread_local RayStream one;
  one.resize(1);
  build(&u, &v, 1, one, 0);
  rh = RTCRayHit{};
  rh.ray.org_x = one.org_x[0];
  rh.ray.org_y = one.org_y[0];
  rh.ray.org_z = one.org_z[0];
  rh.ray.dir_x = one.dir_x[0];
  rh.ray.dir_y = one.dir_y[0];
  rh.ray.dir_z = one.dir_z[0];
  rh.ray.tnear = one.tnear[0];
  rh.ray.tfar = one.tfar[0];
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

}  // namespace shadowref::reference
