// matrices_test.cpp — matrices.json: the D3DX layout is the transpose of the canonical one, and the
// engine light views are OpenGL cube faces at a power of two in a right-handed convention and absent
// in the left-handed one.
#include <gtest/gtest.h>

#include <filesystem>

#include "test_scene_json.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/pack/matrices.hpp"
#include "shadowref/pack/matrix_json.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace shadowref::pack {
namespace {

using nlohmann::json;

scene::Scene minimal() {
  return scene::parse_scene(scene::test::minimal_scene().dump(), std::filesystem::current_path() / "minimal.json");
}

TEST(MatrixJson, D3dxIsTheTransposeAndColumnMajorReadsDownColumns) {
  Mat4<double> m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = 10 * r + c;
  const json j = both_layouts(m);
  const json cm = column_major(m);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      EXPECT_EQ(j["canonical"][r][c].get<double>(), m(r, c));
      EXPECT_EQ(j["d3dx"][c][r].get<double>(), m(r, c));
      EXPECT_EQ(cm[4 * c + r].get<double>(), m(r, c));
    }
}

TEST(Matrices, EngineLightViewsAreGlCubeFacesInRightHandedConventionsOnly) {
  const scene::Scene s = minimal();
  for (const RunConvention& c : kRunConventions) {
    const scene::PreparedScene p = scene::prepare_scene(s, c);
    const json e = engine_light_views(p);
    ASSERT_EQ(e.size(), 1u);
    const unsigned size = e[0]["map_size"].get<unsigned>();
    EXPECT_EQ(size & (size - 1), 0u) << c.name;  // a power of two
    EXPECT_GE(size, static_cast<unsigned>(p.light_fits[0].size));
    if (c.clip.hand == Handedness::Right) {
      EXPECT_EQ(e[0]["views"].size(), 6u) << c.name;
    } else {
      EXPECT_TRUE(e[0]["views"].empty()) << c.name;
      EXPECT_EQ(e[0]["kind"].get<std::string>().rfind("none", 0), 0u);
    }
  }
}

TEST(Matrices, EveryConventionAndThePlanarShadowMatrixOfEachLight) {
  const json m = matrices_json(minimal());
  for (const RunConvention& c : kRunConventions) EXPECT_TRUE(m["conventions"].contains(std::string(c.name))) << c.name;
  ASSERT_TRUE(m.contains("receiver_plane"));
  // The planar matrix puts a point on the receiver plane (y = 0): S · (0, 1.5, 0, 1) has y = 0.
  const json& s = m["lights"][0]["planar_shadow_matrix"]["canonical"];
  double h[4];
  for (int r = 0; r < 4; ++r) h[r] = s[r][1].get<double>() * 1.5 + s[r][3].get<double>();
  EXPECT_NEAR(h[1] / h[3], 0.0, 1e-12);
  EXPECT_EQ(m["lights"][0]["mask_file"], "mask.png");
}

}  // namespace
}  // namespace shadowref::pack
