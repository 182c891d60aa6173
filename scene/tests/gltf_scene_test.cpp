// gltf_scene_test.cpp — an engine team's glTF scene (gltf_scene.hpp): the camera, each light kind,
// node transforms, masks (texture alpha, COLOR_0, baseColorFactor, cutoff, samplers), the receiver,
// and one line for each thing refused or not read. The files are written by the test: a glTF
// document (nlohmann) with one external .bin buffer and, for masks, an external PNG.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "shadowref/outputs/image_io.hpp"
#include "shadowref/scene/gltf_scene.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace shadowref::scene {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Values are written as 32-bit floats and read back through double transforms: 1e-6 of the scene's
// unit (coordinates of order 1..10) is far above float rounding (~1e-7 relative) and far below any
// wrong axis or sign.
constexpr double kTol = 1e-6;

// A glTF document under construction, with one buffer written beside it as data.bin.
class Gltf {
 public:
  Gltf() {
    doc_["asset"] = {{"version", "2.0"}};
    doc_["scene"] = 0;
    doc_["scenes"] = {{{"nodes", json::array()}}};
    doc_["nodes"] = json::array();
    doc_["meshes"] = json::array();
    doc_["accessors"] = json::array();
    doc_["bufferViews"] = json::array();
  }

  json& doc() { return doc_; }

  // Appends floats (count elements of `type`) as an accessor; returns its index.
  int floats(const std::vector<float>& v, std::size_t count, const char* type) {
    const std::size_t offset = bytes_.size();
    bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float));
    doc_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", v.size() * sizeof(float)}});
    doc_["accessors"].push_back({{"bufferView", doc_["bufferViews"].size() - 1}, {"componentType", 5126}, {"count", count}, {"type", type}});
    return static_cast<int>(doc_["accessors"].size() - 1);
  }

  // A node (added to the scene's roots when `root`); returns its index.
  int node(json n, bool root = true) {
    doc_["nodes"].push_back(std::move(n));
    const int i = static_cast<int>(doc_["nodes"].size() - 1);
    if (root) doc_["scenes"][0]["nodes"].push_back(i);
    return i;
  }

  // A unit right triangle in the node's xz plane (normal +y), as a mesh with `attributes` added; returns the mesh index.
  int triangle_mesh(json primitive_extra = json::object()) {
    json attributes = {{"POSITION", floats({0, 0, 0, 0, 0, 1, 1, 0, 0}, 3, "VEC3")}};
    if (primitive_extra.contains("attributes")) attributes.update(primitive_extra["attributes"]);
    json primitive = {{"attributes", attributes}};
    for (auto& [k, v] : primitive_extra.items())
      if (k != "attributes") primitive[k] = v;
    doc_["meshes"].push_back({{"primitives", {primitive}}});
    return static_cast<int>(doc_["meshes"].size() - 1);
  }

  void camera(json node_extra = json::object(), json perspective = {{"yfov", 0.8}, {"znear", 0.5}}) {
    doc_["cameras"] = {{{"type", "perspective"}, {"perspective", perspective}}};
    json n = {{"camera", 0}, {"translation", {0, 3, 6}}};
    n.update(node_extra);
    node(n);
  }

  int light(json def, json node_extra = json::object()) {
    doc_["extensionsUsed"] = {"KHR_lights_punctual"};
    json& lights = doc_["extensions"]["KHR_lights_punctual"]["lights"];
    if (lights.is_null()) lights = json::array();
    lights.push_back(def);
    json n = {{"extensions", {{"KHR_lights_punctual", {{"light", lights.size() - 1}}}}}};
    n.update(node_extra);
    return node(n);
  }

  // A scene that loads: a camera, one point light and a triangle.
  static Gltf minimal() {
    Gltf g;
    g.camera();
    g.light({{"type", "point"}}, {{"translation", {1, 5, 1}}});
    g.node({{"name", "tri"}, {"mesh", g.triangle_mesh()}});
    return g;
  }

  // An image held in the buffer (as a .glb holds it), its bytes 4-aligned; returns the image index.
  int image_in_buffer(const std::string& png) {
    while (bytes_.size() % 4) bytes_.push_back('\0');
    doc_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bytes_.size()}, {"byteLength", png.size()}});
    bytes_ += png;
    doc_["images"].push_back({{"bufferView", doc_["bufferViews"].size() - 1}, {"mimeType", "image/png"}});
    return static_cast<int>(doc_["images"].size() - 1);
  }

  // The document as a binary .glb: the JSON chunk and the buffer as its BIN chunk, each padded to 4 bytes.
  fs::path write_glb(const std::string& stem = "level") {
    const fs::path dir = fs::path(::testing::TempDir()) / ("shadowref-gltf-scene-" + std::to_string(::getpid()) + "-" +
                                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
    std::string bin = bytes_;
    while (bin.size() % 4) bin.push_back('\0');
    doc_["buffers"] = {{{"byteLength", bin.size()}}};
    std::string text = doc_.dump();
    while (text.size() % 4) text.push_back(' ');
    const auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const std::string glb = u32(0x46546C67) + u32(2) + u32(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size())) +
                            u32(static_cast<std::uint32_t>(text.size())) + u32(0x4E4F534A) + text +
                            u32(static_cast<std::uint32_t>(bin.size())) + u32(0x004E4942) + bin;
    const fs::path file = dir / (stem + ".glb");
    std::ofstream(file, std::ios::binary) << glb;
    return file;
  }

  fs::path write(const std::string& stem = "level", const std::string& ext = ".gltf") {
    const fs::path dir = fs::path(::testing::TempDir()) / ("shadowref-gltf-scene-" + std::to_string(::getpid()) + "-" +
                                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
    std::ofstream(dir / "data.bin", std::ios::binary) << bytes_;
    doc_["buffers"] = {{{"uri", "data.bin"}, {"byteLength", bytes_.size()}}};
    const fs::path file = dir / (stem + ext);
    std::ofstream(file) << doc_.dump(1);
    return file;
  }

 private:
  json doc_;
  std::string bytes_;
};

