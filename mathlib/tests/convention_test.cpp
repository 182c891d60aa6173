// convention_test.cpp — the run conventions (convention.hpp): every convention puts every point on
// the same pixel, orders depth its own way, and states its GL state consistently.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "shadowref/convention.hpp"

namespace shadowref {
namespace {

constexpr double kFovy = 0.8;       // radians
constexpr double kAspect = 1.5;
constexpr double kNear = 0.1;

struct Camera {
  Vec3<double> eye{1.0, 3.0, 7.0}, target{0.2, 0.5, -0.3}, up{0.0, 1.0, 0.0};
};

Mat4<double> clip_from_scene(const RunConvention& c, std::optional<double> far = std::nullopt) {
  const Camera cam;
  return perspective_for<double>(c, kFovy, kAspect, kNear, far).value() *
         view_from_scene<double>(c, cam.eye, cam.target, cam.up).value();
}

Vec3<double> ndc(const Mat4<double>& m, const Vec3<double>& p) {
  const Vec4<double> h = m * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
  return h.head<3>() / h.w();
}

TEST(Convention, NamesAreFoundAndUnique) {
  for (const RunConvention& c : kRunConventions) EXPECT_EQ(find_run_convention(c.name), &c);
  EXPECT_EQ(find_run_convention("vulkan"), nullptr);
  EXPECT_EQ(kDefaultConvention.name, "gl");
}

TEST(Convention, EveryConventionPutsEveryPointOnTheSamePixel) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  const Mat4<double> gl = clip_from_scene(kDefaultConvention);
  int in_view = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3<double> p(u(rng), u(rng), u(rng) - 2.0);
    const Vec4<double> hg = gl * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
    if (!(hg.w() > kNear)) continue;  // behind or at the eye: no pixel
    ++in_view;
    const Vec3<double> ref = ndc(gl, p);
    for (const RunConvention& c : kRunConventions) {
      const Mat4<double> m = clip_from_scene(c);
      const Vec4<double> h = m * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
      EXPECT_GT(h.w(), 0.0) << c.name << ": a point in front of the camera must have w > 0";
      const Vec3<double> n = h.head<3>() / h.w();
      // Two different products of the same exact transform: a few ulps of the NDC magnitude.
      const double tol = 64 * std::numeric_limits<double>::epsilon() * (1.0 + ref.head<2>().cwiseAbs().maxCoeff());
      EXPECT_NEAR(n.x(), ref.x(), tol) << c.name;
      EXPECT_NEAR(n.y(), ref.y(), tol) << c.name;
    }
  }
  EXPECT_GT(in_view, 500);
}

TEST(Convention, DepthRunsFromTheNearPlaneTowardTheFarOneInItsOwnDirection) {
  const Camera cam;
  const Vec3<double> forward = (cam.target - cam.eye).normalized();
  for (const RunConvention& c : kRunConventions) {
    for (const std::optional<double> far : {std::optional<double>(), std::optional<double>(50.0)}) {
      const Mat4<double> m = clip_from_scene(c, far);
      const double at_near = ndc(m, cam.eye + kNear * forward).z();
      EXPECT_NEAR(at_near, near_ndc_z(c), 1e-12) << c.name;
      if (far) {
        EXPECT_NEAR(ndc(m, cam.eye + *far * forward).z(), far_ndc_z(c), 1e-9) << c.name;
      }
      const double a = ndc(m, cam.eye + 1.0 * forward).z(), b = ndc(m, cam.eye + 2.0 * forward).z();
      // The nearer point passes the convention's "nearer" test against the farther one.
      if (nearer(c) == DepthCompare::Less) {
        EXPECT_LT(a, b) << c.name;
      } else {
        EXPECT_GT(a, b) << c.name;
      }
    }
  }
}

TEST(Convention, StateIsConsistentWithTheDepthOrder) {
  for (const RunConvention& c : kRunConventions) {
    const bool reversed = c.clip.order == DepthOrder::Reversed;
    EXPECT_EQ(far_depth(c), reversed ? 0.0 : 1.0) << c.name;
    EXPECT_EQ(near_depth(c), reversed ? 1.0 : 0.0) << c.name;
    EXPECT_EQ(lit_when(c), reversed ? DepthCompare::GreaterEqual : DepthCompare::LessEqual) << c.name;
    EXPECT_EQ(nearer_or_equal(c), reversed ? DepthCompare::GreaterEqual : DepthCompare::LessEqual) << c.name;
    EXPECT_EQ(polygon_offset_sign(c), reversed ? -1.0f : 1.0f) << c.name;
    EXPECT_EQ(c.float_depth, reversed) << c.name << ": reversed-Z is only worth it with float depth";
    // The bias matrix maps the clip depth range onto the texture's 0..1.
    const Mat4<double> b = shadow_bias<double>(c);
    const Vec4<double> near_tex = b * Vec4<double>(0, 0, near_ndc_z(c), 1);
    EXPECT_DOUBLE_EQ(near_tex.z(), near_depth(c)) << c.name;
  }
}

TEST(Convention, D3dIsTrulyLeftHanded) {
  const RunConvention& d3d = *find_run_convention("d3d");
  const Camera cam;
  const Mat4<double> v = view_from_scene<double>(d3d, cam.eye, cam.target, cam.up).value();
  // The camera looks down +z of its view space (left-handed), and the view is not a transposed
  // right-handed matrix: its rotation part has determinant −1 over scene coordinates (the mirror).
  const Vec4<double> ahead = v * Vec4<double>(cam.target.x(), cam.target.y(), cam.target.z(), 1.0);
  EXPECT_GT(ahead.z(), 0.0);
  const double det_d3d = v.topLeftCorner<3, 3>().determinant();
  EXPECT_NEAR(det_d3d, -1.0, 1e-12);
  const Mat4<double> gl_view = view_from_scene<double>(kDefaultConvention, cam.eye, cam.target, cam.up).value();
  const double det_gl = gl_view.topLeftCorner<3, 3>().determinant();
  EXPECT_NEAR(det_gl, 1.0, 1e-12);
  EXPECT_GT((v - gl_view.transpose()).cwiseAbs().maxCoeff(), 0.1);
  EXPECT_EQ(world_from_scene<double>(d3d)(2, 2), -1.0);
}

}  // namespace
}  // namespace shadowref
