// scene_test.cpp — a loaded scene's fields, defaults, camera matrices, lights, and the catalogue.
#include <gtest/gtest.h>

#include <set>

#include "shadowref/projection.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/view.hpp"
#include "test_scene_json.hpp"

namespace shadowref::scene {
namespace {

Scene minimal() { return parse_scene(test::minimal_scene().dump(), std::filesystem::path(SHADOWREF_SCENE_TEST_DATA) / "t.json"); }

TEST(Scene, Fields) {
  const Scene s = minimal();
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.width, 64);
  EXPECT_EQ(s.height, 48);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Point);
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].name, "ground");
  EXPECT_TRUE(s.objects[0].receiver);
  EXPECT_FALSE(s.objects[1].receiver);
  EXPECT_EQ(s.receiver_index(), std::optional<std::size_t>(0));
  EXPECT_FALSE(s.camera.far.has_value());
  ASSERT_EQ(s.expect.count("planar"), 1u);
  EXPECT_TRUE(s.expect.at("planar").pass);
}

TEST(Scene, ReceiverPlaneIsTheGround) {
  const auto p = receiver_plane(minimal());
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->abcd, Vec4<double>(0, 1, 0, 0));  // the y = 0 plane, facing up, exactly
}

TEST(Scene, TranslatedSphereBounds) {
  const Scene s = minimal();
  const auto& m = s.objects[1].mesh;
  float lo = 1e9f, hi = -1e9f;
  for (const auto& p : m.positions) {
    lo = std::min(lo, p.y());
    hi = std::max(hi, p.y());
  }
  EXPECT_FLOAT_EQ(lo, 0.5f);  // poles at 1.5 ± 1
  EXPECT_FLOAT_EQ(hi, 2.5f);
}

TEST(Camera, MatricesComeFromMathlib) {
  const Scene s = minimal();
  const Mat4<float> v = view_matrix<float>(s.camera).value();
  const Mat4<float> expected_v = look_at<float>(Vec3<float>(0, 4, 8), Vec3<float>(0, 0, 0), Vec3<float>(0, 1, 0)).value();
  EXPECT_EQ(v, expected_v);
  const Mat4<float> p = projection_matrix<float>(s.camera, s.width, s.height).value();
  const float fovy = static_cast<float>(45.0 * std::numbers::pi / 180.0);
  EXPECT_EQ(p, perspective_infinite<float>(fovy, 64.0f / 48.0f, 0.1f, kOpenGL).value());
}

TEST(Camera, FiniteFarWhenGiven) {
  auto doc = test::minimal_scene();
  doc["camera"]["far"] = 50;
  const Scene s = parse_scene(doc.dump(), std::filesystem::path(SHADOWREF_SCENE_TEST_DATA) / "t.json");
  ASSERT_TRUE(s.camera.far.has_value());
  const float fovy = static_cast<float>(45.0 * std::numbers::pi / 180.0);
  EXPECT_EQ(projection_matrix<float>(s.camera, s.width, s.height).value(),
            perspective<float>(fovy, 64.0f / 48.0f, 0.1f, 50.0f, kOpenGL).value());
}

TEST(Camera, PixelCentresToNdc) {
  // docs/conventions.md: ndc.x = 2 (x + 0.5) / W − 1, ndc.y = 1 − 2 (y + 0.5) / H; row 0 is the top.
  const Vec2<double> first = pixel_to_ndc<double>(0, 0, 0.5, 0.5, 4, 2);
  EXPECT_EQ(first, Vec2<double>(-0.75, 0.5));
  const Vec2<double> last = pixel_to_ndc<double>(3, 1, 0.5, 0.5, 4, 2);
  EXPECT_EQ(last, Vec2<double>(0.75, -0.5));
}

TEST(Lights, Homogeneous) {
  Light point;
  point.position = Vec3<double>(1, 2, 3);
  EXPECT_EQ(homogeneous(point), Vec4<double>(1, 2, 3, 1));
  Light dir;
  dir.type = LightType::Directional;
  dir.direction = Vec3<double>(0, 1, 0);
  EXPECT_EQ(homogeneous(dir), Vec4<double>(0, 1, 0, 0));
  Light rect;
  rect.type = LightType::Rect;
  rect.corner = Vec3<double>(0, 5, 0);
  rect.edge_u = Vec3<double>(2, 0, 0);
  rect.edge_v = Vec3<double>(0, 0, 4);
  EXPECT_EQ(homogeneous(rect), Vec4<double>(1, 5, 2, 1));  // the centre
}

TEST(Lights, DirectionalIsNormalised) {
  auto doc = test::minimal_scene();
  doc["lights"][0] = {{"type", "directional"}, {"direction", {0, 3, 4}}};
  const Scene s = parse_scene(doc.dump(), std::filesystem::path(SHADOWREF_SCENE_TEST_DATA) / "t.json");
  EXPECT_NEAR(s.lights[0].direction.norm(), 1.0, 1e-15);  // one division: within an ulp or two
  EXPECT_NEAR(s.lights[0].direction.z(), 0.8, 1e-15);
}

// Every scene of the catalogue loads, says what it is, and states an expectation for every
// technique (the catalogue's contract with `shadowref conform`).
TEST(Catalogue, EveryScene) {
  const std::filesystem::path dir = SHADOWREF_SCENES_DIR;
  ASSERT_TRUE(std::filesystem::is_directory(dir));
  std::set<std::string> names;
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    SCOPED_TRACE(entry.path().string());
    Scene s;
    ASSERT_NO_THROW(s = load_scene(entry.path()));
    EXPECT_EQ(s.name, entry.path().stem().string()) << "the scene's name is its file name";
    EXPECT_TRUE(names.insert(s.name).second);
    EXPECT_FALSE(s.description.empty());
    // The Cornell box keeps its published millimetres and says so; every other scene is in metres.
    EXPECT_EQ(s.units.symbol, s.name == "cornell_box" ? "mm" : "m");
    for (const auto& t : outputs::kTechniques) EXPECT_EQ(s.expect.count(std::string(t.name)), 1u) << "no expectation for " << t.name;
    if (!s.has_tag("large")) {
      EXPECT_LE(static_cast<long>(s.width) * s.height, 320L * 240L * 2) << "default scenes stay modest";
    }
  }
  EXPECT_GE(count, 14);
}

}  // namespace
}  // namespace shadowref::scene