// The SceneError's message, or "" when it loads.
std::string error_of(const fs::path& file) {
  try {
    (void)read_gltf_scene(file);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

bool mentions(const std::vector<std::string>& lines, const std::string& part) {
  for (const auto& l : lines)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

TEST(GltfScene, LoadsThroughLoadSceneWithItsStemAsName) {
  const fs::path file = Gltf::minimal().write("my_level");
  const Scene s = load_scene(file);
  EXPECT_EQ(s.name, "my_level");
  EXPECT_EQ(s.file, file);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].name, "tri");
  EXPECT_FALSE(s.objects[0].alpha);
  EXPECT_TRUE(s.expect.empty());
  EXPECT_TRUE(is_gltf_scene_file("a/B.GLB"));
  EXPECT_FALSE(is_gltf_scene_file("a/b.json"));
}

// What a catalogue folder counts as a glTF scene: a camera and a light; a mesh file has neither.
TEST(GltfScene, HoldsCameraAndLightTellsAScenesFromAMeshFile) {
  Gltf g = Gltf::minimal();
  EXPECT_TRUE(holds_camera_and_light(g.write("scene_file")));
  EXPECT_TRUE(holds_camera_and_light(g.write_glb("scene_file")));
  g.doc().erase("cameras");
  EXPECT_FALSE(holds_camera_and_light(g.write("mesh_file")));
  const fs::path junk = g.write("junk");
  std::ofstream(junk) << "{ not json";
  EXPECT_FALSE(holds_camera_and_light(junk));
  EXPECT_FALSE(holds_camera_and_light(junk.parent_path() / "absent.gltf"));
}

TEST(GltfScene, CameraLooksAlongItsNodesMinusZ) {
  Gltf g;
  // Turned 90 degrees about +y: −z becomes −x; no extras.resolution, aspectRatio 1.5 → 384 × 256.
  const double h = std::sqrt(0.5);
  g.camera({{"rotation", {0, h, 0, h}}}, {{"yfov", 0.8}, {"znear", 0.5}, {"zfar", 90.0}, {"aspectRatio", 1.5}});
  g.light({{"type", "point"}}, {{"translation", {1, 5, 1}}});
  g.node({{"mesh", g.triangle_mesh()}});
  const Scene s = read_gltf_scene(g.write()).scene;
  EXPECT_NEAR(s.camera.position.y(), 3, kTol);
  EXPECT_NEAR(s.camera.position.z(), 6, kTol);
  const Vec3<double> forward = (s.camera.target - s.camera.position).normalized();
  EXPECT_NEAR(forward.x(), -1, kTol);
  EXPECT_NEAR(s.camera.up.y(), 1, kTol);
  EXPECT_NEAR(s.camera.fovy_deg, 0.8 * 180 / std::numbers::pi, kTol);
  EXPECT_EQ(s.camera.near, 0.5);
  ASSERT_TRUE(s.camera.far);
  EXPECT_EQ(*s.camera.far, 90.0);
  EXPECT_EQ(s.width, 384);
  EXPECT_EQ(s.height, kGltfDefaultHeight);
}

TEST(GltfScene, ResolutionFromTheCameraNodesExtrasAndFarAbsentIsInfinite) {
  Gltf g = Gltf::minimal();
  g.doc()["nodes"][0]["extras"] = {{"resolution", {320, 200}}};
  const Scene s = read_gltf_scene(g.write()).scene;
  EXPECT_EQ(s.width, 320);
  EXPECT_EQ(s.height, 200);
  EXPECT_FALSE(s.camera.far);
  g.doc()["cameras"][0]["perspective"]["aspectRatio"] = 1.0;  // 320 / 200 = 1.6, 120 pixels off
  EXPECT_NE(error_of(g.write()).find("aspectRatio 1.000000 disagrees with extras.resolution 320x200"), std::string::npos);
}

TEST(GltfScene, FirstCameraInWalkOrderUnderParentTransforms) {
  Gltf g;
  g.doc()["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
                        {{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.1}}}}};
  const int child = g.node({{"camera", 1}, {"translation", {0, 0, 4}}}, false);
  g.node({{"translation", {10, 0, 0}}, {"children", {child}}});  // walked first: its child's camera wins
  g.node({{"camera", 0}, {"translation", {0, 1, 9}}});
  g.light({{"type", "point"}}, {{"translation", {1, 5, 1}}});
  g.node({{"mesh", g.triangle_mesh()}});
  const Scene s = read_gltf_scene(g.write()).scene;
  EXPECT_NEAR(s.camera.position.x(), 10, kTol);
  EXPECT_NEAR(s.camera.position.z(), 4, kTol);
  EXPECT_NEAR(s.camera.fovy_deg, 0.9 * 180 / std::numbers::pi, kTol);
}

