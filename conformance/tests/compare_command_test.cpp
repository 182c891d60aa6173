// compare_command_test.cpp — `shadowref compare` end to end: exit codes (0 pass, 2 fail, 3 size
// mismatch, 4 bad input), one line on stderr for errors, the JSON, the error image.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "run_command.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/techniques.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;

class CompareCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    root = fs::temp_directory_path() / ("shadowref-compare-cli-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root);
    fs::create_directories(root / "ref");
    fs::create_directories(root / "cand");
    grey(root / "ref" / "mask.png", 64, 64, 255);
    grey(root / "ref" / "decided.png", 64, 64, 255);
  }
  void TearDown() override { fs::remove_all(root); }
  static void grey(const fs::path& f, int w, int h, std::uint8_t v) {
    outputs::write_png(outputs::Image8{w, h, 1, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h), v)}, f);
  }
  test::CommandResult compare(std::vector<std::string> extra = {}) {
    std::vector<std::string> a{SHADOWREF_EXE, "compare", "--reference", (root / "ref").string(), "--candidate",
                               (root / "cand").string()};
    a.insert(a.end(), extra.begin(), extra.end());
    return test::run_command(a);
  }
  fs::path root;
};

TEST_F(CompareCommand, IdenticalIsAPass) {
  grey(root / "cand" / "mask.png", 64, 64, 255);
  const auto r = compare();
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("verdict: PASS"), std::string::npos) << r.out;
}

