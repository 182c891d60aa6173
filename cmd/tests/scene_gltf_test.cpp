// scene_gltf_test.cpp — the pack's whole-scene glTF (<scene>/scene.gltf), loaded with tinygltf as
// an engine's glTF loader would, against the pack's matrices.json: the camera's view and
// projection (rebuilt from the glTF camera as the glTF specification defines it), every object's
// mesh and colour, every light's kind, position, direction and cone. Point, spot, directional and
// rect lights are each covered by one exported scene.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "run_command.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Mat = std::array<std::array<double, 4>, 4>;  // [row][column]

// The matrices are written with 17 significant digits and read back exactly; what the glTF side
// computes (the view as the inverse of the camera node's matrix, the projection from yfov and
// aspectRatio) goes through a few roundings of values of order 1..100 (scene coordinates): 1e-9
// is far above those and far below anything a wrong matrix would show.
constexpr double kTol = 1e-9;

Mat from_rows(const json& rows) {
  Mat m{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[r][c] = rows[r][c].get<double>();
  return m;
}

// glTF's node.matrix is column-major.
Mat node_matrix(const tinygltf::Node& n) {
  EXPECT_EQ(n.matrix.size(), 16u) << n.name << ": the pack gives every camera and light node a matrix";
  Mat m{};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) m[r][c] = n.matrix.size() == 16 ? n.matrix[static_cast<std::size_t>(4 * c + r)] : 0.0;
  return m;
}

// The inverse of a rigid transform [R t; 0 1]: [Rᵀ −Rᵀt; 0 1]. Checks it is rigid (glTF requires a
// node matrix to decompose into rotation and translation; a light's or camera's must not scale).
Mat rigid_inverse(const Mat& m, const std::string& what) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double dot = 0;
      for (int k = 0; k < 3; ++k) dot += m[k][i] * m[k][j];
      EXPECT_NEAR(dot, i == j ? 1.0 : 0.0, kTol) << what << ": columns " << i << ", " << j << " orthonormal";
    }
  EXPECT_EQ(m[3][0], 0.0);
  EXPECT_EQ(m[3][1], 0.0);
  EXPECT_EQ(m[3][2], 0.0);
  EXPECT_EQ(m[3][3], 1.0);
  Mat inv{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) inv[r][c] = m[c][r];
    inv[r][3] = -(m[0][r] * m[0][3] + m[1][r] * m[1][3] + m[2][r] * m[2][3]);
  }
  inv[3][3] = 1.0;
  return inv;
}

void expect_matrix_near(const Mat& a, const Mat& b, const std::string& what) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(a[r][c], b[r][c], kTol) << what << " (" << r << ", " << c << ")";
}

void expect_vec_near(const std::array<double, 3>& a, const json& b, const std::string& what) {
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k].get<double>(), kTol) << what << " [" << k << "]";
}

std::array<double, 3> column(const Mat& m, int c) { return {m[0][c], m[1][c], m[2][c]}; }

// The glTF specification's perspective projection (Appendix: "Projection Matrices"): infinite when
// zfar is absent, finite otherwise; OpenGL clip depth −1..1, right-handed, as the pack's gl convention.
Mat gltf_projection(const tinygltf::PerspectiveCamera& p) {
  const double t = std::tan(0.5 * p.yfov);
  Mat m{};
  m[0][0] = 1.0 / (p.aspectRatio * t);
  m[1][1] = 1.0 / t;
  m[3][2] = -1.0;
  if (p.zfar > 0) {
    m[2][2] = (p.zfar + p.znear) / (p.znear - p.zfar);
    m[2][3] = 2.0 * p.zfar * p.znear / (p.znear - p.zfar);
  } else {
    m[2][2] = -1.0;
    m[2][3] = -2.0 * p.znear;
  }
  return m;
}

tinygltf::Model load(const fs::path& file) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
  EXPECT_TRUE(ok) << file << ": " << err;
  EXPECT_EQ(err, "") << file;
  EXPECT_EQ(warn, "") << file;
  return model;
}