TEST(GltfScene, EveryLightKindWithItsNodesTransform) {
  Gltf g;
  g.camera();
  // Rotated −90 degrees about x: the node's −z points down (−y).
  const double h = std::sqrt(0.5);
  const json down = {0, 0, 0, 1};
  const json rot_down = {-h, 0, 0, h};
  g.light({{"type", "directional"}}, {{"rotation", rot_down}});
  g.light({{"type", "point"}, {"intensity", 40}, {"color", {1, 0, 0}}}, {{"translation", {1, 2, 3}}});
  g.light({{"type", "spot"}, {"spot", {{"outerConeAngle", 0.5}}}}, {{"translation", {0, 4, 0}}, {"rotation", rot_down}});
  g.light({{"type", "point"},
           {"extras", {{"shadowref_type", "rect"}, {"corner", {-1, 6, -1}}, {"edge_u", {2, 0, 0}}, {"edge_v", {0, 0, 2}}, {"samples", 3}}}},
          {{"translation", {0, 6, 0}}});
  (void)down;
  g.node({{"mesh", g.triangle_mesh()}});
  const Scene s = read_gltf_scene(g.write()).scene;
  ASSERT_EQ(s.lights.size(), 4u);
  EXPECT_EQ(s.lights[0].type, LightType::Directional);
  EXPECT_NEAR(s.lights[0].direction.y(), 1, kTol);  // toward the light: up, since it shines down
  EXPECT_EQ(s.lights[1].type, LightType::Point);
  EXPECT_NEAR((s.lights[1].position - Vec3<double>(1, 2, 3)).norm(), 0, kTol);
  EXPECT_EQ(s.lights[2].type, LightType::Spot);
  EXPECT_NEAR(s.lights[2].direction.y(), -1, kTol);  // the axis it shines along
  EXPECT_NEAR(s.lights[2].cone_deg, 0.5 * 180 / std::numbers::pi, kTol);
  EXPECT_EQ(s.lights[3].type, LightType::Rect);
  EXPECT_EQ(s.lights[3].samples, 3);
  EXPECT_NEAR((s.lights[3].edge_u - Vec3<double>(2, 0, 0)).norm(), 0, kTol);
}

