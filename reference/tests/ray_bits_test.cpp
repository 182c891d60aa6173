// ray_bits_test.cpp — the reference's rays are defined bit for bit (camera_rays.hpp,
// shadow_ray.hpp): the same bits from the baseline (SSE2) and the AVX2 + FMA variants, from one
// big batch and from rays built one at a time or in batches that start at another lane, and close
// to the exact ray (so that the float definition is the ray it claims to be).
//
// The AVX2 + FMA comparison is what fails if the builders' sources lose -ffp-contract=off: GCC
// then fuses their products and sums in that variant only (checked by hand when this test was
// written: with -ffp-contract=fast it fails on every scene).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "shadowref/convention.hpp"
#include "shadowref/reference/camera_rays.hpp"
#include "shadowref/reference/embree_scene.hpp"
#include "shadowref/reference/pixel_surface.hpp"
#include "shadowref/reference/ray_stream.hpp"
#include "shadowref/reference/shadow_ray.hpp"
#include "shadowref/reference/simd_path.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::reference {
namespace {

const std::filesystem::path kScenes = SHADOWREF_SCENES_DIR;

// The bits of rays [first, first + count) of a stream: origin, direction, tnear, tfar.
std::vector<std::uint32_t> bits(const RayStream& r, std::size_t first, std::size_t count) {
  std::vector<std::uint32_t> out;
  for (std::size_t i = first; i < first + count; ++i)
    for (const float f : {r.org_x[i], r.org_y[i], r.org_z[i], r.dir_x[i], r.dir_y[i], r.dir_z[i], r.tnear[i], r.tfar[i]}) {
      std::uint32_t b;
      std::memcpy(&b, &f, sizeof b);
      out.push_back(b);
    }
  return out;
}

std::vector<std::uint32_t> bits(const RTCRay& r) {
  std::vector<std::uint32_t> out;
  for (const float f : {r.org_x, r.org_y, r.org_z, r.dir_x, r.dir_y, r.dir_z, r.tnear, r.tfar}) {
    std::uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    out.push_back(b);
  }
  return out;
}

// The first ray whose bits differ (8 words a ray), or -1: a short message where a vector dump would
// be thousands of lines.
long first_difference(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  if (a.size() != b.size()) return 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i]) return static_cast<long>(i / 8);
  return -1;
}

// Image points over the whole image: every 7th pixel's centre and a 4 × 4 sub-pixel grid.
void image_points(const scene::Scene& s, std::vector<float>& u, std::vector<float>& v) {
  for (int y = 0; y < s.height; y += 7)
    for (int x = 0; x < s.width; x += 7) {
      u.push_back(CameraRays::image_point(x, 0.5));
      v.push_back(CameraRays::image_point(y, 0.5));
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
          u.push_back(CameraRays::image_point(x, (i + 0.5) / 4));
          v.push_back(CameraRays::image_point(y, (j + 0.5) / 4));
        }
    }
}

struct Case {
  std::string scene;
  std::size_t convention;  // index into kRunConventions
};

class RayBits : public ::testing::TestWithParam<Case> {};

TEST_P(RayBits, CameraRaysAreTheSameOnEveryPathAndBatch) {
  const scene::Scene s = scene::load_scene(kScenes / (GetParam().scene + ".json"));
  const scene::PreparedScene prepared = scene::prepare_scene(s, kRunConventions[GetParam().convention]);
  const CameraRays camera(prepared);
  std::vector<float> u, v;
  image_points(s, u, v);
  const std::size_t n = u.size();
  RayStream all;
  all.resize(n);
  camera.build(u.data(), v.data(), n, all, 0, SimdPath::Baseline);
  const auto expected = bits(all, 0, n);

  if (cpu_runs(SimdPath::Avx2Fma)) {
    RayStream wide;
    wide.resize(n);
    camera.build(u.data(), v.data(), n, wide, 0, SimdPath::Avx2Fma);
    EXPECT_EQ(first_difference(bits(wide, 0, n), expected), -1) << "AVX2 + FMA variant";
  }
  // Batches that start 3 lanes in (other lanes, another loop peel) and end anywhere: tile order.
  RayStream shifted;
  shifted.resize(n + 3);
  for (std::size_t first = 0; first < n; first += 37) {
    const std::size_t count = std::min<std::size_t>(37, n - first);
    camera.build(u.data() + first, v.data() + first, count, shifted, first + 3);
  }
  EXPECT_EQ(first_difference(bits(shifted, 3, n), expected), -1) << "batches of 37 starting at lane 3";
  // One at a time, as the cause model builds them.
  for (std::size_t i = 0; i < n; i += 97) {
    RTCRayHit one;
    camera.build(u[i], v[i], one);
    ASSERT_EQ(bits(one.ray), bits(all, i, 1)) << "ray " << i;
    EXPECT_EQ(one.hit.geomID, RTC_INVALID_GEOMETRY_ID);
  }
}

