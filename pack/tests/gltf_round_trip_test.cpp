// gltf_round_trip_test.cpp — the pack's scene.gltf read back by the glTF scene reader
// (scene/gltf_scene.hpp) is the same scene: for every catalogue scene of the default run, the
// camera, every light, every object's triangles, colour and receiver flag, and every mask (texture
// alpha, coordinates, vertex alpha, cutoff). Writer and reader were written from the glTF
// specification each on its own side; this holds them to each other.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "shadowref/pack/gltf_writer.hpp"
#include "shadowref/scene/gltf_scene.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace shadowref::pack {
namespace {

namespace fs = std::filesystem;

// Tolerances, each with its reason:
// - positions, uvs, vertex alpha, colours, cutoffs, skins: exact. Written as the scene's own floats (and
//   doubles in shortest round-trip form), read back through identity node transforms.
// - the camera and light frames: 1e-9 of the scene's scale. The camera node's matrix is the inverse
//   of the view in double, a light's is built from its direction; reading them back divides and
//   normalises again: a few roundings of 1e-16 relative each, far below 1e-9, and a wrong axis,
//   sign or handedness would be off by the scale itself.
// - fovy and cone angles: 1e-12 degrees (degrees → radians → degrees in double).
constexpr double kFrameTol = 1e-9;
constexpr double kAngleTol = 1e-12;

double scale_of(const scene::Scene& s) {
  const auto b = scene::bounds(s);
  return std::max({1.0, b[0].cwiseAbs().maxCoeff(), b[1].cwiseAbs().maxCoeff(), s.camera.position.norm()});
}

void expect_near(const Vec3<double>& a, const Vec3<double>& b, double tol, const std::string& what) {
  EXPECT_LE((a - b).norm(), tol) << what << ": (" << a.transpose() << ") vs (" << b.transpose() << ")";
}

std::vector<fs::path> default_catalogue() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(SHADOWREF_SCENES_DIR))
    if (e.path().extension() == ".json" && !scene::load_scene(e.path()).has_tag("large")) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

class RoundTrip : public ::testing::TestWithParam<fs::path> {};