TEST(GltfScene, RectLightNodeAwayFromItsCentreIsRefused) {
  Gltf g;
  g.camera();
  // The parallelogram written in the node's own frame (centred on its origin) by mistake.
  g.light({{"type", "point"},
           {"extras", {{"shadowref_type", "rect"}, {"corner", {-1, 0, -1}}, {"edge_u", {2, 0, 0}}, {"edge_v", {0, 0, 2}}}}},
          {{"translation", {0, 6, 0}}});
  g.node({{"mesh", g.triangle_mesh()}});
  EXPECT_NE(error_of(g.write()).find("its node must sit at its centre"), std::string::npos) << error_of(g.write());
}

TEST(GltfScene, NodeTransformsAndMirroringKeepCounterClockwiseOutside) {
  Gltf g = Gltf::minimal();
  const int mesh = g.triangle_mesh();
  const int child = g.node({{"name", "mirrored"}, {"mesh", mesh}, {"scale", {1, -1, 1}}}, false);
  g.node({{"translation", {0, 2, 0}}, {"children", {child}}});
  const Scene s = read_gltf_scene(g.write()).scene;
  ASSERT_EQ(s.objects.size(), 2u);
  const auto& m = s.objects[1].mesh;
  EXPECT_NEAR(m.positions[0].y(), 2, kTol);
  // The triangle's normal was +y; mirrored in y it faces −y, and its winding is flipped so the normal follows.
  const Vec3<float> n = (m.positions[m.triangles[0][1]] - m.positions[m.triangles[0][0]])
                            .cross(m.positions[m.triangles[0][2]] - m.positions[m.triangles[0][0]]);
  EXPECT_LT(n.y(), 0);
}

// A 2 × 1 grey + alpha PNG beside the glTF, texel alphas 0 and 200, as a MASK material's baseColorTexture.
int add_mask_material(Gltf& g, const fs::path& dir, double cutoff, json sampler = json::object()) {
  outputs::Image8 png{2, 1, 2, {255, 0, 255, 200}};
  fs::create_directories(dir);
  std::ofstream(dir / "mask.png", std::ios::binary) << outputs::encode_png(png);
  g.doc()["images"] = {{{"uri", "mask.png"}}};
  g.doc()["textures"] = {{{"source", 0}}};
  if (!sampler.empty()) {
    g.doc()["samplers"] = {sampler};
    g.doc()["textures"][0]["sampler"] = 0;
  }
  g.doc()["materials"] = {{{"alphaMode", "MASK"}, {"alphaCutoff", cutoff},
                           {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.4, 0.6, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}}};
  return 0;
}

