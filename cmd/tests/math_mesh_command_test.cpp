// End-to-end tests of `shadowref math mesh-report` and `shadowref math silhouette`: the JSON
// answers, vertex indices of the OBJ file itself, and bad meshes (one line on stderr, exit 4,
// nothing on stdout). The OBJ files are written by the tests into a fresh temporary folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "run_command.hpp"

namespace shadowref {
namespace {

using nlohmann::json;
using test::CommandResult;

namespace fs = std::filesystem;

class MathMeshCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("shadowref-mesh-cli-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }

  static CommandResult cli(std::vector<std::string> args) {
    args.insert(args.begin(), SHADOWREF_EXE);
    return test::run_command(args);
  }

  static json run_json(const std::vector<std::string>& args) {
    const CommandResult r = cli(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    return json::parse(r.out);
  }

  static void expect_bad_mesh(const std::vector<std::string>& args, const std::string& says) {
    const CommandResult r = cli(args);
    EXPECT_EQ(r.exit_code, 4);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  }

  fs::path dir_;
};

// The cube [-1, 1]^3; vertex i has x = 1 if bit 0, y = 1 if bit 1, z = 1 if bit 2.
const char* kCube =
    "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n"
    "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\nf 1 3 4 2\nf 5 6 8 7\n";

TEST_F(MathMeshCommand, ReportOfAClosedCube) {
  const json j = run_json({"math", "mesh-report", "--mesh", write("cube.obj", kCube), "--json"});
  EXPECT_EQ(j.at("command"), "mesh-report");
  EXPECT_EQ(j.at("vertices"), 8);
  EXPECT_EQ(j.at("triangles"), 12);
  EXPECT_EQ(j.at("edges"), 18);
  EXPECT_EQ(j.at("open_edges"), 0);
  EXPECT_EQ(j.at("non_manifold_edges"), 0);
  EXPECT_EQ(j.at("miswound_edges"), 0);
  EXPECT_EQ(j.at("closed_manifold"), true);
}

TEST_F(MathMeshCommand, ReportOfBrokenMeshes) {
  // Open top (the +y face removed), a fin on the top front edge, one face walked backwards.
  std::string open = kCube;
  open.erase(open.find("f 3 7 8 4\n"), 10);
  json j = run_json({"math", "mesh-report", "--mesh", write("open.obj", open), "--json"});
  EXPECT_EQ(j.at("open_edges"), 4);
  EXPECT_EQ(j.at("closed_manifold"), false);
  j = run_json({"math", "mesh-report", "--mesh", write("fin.obj", std::string(kCube) + "v -1 2 2\nv 1 2 2\nf 7 8 10 9\n"), "--json"});
  EXPECT_EQ(j.at("non_manifold_edges"), 1);
  EXPECT_EQ(j.at("open_edges"), 3);
  std::string flipped = kCube;
  flipped.replace(flipped.find("f 1 5 7 3"), 9, "f 3 7 5 1");
  j = run_json({"math", "mesh-report", "--mesh", write("flipped.obj", flipped), "--json"});
  EXPECT_EQ(j.at("miswound_edges"), 4);  // the flipped quad's four sides (its diagonal is internal)
  EXPECT_EQ(j.at("closed_manifold"), false);
}

TEST_F(MathMeshCommand, SilhouetteOfACubeLitFromAbove) {
  const json j =
      run_json({"math", "silhouette", "--mesh", write("cube.obj", kCube), "--light", "0.2,10,0.1,1", "--json"});
  EXPECT_EQ(j.at("count"), 4);
  std::set<std::pair<int, int>> edges;
  for (const auto& e : j.at("edges")) edges.insert({e.at(0).get<int>(), e.at(1).get<int>()});
  // The top square 2 -> 6 -> 7 -> 3 (counter-clockwise from above), walked the other way.
  EXPECT_EQ(edges, (std::set<std::pair<int, int>>{{6, 2}, {7, 6}, {3, 7}, {2, 3}}));
}

TEST_F(MathMeshCommand, SilhouetteNamesTheFilesOwnVertices) {
  // The same cube with the vertex list reversed and every face using its own copies of the top
  // corners (split vertices, as exporters write them): the edges must name vertices whose
  // positions are the top square's corners, in the file's numbering.
  std::string obj;
  const double corner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {-1, 1, -1}, {1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {-1, 1, 1}, {1, 1, 1}};
  for (int i = 7; i >= 0; --i)
    obj += "v " + std::to_string(corner[i][0]) + " " + std::to_string(corner[i][1]) + " " + std::to_string(corner[i][2]) + "\n";
  for (int i : {2, 6, 7, 3})  // copies of the top corners: file vertices 9..12 (0-based 8..11)
    obj += "v " + std::to_string(corner[i][0]) + " " + std::to_string(corner[i][1]) + " " + std::to_string(corner[i][2]) + "\n";
  const auto f = [](int v) { return std::to_string(8 - v); };  // corner v -> 1-based file index
  obj += "f " + f(0) + " " + f(4) + " " + f(6) + " " + f(2) + "\nf " + f(1) + " " + f(3) + " " + f(7) + " " + f(5) + "\n";
  obj += "f " + f(0) + " " + f(1) + " " + f(5) + " " + f(4) + "\nf 9 10 11 12\n";  // top face on the copies
  obj += "f " + f(0) + " " + f(2) + " " + f(3) + " " + f(1) + "\nf " + f(4) + " " + f(5) + " " + f(7) + " " + f(6) + "\n";
  const json j = run_json({"math", "silhouette", "--mesh", write("split.obj", obj), "--light", "0.2,10,0.1,1", "--json"});
  EXPECT_EQ(j.at("count"), 4);
  std::set<std::pair<int, int>> edges;
  for (const auto& e : j.at("edges")) edges.insert({e.at(0).get<int>(), e.at(1).get<int>()});
  // The lit top face owns the silhouette: its copies 8..11 (corners 2, 6, 7, 3), walked backwards.
  EXPECT_EQ(edges, (std::set<std::pair<int, int>>{{9, 8}, {10, 9}, {11, 10}, {8, 11}}));
}

TEST_F(MathMeshCommand, BadMeshesAreOneLineAndExitCode4) {
  for (const char* sub : {"mesh-report", "silhouette"}) {
    SCOPED_TRACE(sub);
    const auto args = [&](const std::string& mesh) {
      std::vector<std::string> a{"math", sub, "--mesh", mesh};
      if (std::string(sub) == "silhouette") a.insert(a.end(), {"--light", "0,5,0,1"});
      return a;
    };
    expect_bad_mesh(args((dir_ / "missing.obj").string()), "no such file");
    expect_bad_mesh(args(write("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")), "uses vertex 9");
    expect_bad_mesh(args(write("empty.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")), "no triangles");
    expect_bad_mesh(args(write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")), "vertex 2");
  }
  expect_bad_mesh({"math", "silhouette", "--mesh", write("cube.obj", kCube), "--light", "0,5,0,-1"}, "w must be >= 0");
}

}  // namespace
}  // namespace shadowref
