// pixel_surface.cpp — hit_surfaces (pixel_surface.hpp): one body, vectorised in each variant of
// simd_path.hpp. Compiled with -ffp-contract=off (reference/CMakeLists.txt), as the ray builders.
#include "shadowref/reference/pixel_surface.hpp"

#include <bit>
#include <cmath>

#include "shadowref/reference/flush_denormals.hpp"

namespace shadowref::reference {
namespace {

struct Hits {
  const float *ox, *oy, *oz, *dx, *dy, *dz, *tfar, *gx, *gy, *gz;
  const std::uint32_t* geom;
};

[[gnu::always_inline]] inline void surface_kernel(const Hits& h, std::size_t count, float* __restrict px,
                                                  float* __restrict py, float* __restrict pz, float* __restrict nx,
                                                  float* __restrict ny, float* __restrict nz) {
  const float* __restrict ox = h.ox;
  const float* __restrict oy = h.oy;
  const float* __restrict oz = h.oz;
  const float* __restrict dx = h.dx;
  const float* __restrict dy = h.dy;
  const float* __restrict dz = h.dz;
  const float* __restrict tf = h.tfar;
  const float* __restrict gx = h.gx;
  const float* __restrict gy = h.gy;
  const float* __restrict gz = h.gz;
  const std::uint32_t* __restrict geom = h.geom;
  // A miss's point and normal are zeroed through a bit mask: a select between an integer test and
  // float values is control flow to GCC 12, which then leaves the loop scalar.
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t keep = geom[i] == RTC_INVALID_GEOMETRY_ID ? 0u : 0xFFFFFFFFu;
    const float t = tf[i];
    const float len = std::sqrt((gx[i] * gx[i] + gy[i] * gy[i]) + gz[i] * gz[i]);
    const bool flat = !(len > 0.0f);
    const float ax = flat ? -dx[i] : gx[i] / len;
    const float ay = flat ? -dy[i] : gy[i] / len;
    const float az = flat ? -dz[i] : gz[i] / len;
    const bool away = (ax * dx[i] + ay * dy[i]) + az * dz[i] > 0.0f;
    const auto masked = [keep](float f) { return std::bit_cast<float>(std::bit_cast<std::uint32_t>(f) & keep); };
    px[i] = masked(ox[i] + t * dx[i]);
    py[i] = masked(oy[i] + t * dy[i]);
    pz[i] = masked(oz[i] + t * dz[i]);
    nx[i] = masked(away ? -ax : ax);
    ny[i] = masked(away ? -ay : ay);
    nz[i] = masked(away ? -az : az);
  }
}

using Kernel = void (*)(const Hits&, std::size_t, float*, float*, float*, float*, float*, float*);

void surface_baseline(const Hits& h, std::size_t n, float* px, float* py, float* pz, float* nx, float* ny, float* nz) {
  surface_kernel(h, n, px, py, pz, nx, ny, nz);
}

[[gnu::target("avx2,fma")]] void surface_avx2_fma(const Hits& h, std::size_t n, float* px, float* py, float* pz,
                                                   float* nx, float* ny, float* nz) {
  surface_kernel(h, n, px, py, pz, nx, ny, nz);
}

}  // namespace

void hit_surfaces(const RayStream& rays, std::size_t first, std::size_t count, const SurfaceArrays& out, SimdPath path) {
  const FlushDenormalsGuard ftz;  // as the rays (camera_rays.hpp)
  const Hits h{rays.org_x + first, rays.org_y + first, rays.org_z + first, rays.dir_x + first, rays.dir_y + first,
               rays.dir_z + first, rays.tfar + first,  rays.ng_x + first,  rays.ng_y + first,  rays.ng_z + first,
               rays.geom_id + first};
  const Kernel kernel = path == SimdPath::Avx2Fma ? surface_avx2_fma : surface_baseline;
  kernel(h, count, out.px, out.py, out.pz, out.nx, out.ny, out.nz);
}

}  // namespace shadowref::reference