TEST_F(CompareCommand, AllWrongIsAFailWithJsonAndErrorImage) {
  grey(root / "cand" / "mask.png", 64, 64, 0);
  const auto r = compare({"--json", "--technique", "shadowmap", "--out", (root / "err").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["comparison"]["verdict"], "fail");
  EXPECT_EQ(j["comparison"]["total"]["false_shadow"], 4096);
  EXPECT_EQ(j["comparison"]["threshold"]["name"], "shadow-map");
  EXPECT_EQ(j["status"], "FAIL");  // without --scene, the verdict's
  EXPECT_EQ(j["scene"], "");
  EXPECT_EQ(j["exit_code"], 2);
  EXPECT_TRUE(fs::exists(root / "err" / "error.png"));
}

TEST_F(CompareCommand, SizeMismatchExits3) {
  grey(root / "cand" / "mask.png", 32, 64, 255);
  const auto r = compare();
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("32x64"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST_F(CompareCommand, BadInputExits4WithOneLine) {
  auto r = compare();  // no candidate mask
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("mask.png"), std::string::npos) << r.err;
  {
    std::ofstream f(root / "cand" / "mask.png");
    f << "\x89PNG\r\n\x1a\n truncated";
  }
  r = compare();
  EXPECT_EQ(r.exit_code, 4) << r.err;
  outputs::write_png(outputs::Image8{64, 64, 3, std::vector<std::uint8_t>(64 * 64 * 3, 255)}, root / "cand" / "mask.png");
  r = compare();
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("3 channel"), std::string::npos) << r.err;
}

// With --scene, `compare` explains a shadow map's wrong pixels as `conform` does (texel footprint,
// depth bias); without it nothing explains them. A correct 512-texel render of the sun 8 degrees up
// has 341 wrong pixels, all but a handful within its texel footprint: FAIL (17.6 % of the edge
// pixels unexplained) without the scene, PASS with it.
TEST_F(CompareCommand, SceneGivesTheShadowMapCausesConformUses) {
  const std::string scene = std::string(SHADOWREF_CATALOGUE) + "/grazing_light.json";
  ASSERT_EQ(test::run_command({SHADOWREF_EXE, "reference", "--scene", scene, "--out", (root / "r").string(), "--quiet"}).exit_code, 0);
  ASSERT_EQ(test::run_command({SHADOWREF_EXE, "render", "--scene", scene, "--technique", "shadowmap", "--shadow-map-size", "512",
                               "--out", (root / "c").string()}).exit_code, 0);
  const std::vector<std::string> base{SHADOWREF_EXE, "compare", "--reference", (root / "r").string(), "--candidate",
                                      (root / "c").string(), "--json"};
  const auto without = test::run_command(base);
  EXPECT_EQ(without.exit_code, 2) << without.err;
  std::vector<std::string> with_scene = base;
  with_scene.insert(with_scene.end(), {"--scene", scene});
  const auto with = test::run_command(with_scene);
  EXPECT_EQ(with.exit_code, 0) << with.err << with.out;
  const nlohmann::json a = nlohmann::json::parse(without.out), b = nlohmann::json::parse(with.out);
  const nlohmann::json &ta = a["comparison"]["total"], &tb = b["comparison"]["total"];
  EXPECT_EQ(ta["wrong"], tb["wrong"]);  // the same pixels, explained or not
  EXPECT_GT(ta["unexplained"].get<int>(), 10 * tb["unexplained"].get<int>());
  // The text says what the verdict could have seen, as report.json does.
  with_scene.pop_back();
  with_scene.pop_back();
  std::erase(with_scene, std::string("--json"));
  with_scene.insert(with_scene.end(), {"--scene", scene});
  const auto text = test::run_command(with_scene);
  EXPECT_NE(text.out.find("  resolving power: "), std::string::npos) << text.out;
  EXPECT_TRUE(b.contains("resolving_power")) << with.out;
}


// One judge: `compare` and `conform` give the same verdict and counts for the same folder. Our
// correct pcss render of soft_penumbra with its visibility.png made all white (every pixel fully
// lit: the lit fraction wrong over the whole penumbra and umbra) FAILs under both; `compare` takes
// the technique from candidate.json (no --technique) and says so. The unmodified render is the
// control: PASS under both.
// Both commands on the same folder: the same exit code, verdict, counts, lit fraction and status.
struct BothJudges {
  fs::path root;
  std::string scene, scene_name, technique;
  int judge(const std::string& what) const {
    const fs::path cand = root / "cands" / scene_name;
    const auto c = test::run_command({SHADOWREF_EXE, "compare", "--reference", (root / "r").string(), "--candidate",
                                      cand.string(), "--scene", scene, "--json"});
    const fs::path out = root / ("conform-" + what);
    const auto k = test::run_command({SHADOWREF_EXE, "conform", "--scenes", scene_name, "--candidate-dir",
                                      (root / "cands").string(), "--technique", technique, "--out", out.string(),
                                      "--cache", (root / "cache").string(), "--quiet"});
    EXPECT_EQ(c.exit_code, k.exit_code) << what << ": compare " << c.err << "\nconform " << k.err << k.out;
    const nlohmann::json a = nlohmann::json::parse(c.out);
    std::ifstream in(out / "report.json");
    const nlohmann::json r = nlohmann::json::parse(in);
    const nlohmann::json& rc = r["cases"][0];
    EXPECT_EQ(a["technique"], technique) << what;
    EXPECT_EQ(a["technique_source"], "candidate.json") << what;
    EXPECT_EQ(a["comparison"]["verdict"], rc["comparison"]["verdict"]) << what;
    // One case shape: every key of the case is compare's too, with the same value, but what says
    // where conform's files and images are and when and where it ran; compare adds only its own three.
    const std::set<std::string> conform_only = {"scene_file", "frame_ms", "notes", "lights", "shaded", "reference_shaded",
                                                "read_through_links", "host", "shard"};
    const std::set<std::string> compare_only = {"technique_source", "error_images", "exit_code"};
    const std::set<std::string> differ = {"seconds", "reference_dir", "candidate_dir"};
    for (const auto& [key, value] : rc.items()) {
      if (conform_only.count(key)) continue;
      EXPECT_TRUE(a.contains(key)) << what << ": compare --json has no \"" << key << "\"";
      if (a.contains(key) && !differ.count(key)) EXPECT_EQ(a[key], value) << what << ": \"" << key << "\"";
    }
    for (const auto& [key, value] : a.items())
      EXPECT_TRUE(rc.contains(key) || compare_only.count(key)) << what << ": \"" << key << "\" is compare's alone";
    return c.exit_code;
  }
};

// Every technique of one scene, our own render each (a PASS, or the catalogue's XFAIL), and a
// blatant mutant of each (its mask inverted: FAIL): the two commands agree on all of them.
TEST_F(CompareCommand, CompareAndConformAgreeOnEveryTechniqueAndItsMutant) {
  const std::string scene = std::string(SHADOWREF_CATALOGUE) + "/cube_seams.json";
  ASSERT_EQ(test::run_command({SHADOWREF_EXE, "reference", "--scene", scene, "--out", (root / "r").string(), "--quiet"}).exit_code, 0);
  for (const auto& t : outputs::kTechniques) {
    const std::string technique(t.name);
    const fs::path cand = root / "cands" / "cube_seams";
    fs::remove_all(cand);
    ASSERT_EQ(test::run_command({SHADOWREF_EXE, "render", "--scene", scene, "--technique", technique, "--out", cand.string()}).exit_code, 0);
    const BothJudges both{root, scene, "cube_seams", technique};
    both.judge(technique);
    outputs::Image8 mask = outputs::read_image8(cand / "mask.png", 1);
    for (std::uint8_t& v : mask.pixels)
      if (v != outputs::kMaskNoSurface) v = v == outputs::kMaskLit ? outputs::kMaskShadowed : outputs::kMaskLit;
    outputs::write_png(mask, cand / "mask.png");
    EXPECT_EQ(both.judge(technique + "-inverted"), 2) << technique << ": an inverted mask must FAIL";
  }
}

TEST_F(CompareCommand, CompareAndConformGiveTheSameVerdict) {
  const std::string scene = std::string(SHADOWREF_CATALOGUE) + "/soft_penumbra.json";
  const fs::path cand = root / "cands" / "soft_penumbra";
  ASSERT_EQ(test::run_command({SHADOWREF_EXE, "reference", "--scene", scene, "--out", (root / "r").string(), "--quiet"}).exit_code, 0);
  ASSERT_EQ(test::run_command({SHADOWREF_EXE, "render", "--scene", scene, "--technique", "pcss", "--out", cand.string()}).exit_code, 0);
  const BothJudges both{root, scene, "soft_penumbra", "pcss"};
  EXPECT_EQ(both.judge("control"), 0);
  const outputs::Image8 vis = outputs::read_image8(cand / "visibility.png", 1);
  grey(cand / "visibility.png", vis.width, vis.height, 255);
  EXPECT_EQ(both.judge("all-white"), 2);
}

}  // namespace
}  // namespace shadowref
