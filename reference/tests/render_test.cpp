// render_test.cpp — whole reference renders of catalogue scenes: shadows where geometry puts
// them, the image right side up, and no shadow at all when the camera sits at the light.
#include <gtest/gtest.h>

#include "shadowref/reference/render.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace shadowref::reference {
namespace {

const std::filesystem::path kScenes = SHADOWREF_SCENES_DIR;

// The pixel whose centre region a world point projects into (row 0 at the top).
std::pair<int, int> pixel_of(const scene::Scene& s, const Vec3<double>& p) {
  const Mat4<double> pv = scene::projection_matrix<double>(s.camera, s.width, s.height).value() *
                          scene::view_matrix<double>(s.camera).value();
  const Vec4<double> c = pv * p.homogeneous();
  const double x = (c.x() / c.w() + 1) / 2 * s.width, y = (1 - c.y() / c.w()) / 2 * s.height;
  return {static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y))};
}

TEST(Render, GroundSphereShadowWhereGeometryPutsIt) {
  const scene::Scene s = scene::load_scene(kScenes / "ground_sphere.json");
  Options o;
  o.samples_per_axis = 2;
  const Images img = render(s, o);
  ASSERT_EQ(img.lights.size(), 1u);
  auto at = [&](const Vec3<double>& p) {
    const auto [x, y] = pixel_of(s, p);
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(x);
  };
  // The light (2, 6, 1) through the sphere centre (0, 1.5, 0) meets the ground at t = 4/3:
  // (−2/3, 0, −1/3), the middle of the shadow.
  const std::size_t shadow = at(Vec3<double>(-2.0 / 3, 0, -1.0 / 3));
  EXPECT_EQ(img.lights[0].mask[shadow], 0);
  EXPECT_EQ(img.lights[0].decided[shadow], 255);
  EXPECT_EQ(img.lights[0].visibility[shadow], 0.0f);
  // Ground in front of the sphere, on the light's side: lit.
  const std::size_t lit = at(Vec3<double>(2, 0, 3));
  EXPECT_EQ(img.lights[0].mask[lit], 255);
  EXPECT_EQ(img.lights[0].visibility[lit], 1.0f);
  // The sphere's top faces the light: lit; the top rows see the sky (no surface): 128 and −1.
  EXPECT_EQ(img.lights[0].mask[at(Vec3<double>(0.3, 2.45, 0.3))], 255);
  EXPECT_EQ(img.lights[0].mask[5], 128) << "row 0 is the top of the image: the sky";
  EXPECT_EQ(img.visibility[5], -1.0f);
  // A shadowed pixel is dark in shaded.png and a lit one bright (sRGB of ambient vs lit).
  EXPECT_LT(img.shaded[3 * shadow], img.shaded[3 * lit]);
}

TEST(Render, CameraAtTheLightSeesNoShadow) {
  const scene::Scene s = scene::load_scene(kScenes / "camera_at_light.json");
  ASSERT_EQ((s.camera.position - s.lights[0].position).norm(), 0.0);
  const Images img = render(s);
  std::size_t surface = 0, shadowed = 0;
  for (std::size_t i = 0; i < img.lights[0].mask.size(); ++i) {
    surface += img.lights[0].mask[i] != 128 ? 1 : 0;
    shadowed += img.lights[0].mask[i] == 0 ? 1 : 0;
  }
  EXPECT_GT(surface, img.lights[0].mask.size() / 2) << "the scene must actually show surfaces";
  EXPECT_EQ(shadowed, 0u) << "every surface seen from the light is lit";
  // Sub-pixel samples that graze a surface (facing cosine at rounding level) may honestly go
  // either way; such pixels are undecided. Every decided pixel is fully lit or shows no surface.
  for (std::size_t i = 0; i < img.visibility.size(); ++i) {
    if (img.decided[i] == 255) {
      EXPECT_TRUE(img.visibility[i] == -1.0f || img.visibility[i] == 1.0f) << i << ": " << img.visibility[i];
    }
  }
}

TEST(Render, SeveralLightsGetOneMaskEach) {
  const scene::Scene s = scene::load_scene(kScenes / "two_lights.json");
  Options o;
  o.samples_per_axis = 1;
  const Images img = render(s, o);
  ASSERT_EQ(img.lights.size(), 2u);
  EXPECT_NE(img.lights[0].mask, img.lights[1].mask) << "two lights, two different shadows";
  for (std::size_t i = 0; i < img.decided.size(); ++i) {
    EXPECT_EQ(img.decided[i] == 255, img.lights[0].decided[i] == 255 && img.lights[1].decided[i] == 255);
  }
}

TEST(Render, OptionsOutOfRange) {
  const scene::Scene s = scene::load_scene(kScenes / "ground_sphere.json");
  Options o;
  o.samples_per_axis = 0;
  EXPECT_THROW((void)render(s, o), std::invalid_argument);
  o.samples_per_axis = 2;
  o.threads = -1;
  EXPECT_THROW((void)render(s, o), std::invalid_argument);
}

}  // namespace
}  // namespace shadowref::reference
