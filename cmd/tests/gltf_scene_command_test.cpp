// gltf_scene_command_test.cpp — an engine team's own glTF scene on the command line
// (scene/gltf_scene.hpp): a catalogue scene exported by `shadowref export` and read back through its
// scene.gltf is judged PASS by `conform`; our renders of the glTF judged against the catalogue's
// JSON scene PASS (the two are one scene); the same glTF with its light turned, or its masks'
// alphaCutoff raised, FAILs beside that control; a glTF skin without weights is one line and exit 4.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
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

class GltfSceneCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("shadowref_gltf_scene_test_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(root_);
  }

  // The pack's scene.gltf of catalogue scene `name`, as <root>/<name>.gltf (the scene's name is the file's stem).
  fs::path exported(const std::string& name) {
    const test::CommandResult r = test::run_command({SHADOWREF_EXE, "export", "--scenes", name, "--out", (root_ / "pack").string(),
                                                     "--cache", (root_ / "cache").string()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const fs::path file = root_ / (name + ".gltf");
    fs::copy_file(root_ / "pack" / name / "scene.gltf", file, fs::copy_options::overwrite_existing);
    return file;
  }

  // `render` of `scene` (a file) with `technique` into <root>/<folder>/<scene name>/.
  void render(const fs::path& scene, const std::string& technique, const std::string& folder, const std::string& name) {
    const test::CommandResult r = test::run_command({SHADOWREF_EXE, "render", "--scene", scene.string(), "--technique", technique,
                                                     "--out", (root_ / folder / name).string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }

  // `conform` judging the renders in <root>/<folder> as `technique` on catalogue scene `name`.
  test::CommandResult judge(const std::string& name, const std::string& technique, const std::string& folder) {
    return test::run_command({SHADOWREF_EXE, "conform", "--scenes", name, "--technique", technique, "--candidate-dir",
                              (root_ / folder).string(), "--out", (root_ / ("judge-" + folder)).string(), "--cache",
                              (root_ / "cache").string(), "--quiet"});
  }

  // A wrong variant `g` of catalogue scene `name`'s glTF, rendered with `technique` into <root>/<folder>
  // and judged against the catalogue's JSON scene.
  test::CommandResult judge_variant(const std::string& name, const json& g, const std::string& technique, const std::string& folder) {
    const fs::path wrong = root_ / ("wrong-" + folder) / (name + ".gltf");
    fs::create_directories(wrong.parent_path());
    write(wrong, g);
    render(wrong, technique, folder, name);
    return judge(name, technique, folder);
  }

  static json read(const fs::path& f) { return json::parse(std::ifstream(f)); }
  static void write(const fs::path& f, const json& j) { std::ofstream(f) << j.dump(); }

  fs::path root_;
};

TEST_F(GltfSceneCommand, ConformOnAnExportedSceneGltfPasses) {
  const fs::path file = exported("ground_sphere");
  const test::CommandResult r = test::run_command({SHADOWREF_EXE, "conform", "--scenes", file.string(), "--techniques",
                                                   "planar,volume-zfail,shadowmap-pcf", "--out", (root_ / "out").string(),
                                                   "--cache", (root_ / "cache").string(), "--quiet"});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("3 cases: 3 PASS"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;  // the pack's glTF holds nothing unread
}

// The wrong variant beside its control: our render of the glTF, judged against the catalogue's JSON
// scene, PASSes; the same glTF with its directional light turned by 10 degrees FAILs.
TEST_F(GltfSceneCommand, TurnedLightFailsBesideItsControl) {
  const fs::path file = exported("directional_light");
  render(file, "shadowmap-pcf", "control", "directional_light");
  EXPECT_EQ(judge("directional_light", "shadowmap-pcf", "control").exit_code, 0);

  json g = read(file);
  bool turned = false;
  for (json& n : g["nodes"]) {
    if (!n.contains("extensions")) continue;
    // Prepend a rotation of 10 degrees about the scene's z axis to the light node's matrix (column-major).
    const double a = 10 * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
    std::vector<double> m = n["matrix"].get<std::vector<double>>();
    for (int col = 0; col < 4; ++col) {
      const double x = m[4 * col], y = m[4 * col + 1];
      m[4 * col] = c * x - s * y;
      m[4 * col + 1] = s * x + c * y;
    }
    n["matrix"] = m;
    turned = true;
  }
  ASSERT_TRUE(turned);
  const test::CommandResult r = judge_variant("directional_light", g, "shadowmap-pcf", "turned");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("FAIL"), std::string::npos) << r.out;
}

// The same for masks: every MASK material's alphaCutoff raised to 0.9 lets light through texels the
// catalogue's cards block.
TEST_F(GltfSceneCommand, RaisedAlphaCutoffFailsBesideItsControl) {
  const fs::path file = exported("alpha_cards");
  render(file, "shadowmap", "control", "alpha_cards");
  EXPECT_EQ(judge("alpha_cards", "shadowmap", "control").exit_code, 0);

  json g = read(file);
  int masks = 0;
  for (json& m : g["materials"])
    if (m.value("alphaMode", "") == "MASK") {
      m["alphaCutoff"] = 0.9;
      ++masks;
    }
  ASSERT_GT(masks, 0);
  const test::CommandResult r = judge_variant("alpha_cards", g, "shadowmap", "raised");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
}

// `export` of a glTF scene whose buffer is an external file: the pack's scenes/ carries both, and
// `conform --catalogue <pack>/scenes` (the pack README's own command) finds and judges it.
TEST_F(GltfSceneCommand, ExportOfAGltfSceneStandsAlone) {
  json g = read(exported("ground_sphere"));
  const std::string uri = g["buffers"][0]["uri"];
  const std::string base64 = uri.substr(uri.find(',') + 1);
  std::string bytes;  // RFC 4648 decoding, enough for the pack's padded base64
  int bits = 0, value = 0;
  for (const char c : base64) {
    const auto at = std::string("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/").find(c);
    if (at == std::string::npos) break;
    value = (value << 6) | static_cast<int>(at);
    if ((bits += 6) >= 8) bytes.push_back(static_cast<char>((value >> (bits -= 8)) & 0xff));
  }
  const fs::path level = root_ / "level";
  fs::create_directories(level / "bin");
  std::ofstream(level / "bin" / "geometry.bin", std::ios::binary) << bytes;
  g["buffers"][0]["uri"] = "bin/geometry.bin";
  write(level / "my_level.gltf", g);
  const test::CommandResult e = test::run_command({SHADOWREF_EXE, "export", "--scenes", (level / "my_level.gltf").string(), "--out",
                                                   (root_ / "level-pack").string(), "--cache", (root_ / "cache").string()});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_TRUE(fs::is_regular_file(root_ / "level-pack" / "scenes" / "bin" / "geometry.bin"));
  EXPECT_TRUE(fs::is_regular_file(root_ / "level-pack" / "my_level" / "scene.gltf"));
  const test::CommandResult r = test::run_command({SHADOWREF_EXE, "conform", "--catalogue", (root_ / "level-pack" / "scenes").string(),
                                                   "--techniques", "planar", "--out", (root_ / "level-out").string(), "--cache",
                                                   (root_ / "cache").string(), "--quiet"});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("1 cases: 1 PASS"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("my_level"), std::string::npos) << r.out;
}

TEST_F(GltfSceneCommand, SkinWithoutWeightsIsOneLineAndExitFour) {
  const fs::path file = exported("ground_sphere");
  json g = read(file);
  g["skins"] = {{{"joints", {0}}}};
  for (json& n : g["nodes"])
    if (n.contains("mesh")) {
      n["skin"] = 0;
      break;
    }
  write(file, g);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"render", "--scene", file.string(), "--technique", "planar", "--out", (root_ / "r").string()},
        std::vector<std::string>{"reference", "--scene", file.string(), "--out", (root_ / "ref").string(), "--spp", "1"},
        std::vector<std::string>{"conform", "--scenes", file.string(), "--out", (root_ / "c").string(), "--quiet"},
        std::vector<std::string>{"export", "--scenes", file.string(), "--out", (root_ / "p").string()}}) {
    std::vector<std::string> argv{SHADOWREF_EXE};
    argv.insert(argv.end(), args.begin(), args.end());
    const test::CommandResult r = test::run_command(argv);
    EXPECT_EQ(r.exit_code, 4) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find(file.string() + ": node "), std::string::npos) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find("a primitive of a skinned mesh lacks JOINTS_0 or WEIGHTS_0"), std::string::npos) << args[0] << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args[0] << ": " << r.err;
  }
}

// What is not read is said once, as a warning, and the run goes on.
TEST_F(GltfSceneCommand, UnreadTexturesAreOneWarningLine) {
  const fs::path file = exported("ground_sphere");
  json g = read(file);
  g["images"] = {{{"uri", "data:image/png;base64,AAAA"}}};
  g["textures"] = {{{"source", 0}}};
  for (json& m : g["materials"]) m["normalTexture"] = {{"index", 0}};
  write(file, g);
  const test::CommandResult r = test::run_command({SHADOWREF_EXE, "reference", "--scene", file.string(), "--out",
                                                   (root_ / "ref").string(), "--spp", "1"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("shadowref: warning: " + file.string() + ": 2 texture reference(s) other than MASK"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
}  // namespace shadowref