fs::path test_dir() {
  return fs::path(::testing::TempDir()) / ("shadowref-gltf-scene-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

TEST(GltfScene, MaskMaterialGivesTheAlphaMask) {
  Gltf g;
  g.camera();
  g.light({{"type", "point"}}, {{"translation", {1, 5, 1}}});
  add_mask_material(g, test_dir(), 0.3);
  const int uv = g.floats({0.25f, 0, 0.25f, 1, 0.75f, 0}, 3, "VEC2");
  const int colour = g.floats({1, 1, 1, 1, 1, 1, 1, 0.5f, 1, 1, 1, 0.25f}, 3, "VEC4");
  g.node({{"name", "card"}, {"mesh", g.triangle_mesh({{"attributes", {{"TEXCOORD_0", uv}, {"COLOR_0", colour}}}, {"material", 0}})}});
  const GltfScene r = read_gltf_scene(g.write());
  ASSERT_EQ(r.scene.objects.size(), 1u);
  const Object& o = r.scene.objects[0];
  ASSERT_TRUE(o.alpha);
  EXPECT_EQ(o.alpha->cutoff, 0.3);
  EXPECT_EQ(o.alpha->texture->width, 2);
  EXPECT_EQ(o.alpha->texture->alpha, (std::vector<std::uint8_t>{0, 200}));  // the PNG's alpha channel
  EXPECT_EQ(o.alpha->uvs[2], Vec2<float>(0.75f, 0));
  EXPECT_TRUE(o.alpha->has_vertex_alpha);
  EXPECT_EQ(o.alpha->vertex_alpha, (std::vector<float>{1, 0.5f, 0.25f}));
  EXPECT_NEAR(o.color.z(), 0.6, kTol);
  EXPECT_TRUE(r.not_read.empty()) << r.not_read.front();
}

// A binary .glb whose mask image lies in its BIN chunk (a buffer view, read range-checked).
TEST(GltfScene, GlbWithItsMaskInTheBinaryChunk) {
  Gltf g;
  g.camera();
  g.light({{"type", "directional"}});
  g.doc()["images"] = json::array();
  const int image = g.image_in_buffer(outputs::encode_png(outputs::Image8{2, 1, 2, {255, 7, 255, 9}}));
  g.doc()["textures"] = {{{"source", image}}};
  g.doc()["materials"] = {{{"alphaMode", "MASK"}, {"alphaCutoff", 0.25}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  const int uv = g.floats({0, 0, 0, 1, 1, 0}, 3, "VEC2");
  g.node({{"name", "card"}, {"mesh", g.triangle_mesh({{"attributes", {{"TEXCOORD_0", uv}}}, {"material", 0}})}});
  const fs::path file = g.write_glb("binary_level");
  const Scene s = load_scene(file);
  EXPECT_EQ(s.name, "binary_level");
  ASSERT_EQ(s.objects.size(), 1u);
  ASSERT_TRUE(s.objects[0].alpha);
  EXPECT_EQ(s.objects[0].alpha->texture->alpha, (std::vector<std::uint8_t>{7, 9}));
  EXPECT_EQ(s.objects[0].alpha->cutoff, 0.25);
  // The image's buffer view claiming bytes past the buffer's end: one line, no read outside it.
  g.doc()["bufferViews"][g.doc()["images"][0]["bufferView"].get<std::size_t>()]["byteLength"] = 1 << 20;
  const std::string e = error_of(g.write_glb("binary_level"));
  EXPECT_NE(e.find("past the end of its buffer"), std::string::npos) << e;
}

TEST(GltfScene, MaskCutoffDefaultsToOneHalfAndFactorAlphaIsVertexAlpha) {
  Gltf g = Gltf::minimal();
  g.doc()["materials"] = {{{"alphaMode", "MASK"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.4}}}}}};
  g.doc()["meshes"][0]["primitives"][0]["material"] = 0;
  const Object o = read_gltf_scene(g.write()).scene.objects[0];
  ASSERT_TRUE(o.alpha);
  EXPECT_EQ(o.alpha->cutoff, 0.5);  // glTF's default alphaCutoff
  EXPECT_EQ(o.alpha->vertex_alpha, (std::vector<float>(3, 0.4f)));
  EXPECT_EQ(o.alpha->texture->width, 1);  // vertex alpha only: one texel of 255
}

TEST(GltfScene, SamplersLinearIsSaidClampOutsideTheUnitSquareIsRefused) {
  Gltf g;
  g.camera();
  g.light({{"type", "point"}}, {{"translation", {1, 5, 1}}});
  add_mask_material(g, test_dir(), 0.5, {{"magFilter", 9729}, {"minFilter", 9987}});
  const int uv = g.floats({0, 0, 0, 1, 1, 0}, 3, "VEC2");
  g.node({{"mesh", g.triangle_mesh({{"attributes", {{"TEXCOORD_0", uv}}}, {"material", 0}})}});
  const GltfScene r = read_gltf_scene(g.write());
  EXPECT_TRUE(mentions(r.not_read, "the nearest texel")) << (r.not_read.empty() ? "" : r.not_read.front());
  // CLAMP_TO_EDGE with coordinates in [0, 1]: the same texels, accepted; with 1.5: refused.
  g.doc()["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33071}}};
  EXPECT_EQ(error_of(g.write()), "");
  const int far_uv = g.floats({0, 0, 0, 1, 1.5f, 0}, 3, "VEC2");
  g.doc()["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = far_uv;
  EXPECT_NE(error_of(g.write()).find("the suite's rule wraps (REPEAT)"), std::string::npos);
}

TEST(GltfScene, OtherTexturesAndBlendAreSaidOnce) {
  Gltf g = Gltf::minimal();
  g.doc()["images"] = {{{"uri", "data:image/png;base64,AAAA"}}};
  g.doc()["textures"] = {{{"source", 0}}};
  g.doc()["materials"] = {{{"alphaMode", "BLEND"}, {"normalTexture", {{"index", 0}}}, {"occlusionTexture", {{"index", 0}}}}};
  g.doc()["meshes"][0]["primitives"][0]["material"] = 0;
  const GltfScene r = read_gltf_scene(g.write());
  ASSERT_EQ(r.not_read.size(), 2u);
  EXPECT_TRUE(mentions(r.not_read, "2 texture reference(s) other than MASK materials' baseColorTexture ignored"));
  EXPECT_TRUE(mentions(r.not_read, "alphaMode BLEND is read as OPAQUE"));
  EXPECT_FALSE(r.scene.objects[0].alpha);
}

TEST(GltfScene, ReceiverFromNodeExtras) {
  Gltf g = Gltf::minimal();
  g.doc()["nodes"][2]["extras"] = {{"receiver", true}, {"shape", "plane"}};
  const Scene s = read_gltf_scene(g.write()).scene;
  ASSERT_TRUE(s.receiver_index());
  EXPECT_EQ(*s.receiver_index(), 0u);
  g.doc()["nodes"][2]["extras"]["receiver"] = "yes";
  EXPECT_NE(error_of(g.write()).find("nodes[2].extras.receiver"), std::string::npos) << error_of(g.write());
}

// glTF's unit is the metre; the pack's scene in another one says so in its scene's extras.units.
TEST(GltfScene, UnitsFromTheScenesExtrasElseMetres) {
  Gltf g = Gltf::minimal();
  EXPECT_EQ(read_gltf_scene(g.write()).scene.units.symbol, "m");
  g.doc()["scenes"][0]["extras"] = {{"units", "mm"}, {"metres_per_unit", 0.001}};
  EXPECT_EQ(read_gltf_scene(g.write()).scene.units.symbol, "mm");
  g.doc()["scenes"][0]["extras"]["units"] = "furlong";
  EXPECT_NE(error_of(g.write()).find("scenes[0].extras.units: must be one of m, cm, mm"), std::string::npos) << error_of(g.write());
}

// Each refusal: one line naming the file and what is wrong.
struct Refusal {
  const char* name;
  void (*spoil)(Gltf&);
  const char* says;
};

const Refusal kRefusals[] = {
    {"no_camera", [](Gltf& g) { g.doc()["nodes"][0].erase("camera"); }, "no camera"},
    {"orthographic", [](Gltf& g) { g.doc()["cameras"][0] = {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 9}}}}; },
     "only perspective cameras are read"},
    {"no_light", [](Gltf& g) { g.doc()["nodes"][1].erase("extensions"); }, "no light"},
    {"no_mesh", [](Gltf& g) { g.doc()["nodes"][2].erase("mesh"); }, "no triangles"},
    {"skin_without_weights", [](Gltf& g) { g.doc()["skins"] = {{{"joints", {1}}}}; g.doc()["nodes"][2]["skin"] = 0; },
     "a primitive of a skinned mesh lacks JOINTS_0 or WEIGHTS_0"},
    {"required_extension", [](Gltf& g) { g.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression"}; g.doc()["extensionsUsed"] = {"KHR_draco_mesh_compression"}; },
     "extensionsRequired names KHR_draco_mesh_compression"},
    {"lines", [](Gltf& g) { g.doc()["meshes"][0]["primitives"][0]["mode"] = 1; }, "only TRIANGLES (4) is supported"},
    {"light_missing", [](Gltf& g) { g.doc()["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 7; }, "light 7 does not exist"},
    {"cutoff_above_one", [](Gltf& g) { g.doc()["materials"] = {{{"alphaMode", "MASK"}, {"alphaCutoff", 1.5}}}; g.doc()["meshes"][0]["primitives"][0]["material"] = 0; },
     "alphaCutoff must be in [0, 1]"},
    {"mask_outside",
     [](Gltf& g) {
       g.doc()["images"] = {{{"uri", "../outside.png"}}};
       g.doc()["textures"] = {{{"source", 0}}};
       g.doc()["materials"] = {{{"alphaMode", "MASK"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
       g.doc()["meshes"][0]["primitives"][0]["material"] = 0;
     },
     "cannot be read (a missing file, or one outside the glTF file's folder)"},
    {"jpeg_mask",
     [](Gltf& g) {
       g.doc()["images"] = {{{"uri", "data:image/jpeg;base64,AAAA"}, {"mimeType", "image/jpeg"}}};
       g.doc()["textures"] = {{{"source", 0}}};
       g.doc()["materials"] = {{{"alphaMode", "MASK"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
       g.doc()["meshes"][0]["primitives"][0]["material"] = 0;
     },
     "only PNG masks are read"},
    {"broken", [](Gltf& g) { g.doc()["accessors"][0]["count"] = "three"; }, "cannot parse glTF"},
};

TEST(GltfScene, RefusalsAreOneLineNamingTheFile) {
  for (const Refusal& r : kRefusals) {
    Gltf g = Gltf::minimal();
    r.spoil(g);
    const fs::path file = g.write(std::string("bad_") + r.name);
    const std::string e = error_of(file);
    EXPECT_EQ(e.rfind(file.string() + ": ", 0), 0u) << r.name << ": " << e;
    EXPECT_NE(e.find(r.says), std::string::npos) << r.name << ": " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << r.name << ": " << e;
  }
}

TEST(GltfScene, NameMustBeASafeIdentifier) {
  const std::string e = error_of(Gltf::minimal().write("my level"));
  EXPECT_NE(e.find("the scene's name is the file's stem 'my level'"), std::string::npos) << e;
}

}  // namespace
}  // namespace shadowref::scene