// The float ray is the ray of the definition: within a few float ulps of the one unprojected in
// double from the pixel point's NDC (origin on the near plane, direction toward the clip-depth
// midpoint). A wrong sign or a wrong coefficient moves it by far more.
TEST_P(RayBits, CameraRaysAreCloseToTheExactRay) {
  scene::Scene s = scene::load_scene(kScenes / (GetParam().scene + ".json"));
  const RunConvention& convention = kRunConventions[GetParam().convention];
  // The scene's camera (infinite far plane in the catalogue), then with a finite far plane.
  for (const std::optional<double> far : {s.camera.far, std::optional<double>(25.0)}) {
    s.camera.far = far;
    const scene::PreparedScene prepared = scene::prepare_scene(s, convention);
    const CameraRays camera(prepared);
    const Mat4<double> inv = prepared.camera.clip_from_scene.inverse();
    const double zn = near_ndc_z(convention), zf = far_ndc_z(convention);
    std::vector<float> u, v;
    image_points(s, u, v);
    RayStream r;
    r.resize(u.size());
    camera.build(u.data(), v.data(), u.size(), r, 0);
    const double scale = (inv * Vec4<double>(0, 0, zn, 1)).hnormalized().norm() + 1;
    for (std::size_t i = 0; i < u.size(); ++i) {
      const double nx = 2.0 * static_cast<double>(u[i]) / s.width - 1, ny = 1 - 2.0 * static_cast<double>(v[i]) / s.height;
      const auto unproject = [&](double z) { return Vec3<double>((inv * Vec4<double>(nx, ny, z, 1)).hnormalized()); };
      const Vec3<double> o = unproject(zn), d = (unproject(0.5 * (zn + zf)) - o).normalized();
      const Vec3<double> ro(r.org_x[i], r.org_y[i], r.org_z[i]), rd(r.dir_x[i], r.dir_y[i], r.dir_z[i]);
      ASSERT_LT((ro - o).norm(), 1e-6 * scale) << "ray " << i;
      ASSERT_LT((rd - d).norm(), 1e-6) << "ray " << i;
      EXPECT_EQ(r.tnear[i], 0.0f);
      if (far) {
        const double tfar = (unproject(zf) - o).norm();
        ASSERT_NEAR(r.tfar[i], tfar, 1e-5 * tfar) << "ray " << i;
      } else {
        EXPECT_TRUE(std::isinf(r.tfar[i])) << "ray " << i;
      }
    }
  }
}

// The surfaces of traced camera rays (pixel_surface.hpp): the same bits on both variants, and
// within float rounding of the barycentric point and the face normal in double.
TEST_P(RayBits, SurfacesAreTheSameOnEveryPathAndCloseToExact) {
  const scene::Scene s = scene::load_scene(kScenes / (GetParam().scene + ".json"));
  const scene::PreparedScene prepared = scene::prepare_scene(s, kRunConventions[GetParam().convention]);
  const EmbreeScene embree(s);
  const CameraRays camera(prepared);
  std::vector<float> u, v;
  image_points(s, u, v);
  const std::size_t n = u.size();
  RayStream rays;
  rays.resize(n);
  camera.build(u.data(), v.data(), n, rays, 0);
  rays.reset_hits();
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  const RTCRayHitNp hits = rays.ray_hits();
  rtcIntersectNp(embree.handle(), &ctx, &hits, static_cast<unsigned>(n));
  std::vector<float> a[6], b[6];
  for (auto* arrays : {&a, &b})
    for (auto& x : *arrays) x.resize(n);
  const SurfaceArrays sa{a[0].data(), a[1].data(), a[2].data(), a[3].data(), a[4].data(), a[5].data()};
  const SurfaceArrays sb{b[0].data(), b[1].data(), b[2].data(), b[3].data(), b[4].data(), b[5].data()};
  hit_surfaces(rays, 0, n, sa, SimdPath::Baseline);
  if (cpu_runs(SimdPath::Avx2Fma)) {
    hit_surfaces(rays, 0, n, sb, SimdPath::Avx2Fma);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(0, std::memcmp(a[k].data(), b[k].data(), n * sizeof(float))) << "array " << k;
  }
  std::size_t surfaces = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Surface f = surface_of(s, rays, i, sa, i);
    ASSERT_EQ(f.hit, rays.geom_id[i] != RTC_INVALID_GEOMETRY_ID);
    if (!f.hit) continue;
    ++surfaces;
    const auto& mesh = s.objects[rays.geom_id[i]].mesh;
    const auto& tri = mesh.triangles[rays.prim_id[i]];
    const Vec3<double> v0 = mesh.positions[tri[0]].cast<double>(), e1 = mesh.positions[tri[1]].cast<double>() - v0,
                       e2 = mesh.positions[tri[2]].cast<double>() - v0;
    const Vec3<double> p = v0 + static_cast<double>(rays.u[i]) * e1 + static_cast<double>(rays.v[i]) * e2;
    const Vec3<double> face = e1.cross(e2).normalized();
    ASSERT_LT((f.p - p).norm(), 1e-6 * embree.extent()) << "ray " << i;
    ASSERT_NEAR(std::abs(f.n.dot(face)), 1.0, 1e-6) << "ray " << i;
    const Vec3<double> dir(rays.dir_x[i], rays.dir_y[i], rays.dir_z[i]);
    ASSERT_LE(f.n.dot(dir), 0.0) << "ray " << i << ": the normal faces the camera";
  }
  EXPECT_GT(surfaces, n / 4);
}