TEST_P(RoundTrip, PackSceneGltfReadsBackAsTheSameScene) {
  const scene::Scene s = scene::load_scene(GetParam());
  const fs::path dir = fs::path(::testing::TempDir()) / ("shadowref-gltf-round-trip-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / (s.name + ".gltf");
  std::ofstream(file) << scene_gltf(s).dump();
  const scene::GltfScene r = scene::read_gltf_scene(file);
  const scene::Scene& g = r.scene;
  EXPECT_TRUE(r.not_read.empty()) << r.not_read.front();
  const double tol = kFrameTol * scale_of(s);

  EXPECT_EQ(g.name, s.name);
  EXPECT_EQ(g.units.symbol, s.units.symbol);
  EXPECT_EQ(g.width, s.width);
  EXPECT_EQ(g.height, s.height);
  expect_near(g.camera.position, s.camera.position, tol, "camera position");
  expect_near((g.camera.target - g.camera.position).normalized(), (s.camera.target - s.camera.position).normalized(), kFrameTol,
              "camera forward");
  // The glTF up is the view's orthogonalised up: compare it with the JSON up made orthogonal to the forward.
  const Vec3<double> f = (s.camera.target - s.camera.position).normalized();
  expect_near(g.camera.up, (s.camera.up - s.camera.up.dot(f) * f).normalized(), kFrameTol, "camera up");
  EXPECT_NEAR(g.camera.fovy_deg, s.camera.fovy_deg, kAngleTol);
  EXPECT_EQ(g.camera.near, s.camera.near);
  EXPECT_EQ(g.camera.far, s.camera.far);

  ASSERT_EQ(g.lights.size(), s.lights.size());
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const scene::Light &a = g.lights[i], &b = s.lights[i];
    const std::string what = "light " + std::to_string(i);
    ASSERT_EQ(a.type, b.type) << what;
    if (b.type == scene::LightType::Point || b.type == scene::LightType::Spot) expect_near(a.position, b.position, tol, what);
    if (b.type == scene::LightType::Spot || b.type == scene::LightType::Directional) expect_near(a.direction, b.direction, kFrameTol, what);
    if (b.type == scene::LightType::Spot) {
      EXPECT_NEAR(a.cone_deg, b.cone_deg, kAngleTol) << what;
    }
    if (b.type == scene::LightType::Rect) {
      EXPECT_EQ(a.corner, b.corner) << what;
      EXPECT_EQ(a.edge_u, b.edge_u) << what;
      EXPECT_EQ(a.edge_v, b.edge_v) << what;
      EXPECT_EQ(a.samples, b.samples) << what;
    }
  }

  ASSERT_EQ(g.objects.size(), s.objects.size());
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const scene::Object &a = g.objects[i], &b = s.objects[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.receiver, b.receiver) << b.name;
    EXPECT_EQ(a.color, b.color) << b.name;
    // The pack writes flat triangles: triangle t's corner k is vertex 3t + k.
    ASSERT_EQ(a.mesh.triangles.size(), b.mesh.triangles.size()) << b.name;
    for (std::size_t t = 0; t < b.mesh.triangles.size(); ++t)
      for (std::size_t k = 0; k < 3; ++k) {
        ASSERT_EQ(a.mesh.triangles[t][k], 3 * t + k) << b.name;
        ASSERT_EQ(a.mesh.positions[3 * t + k], b.mesh.positions[b.mesh.triangles[t][k]]) << b.name << " triangle " << t;
      }
    // A skin comes back as written: the bind pose, joints and weights per vertex, the joints at the
    // pose (the posed positions above are then the same sums: skin.hpp's pose_vertex).
    ASSERT_EQ(a.skin.has_value(), b.skin.has_value()) << b.name;
    if (b.skin) {
      ASSERT_EQ(a.skin->joints.size(), b.skin->joints.size()) << b.name;
      for (std::size_t j = 0; j < b.skin->joints.size(); ++j) {
        EXPECT_EQ(a.skin->joints[j].world, b.skin->joints[j].world) << b.name << " joint " << j;
        EXPECT_EQ(a.skin->joints[j].inverse_bind, b.skin->joints[j].inverse_bind) << b.name << " joint " << j;
      }
      for (std::size_t t = 0; t < b.mesh.triangles.size(); ++t)
        for (std::size_t k = 0; k < 3; ++k) {
          const std::uint32_t from = b.mesh.triangles[t][k];
          ASSERT_EQ(a.skin->bind_positions[3 * t + k], b.skin->bind_positions[from]) << b.name;
          ASSERT_EQ(a.skin->joint_indices[3 * t + k], b.skin->joint_indices[from]) << b.name;
          ASSERT_EQ(a.skin->weights[3 * t + k], b.skin->weights[from]) << b.name;
        }
    }
    ASSERT_EQ(a.alpha.has_value(), b.alpha.has_value()) << b.name;
    if (!b.alpha) continue;
    EXPECT_EQ(a.alpha->cutoff, b.alpha->cutoff) << b.name;
    EXPECT_EQ(a.alpha->has_vertex_alpha, b.alpha->has_vertex_alpha) << b.name;
    EXPECT_EQ(a.alpha->texture->width, b.alpha->texture->width) << b.name;
    EXPECT_EQ(a.alpha->texture->height, b.alpha->texture->height) << b.name;
    EXPECT_EQ(a.alpha->texture->alpha, b.alpha->texture->alpha) << b.name;
    const bool textured = !b.alpha->texture->file.empty();
    for (std::size_t t = 0; t < b.mesh.triangles.size(); ++t)
      for (std::size_t k = 0; k < 3; ++k) {
        const std::uint32_t from = b.mesh.triangles[t][k];
        if (textured) {
          ASSERT_EQ(a.alpha->uvs[3 * t + k], b.alpha->uvs[from]) << b.name;
        }
        ASSERT_EQ(a.alpha->vertex_alpha[3 * t + k], b.alpha->vertex_alpha[from]) << b.name;
      }
  }
  fs::remove(file);
}

INSTANTIATE_TEST_SUITE_P(Catalogue, RoundTrip, ::testing::ValuesIn(default_catalogue()),
                         [](const ::testing::TestParamInfo<fs::path>& p) { return p.param.stem().string(); });

}  // namespace
}  // namespace shadowref::pack
