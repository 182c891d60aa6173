// export_command_test.cpp — `shadowref export`: the pack carries the camera and light matrices of
// every run convention, and they agree on where a scene point lands (independently recomputed here
// from the matrices in matrices.json, not from mathlib).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>
#include <nlohmann/json.hpp>

#include "run_command.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// clip = M · (x, y, z, 1) with M given as canonical rows.
std::array<double, 4> apply(const json& rows, const std::array<double, 3>& p) {
  std::array<double, 4> out{};
  for (int r = 0; r < 4; ++r)
    out[static_cast<std::size_t>(r)] = rows[r][0].get<double>() * p[0] + rows[r][1].get<double>() * p[1] +
                                      rows[r][2].get<double>() * p[2] + rows[r][3].get<double>();
  return out;
}

double det3(const json& rows) {
  const auto m = [&](int r, int c) { return rows[r][c].get<double>(); };
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
}

// Exports `scene` under `root` (removed first) and returns its matrices.json.
json exported_matrices(const char* scene, const fs::path& root) {
  fs::remove_all(root);
  const test::CommandResult r = test::run_command(
      {SHADOWREF_EXE, "export", "--scenes", scene, "--out", (root / "pack").string(), "--cache", (root / "cache").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(root / "pack" / scene / "matrices.json");
  return json::parse(in);
}

TEST(ExportCommand, PackHasEveryConventionAndTheyPutPointsOnTheSamePixel) {
  const fs::path root = fs::temp_directory_path() / ("shadowref_export_test_" + std::to_string(::getpid()));
  const json m = exported_matrices("ground_sphere", root);
  ASSERT_TRUE(m.contains("world"));
  const json& conv = m["conventions"];
  for (const char* name : {"gl", "gl-zo", "reversed-z", "d3d"}) ASSERT_TRUE(conv.contains(name)) << name;
  // Points of the scene (on the ground, on the ball): the same NDC x, y in every convention.
  const std::array<std::array<double, 3>, 3> points{{{0.0, 1.5, 0.0}, {1.0, 0.0, -1.0}, {-2.0, 0.0, 1.0}}};
  for (const auto& p : points) {
    const auto g = apply(conv["gl"]["view_projection"]["canonical"], p);
    for (const auto& [name, c] : conv.items()) {
      const auto h = apply(c["view_projection"]["canonical"], p);
      ASSERT_GT(h[3], 0.0) << name;
      EXPECT_NEAR(h[0] / h[3], g[0] / g[3], 1e-9) << name;
      EXPECT_NEAR(h[1] / h[3], g[1] / g[3], 1e-9) << name;
    }
  }
  // d3d is left-handed over scene coordinates (a mirror), gl right-handed; both are rotations.
  EXPECT_NEAR(det3(conv["d3d"]["view"]["canonical"]), -1.0, 1e-9);
  EXPECT_NEAR(det3(conv["gl"]["view"]["canonical"]), 1.0, 1e-9);
  EXPECT_EQ(conv["reversed-z"]["depth_test"], "GREATER");
  EXPECT_EQ(conv["reversed-z"]["depth_clear"], 0.0);
  // Every light has shadow-map views in every convention, mapping the ball's centre into the map:
  // the light at (2, 6, 1) is inside the ground's bounds, so it has a cube, and the ball's centre
  // (0, 1.5, 0) is in the face of the largest component of (p − light) = (−2, −4.5, −1): −y, view 3.
  for (const auto& [name, c] : conv.items()) {
    ASSERT_EQ(c["light_views"].size(), m["lights"].size()) << name;
    ASSERT_EQ(c["light_views"][0]["views"].size(), 6u) << name;
    const json& view = c["light_views"][0]["views"][3];
    const auto t = apply(view["shadow_from_scene"]["canonical"], points[0]);
    EXPECT_GT(t[0] / t[3], 0.0) << name;
    EXPECT_LT(t[0] / t[3], 1.0) << name;
    EXPECT_GT(t[2] / t[3], 0.0) << name;
    EXPECT_LT(t[2] / t[3], 1.0) << name;
  }
  fs::remove_all(root);
}

// The cascaded techniques' views: a directional light's splits run from the camera's near plane
// forward and increase, the depth row gives a visible ground point a camera depth inside them, and
// the view of the cascade that depth falls in maps the point inside its map — checked from the
// numbers in matrices.json alone, in every convention.
TEST(ExportCommand, EngineLightViewsAreOpenGLCubeMapFacesAtAPowerOfTwo) {
  const fs::path root = fs::temp_directory_path() / ("shadowref_export_engine_views_" + std::to_string(::getpid()));
  const json m = exported_matrices("ground_sphere", root);
  const json& L = m["lights"][0]["homogeneous"];  // the point light at (2, 6, 1)
  // The OpenGL specification's cube-map face selection (OpenGL 4.6, table 8.19), written out here:
  // per face, (sc, tc, ma) of a direction r; s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2.
  using Dir = std::array<double, 3>;
  const auto table = [](int face, const Dir& r) -> std::array<double, 3> {
    switch (face) {
      case 0: return {-r[2], -r[1], r[0]};
      case 1: return {r[2], -r[1], r[0]};
      case 2: return {r[0], r[2], r[1]};
      case 3: return {r[0], -r[2], r[1]};
      case 4: return {r[0], -r[1], r[2]};
      default: return {-r[0], -r[1], r[2]};
    }
  };
  const std::array<Dir, 6> axes{{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
  for (const char* name : {"gl", "gl-zo", "reversed-z"}) {
    const json& e = m["conventions"][name]["engine_light_views"][0];
    const auto size = e["map_size"].get<unsigned>();
    EXPECT_EQ(size & (size - 1), 0u) << name << ": a power of two";
    EXPECT_GE(size, m["conventions"][name]["light_views"][0]["map_size"].get<unsigned>()) << name;
    ASSERT_EQ(e["views"].size(), 6u) << name;
    for (int face = 0; face < 6; ++face)
      for (const auto& [u, v] : {std::pair{0.0, 0.0}, {0.5, -0.3}, {-0.9, 0.8}, {0.99, 0.99}}) {
        // A direction in the face: the axis plus the two others at (u, v).
        const Dir& a = axes[static_cast<std::size_t>(face)];
        const Dir r = a[0] != 0 ? Dir{a[0], u, v} : a[1] != 0 ? Dir{u, a[1], v} : Dir{u, v, a[2]};
        const std::array<double, 3> p{L[0].get<double>() + 2 * r[0], L[1].get<double>() + 2 * r[1], L[2].get<double>() + 2 * r[2]};
        const auto t = apply(e["views"][face]["shadow_from_scene"]["canonical"], p);
        const auto [sc, tc, ma] = table(face, r);
        EXPECT_NEAR(t[0] / t[3], 0.5 * (sc / std::abs(ma) + 1), 1e-9) << name << " face " << face;
        EXPECT_NEAR(t[1] / t[3], 0.5 * (tc / std::abs(ma) + 1), 1e-9) << name << " face " << face;
      }
  }
  // d3d: no cube (GL's orientation is a right-handed world's), said in its kind.
  EXPECT_EQ(m["conventions"]["d3d"]["engine_light_views"][0]["views"].size(), 0u);
  fs::remove_all(root);
}

TEST(ExportCommand, PackCarriesTheCascadesOfADirectionalLight) {
  const fs::path root = fs::temp_directory_path() / ("shadowref_export_csm_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const test::CommandResult r = test::run_command(
      {SHADOWREF_EXE, "export", "--scenes", "sun_horizon", "--out", (root / "pack").string(), "--cache", (root / "cache").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(root / "pack" / "sun_horizon" / "matrices.json");
  const json m = json::parse(in);
  const std::array<double, 3> ground{1.0, 0.0, -12.0};  // a ground point in view
  for (const auto& [name, c] : m["conventions"].items()) {
    ASSERT_EQ(c["cascade_views"].size(), 1u) << name;
    const json& l = c["cascade_views"][0];
    const json& splits = l["splits"];
    ASSERT_EQ(splits.size(), 5u) << name;
    ASSERT_EQ(l["views"].size(), 4u) << name;
    EXPECT_NEAR(splits[0].get<double>(), 0.1, 1e-12) << name << ": the first split is the camera's near plane";
    for (std::size_t i = 0; i + 1 < splits.size(); ++i) EXPECT_LT(splits[i].get<double>(), splits[i + 1].get<double>()) << name;
    const json& row = l["camera_depth_from_scene"];
    const double depth = row[0].get<double>() * ground[0] + row[1].get<double>() * ground[1] +
                         row[2].get<double>() * ground[2] + row[3].get<double>();
    EXPECT_NEAR(depth, (1.7 * 2.5 + 50.0 * 22.0) / std::hypot(1.7, 50.0), 1e-6) << name << ": the camera depth of (1, 0, -12)";
    std::size_t cascade = 0;
    while (cascade + 2 < splits.size() && depth >= splits[cascade + 1].get<double>()) ++cascade;
    const auto t = apply(l["views"][cascade]["shadow_from_scene"]["canonical"], ground);
    for (int k : {0, 1, 2}) {
      EXPECT_GT(t[static_cast<std::size_t>(k)] / t[3], 0.0) << name << " cascade " << cascade << " coordinate " << k;
      EXPECT_LT(t[static_cast<std::size_t>(k)] / t[3], 1.0) << name << " cascade " << cascade << " coordinate " << k;
    }
  }
  fs::remove_all(root);
}

// A rect light's size for soft techniques: its edges, the side of the square of equal area, the
// reference's samples, and the lit-fraction file a soft candidate writes; the reference's
// covered.png (the pixels a lit fraction is judged on) travels with the pack.
TEST(ExportCommand, PackCarriesTheSizeOfAnAreaLight) {
  const fs::path root = fs::temp_directory_path() / ("shadowref_export_soft_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const test::CommandResult r = test::run_command(
      {SHADOWREF_EXE, "export", "--scenes", "soft_penumbra", "--out", (root / "pack").string(), "--cache", (root / "cache").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(root / "pack" / "soft_penumbra" / "matrices.json");
  const json m = json::parse(in);
  ASSERT_EQ(m["lights"].size(), 1u);
  const json& l = m["lights"][0];
  EXPECT_EQ(l["type"], "rect");
  EXPECT_NEAR(l["size"]["edge_u_length"].get<double>(), 1.2, 1e-12);
  EXPECT_NEAR(l["size"]["edge_v_length"].get<double>(), 1.2, 1e-12);
  EXPECT_NEAR(l["size"]["equal_area_square_side"].get<double>(), 1.2, 1e-12);
  EXPECT_EQ(l["size"]["reference_samples_per_axis"], 8);
  EXPECT_EQ(l["visibility_file"], "visibility.png");
  EXPECT_TRUE(fs::is_regular_file(root / "pack" / "soft_penumbra" / "reference" / "covered.png"));
  EXPECT_TRUE(fs::is_regular_file(root / "pack" / "soft_penumbra" / "reference" / "visibility.exr"));
  std::ifstream readme(root / "pack" / "README.md");
  const std::string text((std::istreambuf_iterator<char>(readme)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("## Soft shadows"), std::string::npos);
  fs::remove_all(root);
}

// An engine team's soft shadows, judged from the pack alone: our renderer stands in for the engine
// (pcss into my-renders/<scene>/: mask.png, visibility.png, candidate.json). soft_penumbra PASSes;
// on cornell_box, where pcss is an expected failure, the candidate's masks are held against the
// technique's own model and the case is an XFAIL, not an ERROR; and a candidate whose lit fraction
// is the hard mask (no penumbra at all) FAILs in visibility units.
TEST(ExportCommand, ASoftCandidateIsJudgedFromThePackAlone) {
  const fs::path root = fs::temp_directory_path() / ("shadowref_export_soft_judged_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const fs::path pack = root / "pack";
  ASSERT_EQ(test::run_command({SHADOWREF_EXE, "export", "--scenes", "soft_penumbra,cornell_box", "--out", pack.string(),
                               "--cache", (root / "cache").string()})
                .exit_code,
            0);
  for (const char* scene : {"soft_penumbra", "cornell_box"}) {
    const test::CommandResult r = test::run_command({SHADOWREF_EXE, "render", "--scene", (pack / "scenes" / (std::string(scene) + ".json")).string(),
                                                     "--technique", "pcss", "--out", (root / "my-renders" / scene).string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto judge = [&](const std::string& out) {
    return test::run_command({SHADOWREF_EXE, "conform", "--catalogue", (pack / "scenes").string(), "--candidate-dir",
                              (root / "my-renders").string(), "--technique", "pcss", "--out", (root / out).string(),
                              "--cache", (root / "cache").string()});
  };
  const test::CommandResult good = judge("verdict");
  EXPECT_EQ(good.exit_code, 0) << good.out << good.err;
  {
    std::ifstream in(root / "verdict" / "report.json");
    const json report = json::parse(in);
    for (const json& c : report["cases"]) {
      EXPECT_EQ(c["status"], c["scene"] == "cornell_box" ? "XFAIL" : "PASS") << c["scene"] << ": " << c.value("error", "");
      EXPECT_TRUE(c["comparison"].contains("visibility")) << c["scene"] << ": the lit fraction was judged";
    }
  }
  // The lit fraction replaced by the hard mask (background 0): every penumbra is wrong.
  fs::copy_file(root / "my-renders" / "soft_penumbra" / "mask.png", root / "my-renders" / "soft_penumbra" / "visibility.png",
                fs::copy_options::overwrite_existing);
  const test::CommandResult hard = judge("verdict-hard");
  EXPECT_EQ(hard.exit_code, 2) << hard.out;
  EXPECT_NE(hard.out.find("FAIL   soft_penumbra x pcss: visibility:"), std::string::npos) << hard.out;
  fs::remove_all(root);
}

// Without --cache, export writes nothing outside --out (no cache in the working folder, none left in
// the pack), and the pack's README gives what an engine team needs with the commands run from the pack.
TEST(ExportCommand, WritesOnlyUnderOutAndItsReadmeStandsAlone) {
  const fs::path root = fs::temp_directory_path() / ("shadowref_export_only_out_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "cwd");
  const fs::path before = fs::current_path();
  fs::current_path(root / "cwd");  // the child inherits it
  const test::CommandResult r = test::run_command({SHADOWREF_EXE, "export", "--scenes", "ground_sphere", "--out", "pack"});
  fs::current_path(before);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(root / "cwd")) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"pack"});
  const fs::path pack = root / "cwd" / "pack";
  EXPECT_FALSE(fs::exists(pack / ".reference-cache"));
  EXPECT_TRUE(fs::exists(pack / "ground_sphere" / "reference" / "mask.png"));
  std::ifstream in(pack / "README.md");
  const std::string readme((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* needed : {"shadowref conform --catalogue scenes --candidate-dir my-renders", "Right-handed, y up",
                             "Faces turned away from a light are shadowed", "any other value", "is refused",
                             "\"light_views\": \"pack\"", "\"producer\"", "\"shadow_map_size\"", "conventions.<name>.view",
                             "a rect light's centre", "A spot light's cone is lighting, not shadow", "at least half of its",
                             "Which technique name is my engine", "| `volume-zfail` |", "scene.gltf", "KHR_lights_punctual"})
    EXPECT_NE(readme.find(needed), std::string::npos) << needed;
  fs::remove_all(root);
}

}  // namespace
}  // namespace shadowref
