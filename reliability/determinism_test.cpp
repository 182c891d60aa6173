// determinism_test.cpp — the reference and the renderer produce byte-identical
// images across two runs, and the reference across thread counts, for every scene of the default
// catalogue (conformance/scenes/*.json, without the scenes tagged "large"), at a reduced resolution
// (reduced_resolution.hpp: the longer side at most kMaxSide pixels) to keep the test small.
//   reference: in process, Options::threads 1, then 2, then 2 again, compared bit for bit
//              (masks, decided, shaded, and the float visibility by its bits);
//   renderer:  llvmpipe through OSMesa, every technique, in a child process (determinism_render),
//              twice, the PNG files' hashes compared; each child's environment asks llvmpipe for
//              two rasteriser threads (LP_NUM_THREADS=2), and each must have none: the renderer
//              rasterises in its own thread (renderer/gl_context.cpp says why).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "reduced_resolution.hpp"
#include "run_command.hpp"
#include "shadowref/reference/render.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace shadowref::reliability {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxSide = 64;

// The default catalogue: every scene file not tagged "large", by name.
std::vector<std::string> default_catalogue() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(SHADOWREF_SCENES_DIR)) {
    if (e.path().extension() != ".json") continue;
    std::ifstream in(e.path());
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    bool large = false;
    if (j.is_object() && j.contains("tags") && j["tags"].is_array())
      for (const auto& t : j["tags"]) large = large || (t.is_string() && t.get<std::string>() == "large");
    if (!large) names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

void expect_identical(const reference::Images& a, const reference::Images& b) {
  ASSERT_EQ(a.lights.size(), b.lights.size());
  const auto same_floats = [](const std::vector<float>& x, const std::vector<float>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(float)) == 0;
  };
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_EQ(a.lights[i].mask, b.lights[i].mask) << "light " << i;
    EXPECT_EQ(a.lights[i].decided, b.lights[i].decided) << "light " << i;
    EXPECT_TRUE(same_floats(a.lights[i].visibility, b.lights[i].visibility)) << "light " << i;
  }
  EXPECT_EQ(a.shaded, b.shaded);
  EXPECT_EQ(a.decided, b.decided);
  EXPECT_TRUE(same_floats(a.visibility, b.visibility));
}

class Catalogue : public ::testing::TestWithParam<std::string> {
 protected:
  scene::Scene load() const {
    scene::Scene s = scene::load_scene(fs::path(SHADOWREF_SCENES_DIR) / (GetParam() + ".json"));
    reduce_resolution(s, kMaxSide);
    return s;
  }
};

TEST_P(Catalogue, ReferenceIsIdenticalAcrossRunsAndThreadCounts) {
  const scene::Scene s = load();
  reference::Options one;
  one.samples_per_axis = 2;
  one.threads = 1;
  reference::Options two = one;
  two.threads = 2;
  const reference::Images a = reference::render(s, one);
  const reference::Images b = reference::render(s, two);
  {
    SCOPED_TRACE("1 thread vs 2 threads");
    expect_identical(a, b);
  }
  SCOPED_TRACE("2 threads, run 1 vs run 2");
  expect_identical(b, reference::render(s, two));
}

TEST_P(Catalogue, RendererIsIdenticalAcrossRunsWithoutRasteriserThreads) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("shadowref-determinism-" + GetParam());
  fs::remove_all(dir);
  const std::string scene = (fs::path(SHADOWREF_SCENES_DIR) / (GetParam() + ".json")).string();
  std::vector<test::CommandResult> runs;
  ::setenv("LP_NUM_THREADS", "2", 1);  // inherited by the child: asks llvmpipe for threads it must not start
  ::setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  for (int run = 0; run < 2; ++run) {
    runs.push_back(test::run_command({"/usr/bin/timeout", "300", SHADOWREF_DETERMINISM_RENDER, scene, std::to_string(kMaxSide),
                                      (dir / ("run" + std::to_string(run))).string()}));
    ASSERT_EQ(runs.back().exit_code, 0) << runs.back().err;
  }
  ::unsetenv("LP_NUM_THREADS");
  ASSERT_FALSE(runs[0].out.empty());
  EXPECT_NE(runs[0].out.find("\nllvmpipe threads: 0\n"), std::string::npos) << runs[0].out;
  EXPECT_EQ(runs[0].out, runs[1].out) << "run 1 vs run 2";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Default, Catalogue, ::testing::ValuesIn(default_catalogue()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) { return param_info.param; });

}  // namespace
}  // namespace shadowref::reliability