// The bytes an accessor covers (tightly packed, as the pack writes them).
std::string accessor_bytes(const tinygltf::Model& m, int index) {
  const tinygltf::Accessor& a = m.accessors.at(static_cast<std::size_t>(index));
  const tinygltf::BufferView& v = m.bufferViews.at(static_cast<std::size_t>(a.bufferView));
  const std::vector<unsigned char>& b = m.buffers.at(static_cast<std::size_t>(v.buffer)).data;
  const std::size_t start = v.byteOffset + a.byteOffset;
  const std::size_t size = a.count * static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type))) *
                           static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
  EXPECT_LE(start + size, b.size());
  return std::string(reinterpret_cast<const char*>(b.data()) + start, std::min(size, b.size() - std::min(start, b.size())));
}

double number(const tinygltf::Value& v, const std::string& key) {
  EXPECT_TRUE(v.Has(key)) << key;
  return v.Get(key).GetNumberAsDouble();
}

void check_scene(const fs::path& pack, const std::string& scene) {
  SCOPED_TRACE(scene);
  const fs::path dir = pack / scene;
  std::ifstream in(dir / "matrices.json");
  const json m = json::parse(in);
  EXPECT_EQ(m["scene_gltf"], "scene.gltf");
  const json& gl = m["conventions"]["gl"];
  const tinygltf::Model g = load(dir / "scene.gltf");
  ASSERT_EQ(g.scenes.size(), 1u);
  ASSERT_EQ(g.defaultScene, 0);
  // Every node is a root of the scene: nothing inherits a parent's transform.
  ASSERT_EQ(g.scenes[0].nodes.size(), g.nodes.size());

  // The camera.
  ASSERT_EQ(g.cameras.size(), 1u);
  ASSERT_EQ(g.cameras[0].type, "perspective");
  const tinygltf::PerspectiveCamera& p = g.cameras[0].perspective;
  EXPECT_NEAR(p.yfov, m["camera"]["fovy_deg"].get<double>() * std::numbers::pi / 180.0, 1e-15);
  EXPECT_DOUBLE_EQ(p.aspectRatio, m["resolution"][0].get<double>() / m["resolution"][1].get<double>());
  EXPECT_EQ(p.znear, m["camera"]["near"].get<double>());
  ASSERT_EQ(m["camera"]["far"], "infinite") << "the catalogue's cameras are infinite; a finite one gets zfar";
  EXPECT_EQ(p.zfar, 0.0) << "no zfar: an infinite projection, as the pack's";
  const tinygltf::Node* camera = nullptr;
  for (const tinygltf::Node& n : g.nodes)
    if (n.camera == 0) camera = &n;
  ASSERT_NE(camera, nullptr);
  expect_matrix_near(rigid_inverse(node_matrix(*camera), "camera"), from_rows(gl["view"]["canonical"]), "camera view");
  expect_matrix_near(gltf_projection(p), from_rows(gl["projection"]["canonical"]), "camera projection");
  // extras: the exact matrices, bit for bit.
  for (const char* key : {"view", "projection", "projection_finite"}) {
    const tinygltf::Value& rows = camera->extras.Get(key);
    ASSERT_TRUE(rows.IsArray()) << key;
    const json& want = gl[key]["canonical"];
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) EXPECT_EQ(rows.Get(r).Get(c).GetNumberAsDouble(), want[r][c].get<double>()) << key;
  }

  // The objects: in matrices.json's order, no transform (world space), the very mesh of the
  // object's own glTF, its colour.
  const json& objects = m["objects"];
  std::vector<const tinygltf::Node*> mesh_nodes;
  for (const tinygltf::Node& n : g.nodes)
    if (n.mesh >= 0) mesh_nodes.push_back(&n);
  ASSERT_EQ(mesh_nodes.size(), objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const tinygltf::Node& n = *mesh_nodes[i];
    const json& o = objects[i];
    EXPECT_EQ(n.name, o["name"].get<std::string>());
    EXPECT_TRUE(n.matrix.empty() && n.translation.empty() && n.rotation.empty() && n.scale.empty()) << n.name << ": world space";
    const tinygltf::Primitive& prim = g.meshes.at(static_cast<std::size_t>(n.mesh)).primitives.at(0);
    const tinygltf::Model own = load(dir / o["gltf"].get<std::string>());
    const tinygltf::Primitive& own_prim = own.meshes.at(0).primitives.at(0);
    EXPECT_EQ(accessor_bytes(g, prim.attributes.at("POSITION")), accessor_bytes(own, own_prim.attributes.at("POSITION"))) << n.name;
    EXPECT_EQ(accessor_bytes(g, prim.indices), accessor_bytes(own, own_prim.indices)) << n.name;
    EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
    ASSERT_GE(prim.material, 0);
    const std::vector<double>& colour = g.materials.at(static_cast<std::size_t>(prim.material)).pbrMetallicRoughness.baseColorFactor;
    for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(static_cast<float>(colour[k]), o["color"][k].get<float>()) << n.name;
    EXPECT_EQ(n.extras.Get("receiver").Get<bool>(), o["receiver"].get<bool>()) << n.name;
  }

  // The lights, in the masks' order.
  const json& lights = m["lights"];
  ASSERT_EQ(g.lights.size(), lights.size());
  std::vector<const tinygltf::Node*> light_nodes(lights.size(), nullptr);
  for (const tinygltf::Node& n : g.nodes) {
    const auto e = n.extensions.find("KHR_lights_punctual");
    if (e == n.extensions.end()) continue;
    const int index = e->second.Get("light").GetNumberAsInt();
    ASSERT_GE(index, 0);
    ASSERT_LT(static_cast<std::size_t>(index), lights.size());
    light_nodes[static_cast<std::size_t>(index)] = &n;
  }
  for (std::size_t i = 0; i < lights.size(); ++i) {
    SCOPED_TRACE("light " + std::to_string(i));
    ASSERT_NE(light_nodes[i], nullptr);
    const json& l = lights[i];
    const tinygltf::Light& gl_light = g.lights[i];
    const Mat at = node_matrix(*light_nodes[i]);
    rigid_inverse(at, "light node");
    const std::string type = l["type"];
    EXPECT_EQ(gl_light.extras.Get("shadowref_type").Get<std::string>(), type);
    EXPECT_EQ(gl_light.extras.Get("mask_file").Get<std::string>(), l["mask_file"].get<std::string>());
    // glTF lights shine along their node's −z.
    const std::array<double, 3> shines = {-at[0][2], -at[1][2], -at[2][2]};
    if (type == "point") {
      EXPECT_EQ(gl_light.type, "point");
      expect_vec_near(column(at, 3), l["position"], "position");
    } else if (type == "spot") {
      EXPECT_EQ(gl_light.type, "spot");
      expect_vec_near(column(at, 3), l["position"], "position");
      expect_vec_near(shines, l["direction"], "direction");
      EXPECT_NEAR(gl_light.spot.outerConeAngle, l["cone_half_angle_deg"].get<double>() * std::numbers::pi / 180.0, 1e-15);
      EXPECT_EQ(gl_light.spot.innerConeAngle, 0.0);
    } else if (type == "directional") {
      EXPECT_EQ(gl_light.type, "directional");
      const json& toward = l["direction_toward_light"];
      expect_vec_near(shines, json{-toward[0].get<double>(), -toward[1].get<double>(), -toward[2].get<double>()}, "direction");
    } else if (type == "rect") {
      // Its centre, as the homogeneous point the hard techniques are judged with, and its size.
      EXPECT_EQ(gl_light.type, "point");
      expect_vec_near(column(at, 3), l["homogeneous"], "centre");
      EXPECT_EQ(l["homogeneous"][3], 1.0);
      for (const char* key : {"corner", "edge_u", "edge_v"})
        for (int k = 0; k < 3; ++k)
          EXPECT_EQ(gl_light.extras.Get(key).Get(k).GetNumberAsDouble(), l[key][k].get<double>()) << key;
      EXPECT_EQ(number(gl_light.extras.Get("size"), "equal_area_square_side"), l["size"]["equal_area_square_side"].get<double>());
    } else {
      ADD_FAILURE() << "a light type the test does not know: " << type;
    }
  }
}

