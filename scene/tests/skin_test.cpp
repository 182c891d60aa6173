// skin_test.cpp — glTF skins posed by linear blend skinning (skin.hpp): a two-joint skin whose pose
// is computed here by hand (not by the code under test), read as a mesh file, through a catalogue
// scene's pose_time, and as an engine team's glTF scene; the catalogue's character closed and posed.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "shadowref/scene/gltf_scene.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/mesh_file.hpp"
#include <nlohmann/json.hpp>

#include "shadowref/adjacency.hpp"

namespace shadowref::scene {
namespace {

const std::filesystem::path kData = SHADOWREF_SCENE_TEST_DATA;
const std::filesystem::path kScenes = SHADOWREF_SCENES_DIR;

// two_joints.gltf: joint a at the origin, its child b at (1, 0, 0) (inverse bind: translate(-1, 0, 0));
// the animation moves a to (0, 2, 0) and turns b by 90 degrees about z between t = 0 and t = 1, and
// its extras.pose_time is 0.5. The mesh node sits at (5, 5, 5), which glTF says not to apply.
// Vertices: (0.5, 0, 0) on a alone, (2, 0, 0) on b alone, (1, 1, 0) half and half.
// By hand at t = 0.5: G_a = T(0, 1, 0); G_b = G_a · T(1, 0, 0) · R_z(45°).
//   v0 = G_a · v0 = (0.5, 1, 0)
//   v1 = G_b · IBM_b · v1 = G_b · (1, 0, 0) = (1 + cos 45°, 1 + sin 45°, 0)
//   v2 = ½ G_a · v2 + ½ G_b · (0, 1, 0) = ½ (1, 2, 0) + ½ (1 − sin 45°, 1 + cos 45°, 0)
const double kS = std::sqrt(0.5);
const Vec3<double> kPosed[3] = {{0.5, 1, 0}, {1 + kS, 1 + kS, 0}, {0.5 * (1 + 1 - kS), 0.5 * (2 + 1 + kS), 0}};

void expect_near(const Vec3<double>& got, const Vec3<double>& want, const char* what) {
  EXPECT_LT((got - want).norm(), 1e-6) << what << ": got " << got.transpose() << ", want " << want.transpose();
}

TEST(Skin, TwoJointsPosedAsComputedByHand) {
  const PosedMesh m = load_posed_mesh_file(kData / "two_joints.gltf");
  ASSERT_EQ(m.mesh.positions.size(), 3u);
  ASSERT_TRUE(m.skin);
  ASSERT_EQ(m.skin->joints.size(), 2u);
  for (int i = 0; i < 3; ++i) expect_near(m.mesh.positions[static_cast<std::size_t>(i)], kPosed[i], "vertex");
  for (std::size_t i = 0; i < 3; ++i) expect_near(pose_vertex(*m.skin, i), m.mesh.positions[i], "pose_vertex");
  // The bind pose as stored, at t = 0 (no rotation, a at the origin).
  const PosedMesh bind = load_posed_mesh_file(kData / "two_joints.gltf", 0.0);
  expect_near(bind.mesh.positions[0], {0.5, 0, 0}, "t = 0");
  expect_near(bind.mesh.positions[1], {2, 0, 0}, "t = 0");
  expect_near(bind.mesh.positions[2], {1, 1, 0}, "t = 0");
  // After the last key: the last value (a at (0, 2, 0), b turned by 90 degrees).
  const PosedMesh late = load_posed_mesh_file(kData / "two_joints.gltf", 7.0);
  expect_near(late.mesh.positions[1], {1, 3, 0}, "t = 7");
}

TEST(Skin, CatalogueObjectTransformIsInFrontOfEveryJoint) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "shadowref_skin_test";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(kData / "two_joints.gltf", dir / "two_joints.gltf", std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "s.json") << R"({"name": "s", "camera": {"position": [0, 1, 8], "target": [0, 1, 0]},
    "lights": [{"type": "point", "position": [0, 5, 5]}],
    "objects": [{"name": "m", "shape": {"type": "mesh", "file": "two_joints.gltf", "pose_time": 0.5},
                 "transform": {"translate": [10, 0, 0]}}]})";
  const Scene s = load_scene(dir / "s.json");
  const Object& o = s.objects[0];
  ASSERT_TRUE(o.skin);
  for (std::size_t i = 0; i < 3; ++i) {
    expect_near(o.mesh.positions[i].cast<double>(), kPosed[i] + Vec3<double>(10, 0, 0), "posed and moved");
    expect_near(pose_vertex(*o.skin, i), kPosed[i] + Vec3<double>(10, 0, 0), "the skin's joints carry the transform");
  }
  EXPECT_TRUE(o.skin->bind_to_world.isApprox(Eigen::Matrix4d(Eigen::Affine3d(Eigen::Translation3d(10, 0, 0)).matrix())));
  std::ofstream(dir / "bad.json") << R"({"name": "bad", "camera": {"position": [0, 1, 8], "target": [0, 1, 0]},
    "lights": [{"type": "point", "position": [0, 5, 5]}],
    "objects": [{"shape": {"type": "mesh", "file": "two_joints.gltf", "pose_time": -1}}]})";
  try {
    (void)load_scene(dir / "bad.json");
    ADD_FAILURE() << "a negative pose_time was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("objects[0].shape.pose_time: must be >= 0"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(Skin, GltfSceneReadsTheSkinAtItsPose) {
  // two_joints.gltf with a camera and a light: an engine team's skinned scene.
  std::ifstream in(kData / "two_joints.gltf");
  nlohmann::json g = nlohmann::json::parse(in);
  g["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
  g["nodes"].push_back({{"camera", 0}, {"translation", {0, 1, 8}}});
  g["extensionsUsed"] = {"KHR_lights_punctual"};
  g["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}}}}}}};
  g["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}, {"translation", {0, 5, 5}}});
  g["scenes"][0]["nodes"] = {0, 1, 3, 4};
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "shadowref_skinned_scene.gltf";
  std::ofstream(file) << g.dump();
  const GltfScene r = read_gltf_scene(file);
  ASSERT_EQ(r.scene.objects.size(), 1u);
  const Object& o = r.scene.objects[0];
  ASSERT_TRUE(o.skin);
  for (std::size_t i = 0; i < 3; ++i) expect_near(o.mesh.positions[i].cast<double>(), kPosed[i], "glTF scene");
  // Without the animation: every node at its own transform (the bind pose here).
  g.erase("animations");
  std::ofstream(file) << g.dump();
  const Object still = read_gltf_scene(file).scene.objects[0];
  expect_near(still.mesh.positions[1].cast<double>(), {2, 0, 0}, "no animation");
  std::filesystem::remove(file);
}

TEST(Skin, Refusals) {
  std::ifstream in(kData / "two_joints.gltf");
  const nlohmann::json base = nlohmann::json::parse(in);
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "shadowref_bad_skin.gltf";
  const auto error_of = [&](const nlohmann::json& g) -> std::string {
    std::ofstream(file) << g.dump();
    try {
      (void)load_posed_mesh_file(file);
    } catch (const MeshFileError& e) {
      return e.what();
    }
    return "";
  };
  nlohmann::json g = base;
  g["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0");
  EXPECT_NE(error_of(g).find("lacks JOINTS_0 or WEIGHTS_0"), std::string::npos) << error_of(g);
  g = base;
  g["skins"][0]["joints"] = {1, 9};
  EXPECT_NE(error_of(g).find("does not exist"), std::string::npos) << error_of(g);
  g = base;
  g["animations"][0]["channels"][0]["target"]["path"] = "weights";
  EXPECT_NE(error_of(g).find("morph target weights"), std::string::npos) << error_of(g);
  g = base;
  g["animations"][0]["extras"]["pose_time"] = -1;
  EXPECT_NE(error_of(g).find("pose_time must be finite and >= 0"), std::string::npos) << error_of(g);
  g = base;
  g["skins"][0]["joints"] = {1};  // vertex 1 names joint 1 of 1
  EXPECT_NE(error_of(g).find("names joint 1 of 1"), std::string::npos) << error_of(g);
  std::filesystem::remove(file);
}

// The catalogue's character: closed (each part a closed tube), posed away from its bind pose.
TEST(Skin, CatalogueCharacterIsClosedAndPosed) {
  const PosedMesh posed = load_posed_mesh_file(kScenes / "meshes" / "character.gltf");
  const PosedMesh bind = load_posed_mesh_file(kScenes / "meshes" / "character.gltf", 0.0);
  ASSERT_TRUE(posed.skin);
  EXPECT_EQ(posed.skin->joints.size(), 11u);
  const auto adjacency = build_adjacency(posed.mesh);
  ASSERT_TRUE(adjacency.ok());
  EXPECT_TRUE(adjacency.value().report.closed_manifold());
  double moved = 0;
  for (std::size_t i = 0; i < posed.mesh.positions.size(); ++i)
    moved = std::max(moved, (posed.mesh.positions[i] - bind.mesh.positions[i]).norm());
  EXPECT_GT(moved, 0.3);  // the hands and feet move by tens of centimetres
  for (std::size_t i = 0; i < bind.mesh.positions.size(); ++i)
    expect_near(bind.mesh.positions[i], bind.skin->bind_positions[i].cast<double>(), "t = 0 is the bind pose");
}

}  // namespace
}  // namespace shadowref::scene
