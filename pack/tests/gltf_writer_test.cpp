// gltf_writer_test.cpp — the pack's glTF: an object's file read back by the scene's own mesh reader
// (tinygltf) as the same triangles, and the whole scene's camera, lights and nodes as the contract
// says (docs/output-contract.md, "The pack's whole-scene glTF").
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "test_scene_json.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/pack/gltf_writer.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/mesh_file.hpp"

namespace shadowref::pack {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

scene::Scene minimal() {
  json j = scene::test::minimal_scene();
  j["lights"].push_back({{"type", "spot"}, {"position", {0, 5, 0}}, {"direction", {0, -1, 0}}, {"cone_deg", 30}});
  j["lights"].push_back({{"type", "rect"}, {"corner", {-1, 6, -1}}, {"edge_u", {2, 0, 0}}, {"edge_v", {0, 0, 2}}});
  return scene::parse_scene(j.dump(), fs::current_path() / "minimal.json");
}

TEST(GltfWriter, AnObjectIsReadBackAsTheSameTriangles) {
  const scene::Scene s = minimal();
  const scene::Object& o = s.objects[1];
  const fs::path file = fs::temp_directory_path() / ("shadowref_gltf_writer_" + std::to_string(::getpid()) + ".gltf");
  std::ofstream(file) << object_gltf(o).dump();
  const TriangleMesh<double> back = scene::load_mesh_file(file);
  fs::remove(file);
  ASSERT_EQ(back.triangles.size(), o.mesh.triangles.size());
  for (std::size_t t = 0; t < back.triangles.size(); t += 7)
    for (int k = 0; k < 3; ++k) {
      const auto& a = back.positions[back.triangles[t][static_cast<std::size_t>(k)]];
      const auto& b = o.mesh.positions[o.mesh.triangles[t][static_cast<std::size_t>(k)]];
      EXPECT_EQ(static_cast<float>(a.x()), b.x());
      EXPECT_EQ(static_cast<float>(a.y()), b.y());
      EXPECT_EQ(static_cast<float>(a.z()), b.z());
    }
}

TEST(GltfWriter, NodeFacingPointsMinusZAlongForward) {
  for (const Vec3<double>& f : {Vec3<double>(1, -1, 0), Vec3<double>(0, -1, 0), Vec3<double>(0, 0, 3)}) {
    const Mat4<double> m = node_facing(Vec3<double>(1, 2, 3), f);
    const Vec3<double> minus_z = -m.block<3, 1>(0, 2);
    EXPECT_NEAR((minus_z - f.normalized()).norm(), 0.0, 1e-12) << f.transpose();
    EXPECT_NEAR((m.block<3, 3>(0, 0).determinant()), 1.0, 1e-12);  // a rotation, not a mirror
    EXPECT_EQ(m(0, 3), 1.0);
  }
}

TEST(GltfWriter, TheSceneHasEveryObjectTheCameraAndEveryLightInMaskOrder) {
  const scene::Scene s = minimal();
  const json g = scene_gltf(s);
  const json& lights = g["extensions"]["KHR_lights_punctual"]["lights"];
  ASSERT_EQ(lights.size(), 3u);
  EXPECT_EQ(lights[0]["type"], "point");
  EXPECT_EQ(lights[1]["type"], "spot");
  EXPECT_NEAR(lights[1]["spot"]["outerConeAngle"].get<double>(), 30.0 * M_PI / 180.0, 1e-15);
  EXPECT_EQ(lights[2]["type"], "point");  // a rect light: a point light at its centre
  EXPECT_EQ(lights[2]["extras"]["shadowref_type"], "rect");
  EXPECT_EQ(lights[2]["extras"]["mask_file"], "mask_2.png");
  // Nodes: the objects, the camera, the lights; the rect light's node at the parallelogram's centre.
  const json& nodes = g["nodes"];
  ASSERT_EQ(nodes.size(), s.objects.size() + 1 + 3);
  EXPECT_EQ(nodes[0]["extras"]["receiver"], true);
  EXPECT_EQ(nodes[2]["name"], "camera");
  const json& rect = nodes[5]["matrix"];
  EXPECT_EQ(rect[12], 0.0);
  EXPECT_EQ(rect[13], 6.0);
  EXPECT_EQ(rect[14], 0.0);
  // No far plane unless the scene's camera has one: glTF's infinite projection.
  EXPECT_FALSE(g["cameras"][0]["perspective"].contains("zfar"));
  EXPECT_NEAR(g["cameras"][0]["perspective"]["aspectRatio"].get<double>(), 64.0 / 48.0, 1e-15);
}

// A masked card (docs/scene-format.md, "Alpha masks"): its material is glTF's own alpha test with the
// scene's cutoff, its mask an embedded PNG read by the sampler the rule names, its vertex alpha
// COLOR_0's alpha, and every mesh carries flat normals.
TEST(GltfWriter, AMaskedCardCarriesItsMaskCutoffVertexAlphaAndNormals) {
  const fs::path dir = fs::temp_directory_path() / ("shadowref_gltf_mask_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  outputs::write_png(outputs::Image8{2, 1, 1, {0, 255}}, dir / "mask.png");  // a grey mask: no alpha channel
  json j = scene::test::minimal_scene();
  j["objects"][1] = {{"name", "card"}, {"shape", {{"type", "plane"}, {"size", {1, 1}}}},
                     {"transform", {{"translate", {0, 1, 0}}}},
                     {"uvs", {{0, 0}, {2, 0}, {2, 1}, {0, 1}}}, {"alpha_texture", "mask.png"},
                     {"vertex_alpha", {1, 0.5, 0.25, 0}}, {"alpha_cutoff", 0.3}};
  const scene::Scene s = scene::parse_scene(j.dump(), dir / "scene.json");
  const json g = scene_gltf(s);
  const json& material = g["materials"][1];
  EXPECT_EQ(material["alphaMode"], "MASK");
  EXPECT_EQ(material["alphaCutoff"], 0.3);
  EXPECT_EQ(material["doubleSided"], true);  // a masked card: alpha-tested foliage is authored double-sided
  EXPECT_FALSE(g["materials"][0].contains("doubleSided"));  // the open ground, unmasked: single-sided
  EXPECT_FALSE(g["materials"][0].contains("alphaMode"));
  const json& texture = material["pbrMetallicRoughness"]["baseColorTexture"];
  EXPECT_EQ(texture["texCoord"], 0);
  const json& sampler = g["samplers"][g["textures"][texture["index"].get<int>()]["sampler"].get<int>()];
  EXPECT_EQ(sampler["magFilter"], 9728);  // NEAREST
  EXPECT_EQ(sampler["minFilter"], 9728);
  EXPECT_EQ(sampler["wrapS"], 10497);     // REPEAT
  EXPECT_EQ(sampler["wrapT"], 10497);
  // The image: a grey + alpha PNG whose alpha is the grey mask, read back by the project's reader.
  const std::string uri = g["images"][0]["uri"];
  const std::string prefix = "data:image/png;base64,";
  ASSERT_EQ(uri.rfind(prefix, 0), 0u);
  std::string bytes;
  {
    static const std::string k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    unsigned v = 0;
    int bits = 0;
    for (const char c : uri.substr(prefix.size())) {
      if (c == '=') break;
      v = (v << 6) | static_cast<unsigned>(k.find(c));
      bits += 6;
      if (bits >= 8) {
        bits -= 8;
        bytes.push_back(static_cast<char>((v >> bits) & 0xFF));
      }
    }
  }
  std::ofstream(dir / "back.png", std::ios::binary) << bytes;
  const outputs::Image8 back = outputs::read_image8(dir / "back.png", 2);
  EXPECT_EQ(back.pixels, (std::vector<std::uint8_t>{255, 0, 255, 255}));
  // The card's mesh: flat, with NORMAL, TEXCOORD_0 and COLOR_0 per corner of each triangle.
  const json& card = g["meshes"][1]["primitives"][0]["attributes"];
  ASSERT_TRUE(card.contains("TEXCOORD_0"));
  ASSERT_TRUE(card.contains("COLOR_0"));
  EXPECT_EQ(g["accessors"][card["COLOR_0"].get<int>()]["type"], "VEC4");
  EXPECT_EQ(g["accessors"][card["TEXCOORD_0"].get<int>()]["count"], 6);  // 2 triangles × 3 corners
  for (const json& mesh : g["meshes"]) EXPECT_TRUE(mesh["primitives"][0]["attributes"].contains("NORMAL")) << mesh["name"];
  EXPECT_FALSE(g["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_0"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shadowref::pack