TEST(ExportSceneGltf, EveryMatrixMatchesMatricesJson) {
  const fs::path root = fs::temp_directory_path() / ("shadowref_scene_gltf_" + std::to_string(::getpid()));
  fs::remove_all(root);
  // One scene per light kind (spot_light, sun_horizon, soft_penumbra) and two lights (two_lights).
  const std::vector<std::string> scenes{"ground_sphere", "two_lights", "spot_light", "sun_horizon", "soft_penumbra"};
  std::string list;
  for (const std::string& s : scenes) list += (list.empty() ? "" : ",") + s;
  const test::CommandResult r = test::run_command(
      {SHADOWREF_EXE, "export", "--scenes", list, "--out", (root / "pack").string(), "--cache", (root / "cache").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::array<int, 4> kinds{};  // point, spot, directional, rect lights seen
  for (const std::string& s : scenes) {
    check_scene(root / "pack", s);
    std::ifstream in(root / "pack" / s / "matrices.json");
    const json m = json::parse(in);
    for (const json& l : m["lights"]) {
      const std::string t = l["type"];
      ++kinds[t == "point" ? 0 : t == "spot" ? 1 : t == "directional" ? 2 : 3];
    }
  }
  for (int k : kinds) EXPECT_GT(k, 0) << "every light kind is covered";
  fs::remove_all(root);
}

// The catalogue's masked scenes as an engine's loader reads them (tinygltf, stb_image for the
// embedded PNG): glTF's own alpha test with the scene's cutoff, the mask in the image's alpha channel
// with a NEAREST / REPEAT sampler, vertex alpha in COLOR_0, and every mesh with flat normals, each the
// unit normal of its own triangle (docs/scene-format.md, "Alpha masks"; docs/output-contract.md).
TEST(ExportSceneGltf, MasksCutoffsVertexAlphaAndFlatNormalsAsALoaderReadsThem) {
  const fs::path root = fs::temp_directory_path() / ("shadowref_scene_gltf_masks_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const test::CommandResult r = test::run_command({SHADOWREF_EXE, "export", "--scenes", "alpha_fence,alpha_vertex", "--out",
                                                   (root / "pack").string(), "--cache", (root / "cache").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The fence: one masked material, cutoff 0.75, its grey mask (0, 160, 255) as the image's alpha.
  const tinygltf::Model fence = load(root / "pack" / "alpha_fence" / "scene.gltf");
  int masked = 0;
  for (const tinygltf::Material& mat : fence.materials) {
    if (mat.alphaMode != "MASK") continue;
    ++masked;
    EXPECT_EQ(mat.alphaCutoff, 0.75);
    const int t = mat.pbrMetallicRoughness.baseColorTexture.index;
    ASSERT_GE(t, 0);
    EXPECT_EQ(mat.pbrMetallicRoughness.baseColorTexture.texCoord, 0);
    const tinygltf::Sampler& sampler = fence.samplers.at(static_cast<std::size_t>(fence.textures.at(static_cast<std::size_t>(t)).sampler));
    EXPECT_EQ(sampler.magFilter, TINYGLTF_TEXTURE_FILTER_NEAREST);
    EXPECT_EQ(sampler.minFilter, TINYGLTF_TEXTURE_FILTER_NEAREST);
    EXPECT_EQ(sampler.wrapS, TINYGLTF_TEXTURE_WRAP_REPEAT);
    EXPECT_EQ(sampler.wrapT, TINYGLTF_TEXTURE_WRAP_REPEAT);
    const tinygltf::Image& image = fence.images.at(static_cast<std::size_t>(fence.textures.at(static_cast<std::size_t>(t)).source));
    ASSERT_GE(image.component, 2) << "the mask must be an alpha channel";
    std::vector<int> alphas;
    for (std::size_t i = static_cast<std::size_t>(image.component) - 1; i < image.image.size(); i += static_cast<std::size_t>(image.component))
      alphas.push_back(image.image[i]);
    std::sort(alphas.begin(), alphas.end());
    alphas.erase(std::unique(alphas.begin(), alphas.end()), alphas.end());
    EXPECT_EQ(alphas, (std::vector<int>{0, 160, 255}));
    EXPECT_TRUE(mat.doubleSided);
  }
  EXPECT_EQ(masked, 1);
  // alpha_vertex: vertex alpha as COLOR_0 (the fade card's alone, without a texture).
  const tinygltf::Model vertex = load(root / "pack" / "alpha_vertex" / "scene.gltf");
  int with_colour = 0, without_texture = 0;
  for (const tinygltf::Mesh& mesh : vertex.meshes) {
    const tinygltf::Primitive& prim = mesh.primitives.at(0);
    if (!prim.attributes.count("COLOR_0")) continue;
    ++with_colour;
    EXPECT_EQ(vertex.materials.at(static_cast<std::size_t>(prim.material)).alphaMode, "MASK") << mesh.name;
    without_texture += prim.attributes.count("TEXCOORD_0") ? 0 : 1;
  }
  EXPECT_EQ(with_colour, 2);
  EXPECT_EQ(without_texture, 1);
  // Flat normals: each vertex's NORMAL is its triangle's unit face normal.
  for (const tinygltf::Model* model : {&fence, &vertex})
    for (const tinygltf::Mesh& mesh : model->meshes) {
      const tinygltf::Primitive& prim = mesh.primitives.at(0);
      ASSERT_TRUE(prim.attributes.count("NORMAL")) << mesh.name;
      const std::string pos = accessor_bytes(*model, prim.attributes.at("POSITION"));
      const std::string nor = accessor_bytes(*model, prim.attributes.at("NORMAL"));
      ASSERT_EQ(pos.size(), nor.size());
      std::vector<float> p(pos.size() / 4), n(nor.size() / 4);
      std::memcpy(p.data(), pos.data(), pos.size());
      std::memcpy(n.data(), nor.data(), nor.size());
      for (std::size_t t = 0; t + 9 <= p.size(); t += 9) {  // unindexed in effect: the indices run 0, 1, 2, ...
        const double ax = p[t + 3] - p[t], ay = p[t + 4] - p[t + 1], az = p[t + 5] - p[t + 2];
        const double bx = p[t + 6] - p[t], by = p[t + 7] - p[t + 1], bz = p[t + 8] - p[t + 2];
        double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
        const double len = std::sqrt(cx * cx + cy * cy + cz * cz);
        cx /= len, cy /= len, cz /= len;
        for (std::size_t k = 0; k < 9; k += 3) {
          // float normals of a double cross product: 1e-6 is a few float ulps of a unit vector.
          EXPECT_NEAR(n[t + k], cx, 1e-6) << mesh.name;
          EXPECT_NEAR(n[t + k + 1], cy, 1e-6) << mesh.name;
          EXPECT_NEAR(n[t + k + 2], cz, 1e-6) << mesh.name;
        }
      }
    }
  fs::remove_all(root);
}

// A broken scene.gltf is caught: the test's own checks fail on a camera moved by a millimetre.
TEST(ExportSceneGltf, AMovedCameraIsCaught) {
  const fs::path root = fs::temp_directory_path() / ("shadowref_scene_gltf_moved_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const test::CommandResult r = test::run_command({SHADOWREF_EXE, "export", "--scenes", "ground_sphere", "--out",
                                                   (root / "pack").string(), "--cache", (root / "cache").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path file = root / "pack" / "ground_sphere" / "scene.gltf";
  json g;
  {
    std::ifstream in(file);
    g = json::parse(in);
  }
  for (json& n : g["nodes"])
    if (n.contains("camera")) n["matrix"][12] = n["matrix"][12].get<double>() + 1e-3;
  std::ofstream(file) << g.dump();
  ::testing::TestPartResultArray failures;
  {
    ::testing::ScopedFakeTestPartResultReporter reporter(::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD,
                                                         &failures);
    check_scene(root / "pack", "ground_sphere");
  }
  int view_failures = 0;
  for (int i = 0; i < failures.size(); ++i)
    if (std::string(failures.GetTestPartResult(i).message()).find("camera view") != std::string::npos) ++view_failures;
  EXPECT_GT(view_failures, 0);
  fs::remove_all(root);
}

}  // namespace
}  // namespace shadowref