TEST_P(RayBits, ShadowRaysAreTheSameOnEveryPathAndBatch) {
  const scene::Scene s = scene::load_scene(kScenes / (GetParam().scene + ".json"));
  // Surface points spread over the scene's box, normals over the sphere (a fixed sequence), and
  // some exactly at a light, so that every kind (traced, attached, touching) occurs.
  const auto box = scene::bounds(s);
  std::vector<float> p[3], n[3];
  const std::size_t count = 4099;
  for (std::size_t i = 0; i < count; ++i) {
    const double a = 0.7548776662466927 * static_cast<double>(i), b = 0.5698402909980532 * static_cast<double>(i);
    const double f[3] = {a - std::floor(a), b - std::floor(b), std::fmod(0.3 + 0.61803398875 * static_cast<double>(i), 1.0)};
    const double theta = 2 * std::acos(-1.0) * f[0], z = 2 * f[1] - 1, r = std::sqrt(1 - z * z);
    const Vec3<double> normal(r * std::cos(theta), r * std::sin(theta), z);
    for (int k = 0; k < 3; ++k) {
      p[k].push_back(static_cast<float>(box[0][k] + f[k] * (box[1][k] - box[0][k])));
      n[k].push_back(static_cast<float>(normal[k]));
    }
  }
  const double eps = 1e-5 * (box[1] - box[0]).norm();
  const Vec4<double> light = scene::homogeneous(s.lights[0]);
  const bool point = light[3] != 0;
  // Half an offset in front of a point light, facing it: touching.
  if (point)
    for (int k = 0; k < 3; ++k) p[k][5] = static_cast<float>(light[k] / light[3] - 0.5 * eps * static_cast<double>(n[k][5]));
  const SurfacePoints points{p[0].data(), p[1].data(), p[2].data(), n[0].data(), n[1].data(), n[2].data()};
  for (const Vec4<double>& L : {light, Vec4<double>(0.3, 1, 0.2, 0)}) {
    RayStream all;
    all.resize(count);
    build_shadow_rays(points, count, L, eps, all, 0, SimdPath::Baseline);
    const auto expected = bits(all, 0, count);
    std::size_t attached = 0, touching = 0;
    for (std::size_t i = 0; i < count; ++i) {
      attached += all.tnear[i] > all.tfar[i] && !all.lit(i);
      touching += all.tnear[i] > all.tfar[i] && all.lit(i);
    }
    EXPECT_GT(attached, count / 4);
    EXPECT_LT(attached, 3 * count / 4);
    EXPECT_EQ(touching, point && L[3] != 0 ? 1u : 0u);
    if (cpu_runs(SimdPath::Avx2Fma)) {
      RayStream wide;
      wide.resize(count);
      build_shadow_rays(points, count, L, eps, wide, 0, SimdPath::Avx2Fma);
      EXPECT_EQ(first_difference(bits(wide, 0, count), expected), -1) << "AVX2 + FMA variant, L.w = " << L[3];
    }
    RayStream shifted;
    shifted.resize(count + 5);
    for (std::size_t first = 0; first < count; first += 61) {
      const std::size_t c = std::min<std::size_t>(61, count - first);
      const SurfacePoints part{p[0].data() + first, p[1].data() + first, p[2].data() + first,
                               n[0].data() + first, n[1].data() + first, n[2].data() + first};
      build_shadow_rays(part, c, L, eps, shifted, first + 5);
    }
    EXPECT_EQ(first_difference(bits(shifted, 5, count), expected), -1) << "batches of 61 starting at lane 5, L.w = " << L[3];
    // One at a time from double inputs (lit(), the cause model): the same ray, or the same kind.
    for (std::size_t i = 0; i < count; i += 13) {
      RTCRay ray{};
      const ShadowRayKind kind = make_shadow_ray(Vec3<double>(p[0][i], p[1][i], p[2][i]), Vec3<double>(n[0][i], n[1][i], n[2][i]),
                                                 L, eps, ray);
      if (all.tnear[i] > all.tfar[i]) {
        ASSERT_EQ(kind, all.lit(i) ? ShadowRayKind::Touching : ShadowRayKind::Attached) << i;
      } else {
        ASSERT_EQ(kind, ShadowRayKind::Trace) << i;
        ASSERT_EQ(bits(ray), bits(all, i, 1)) << i;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Reference, RayBits,
                         ::testing::Values(Case{"ground_sphere", 0}, Case{"ground_sphere", 1}, Case{"ground_sphere", 2},
                                           Case{"ground_sphere", 3}, Case{"stairs_room", 2}, Case{"soft_penumbra", 0},
                                           Case{"directional_light", 3}, Case{"cornell_box", 1}),
                         [](const ::testing::TestParamInfo<Case>& i) {
                           std::string c(kRunConventions[i.param.convention].name);
                           for (char& ch : c)
                             if (ch == '-') ch = '_';
                           return i.param.scene + "_" + c;
                         });

}  // namespace
}  // namespace shadowref::reference
