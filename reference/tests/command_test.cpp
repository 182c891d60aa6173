// command_test.cpp — `shadowref reference` as a script sees it: files written, exit code 0; a bad
// scene file gives one line naming the JSON path, and exit code 4.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <fstream>

namespace {

struct CommandRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

CommandRun run(const std::string& args) {
  CommandRun r;
  const std::string cmd = std::string(SHADOWREF_EXE) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A fresh folder per test: CTest runs each test as its own process, in parallel, so a folder
// shared between tests (one of them clearing it) made them race.
std::filesystem::path fresh_dir() {
  const auto dir = std::filesystem::path(::testing::TempDir()) /
                   (std::string("shadowref_reference_cli_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(ReferenceCommand, WritesTheFourImages) {
  const auto dir = fresh_dir();
  const CommandRun r = run("reference --scene " SHADOWREF_SCENES_DIR "/ground_sphere.json --spp 1 --out " + (dir / "gs").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"mask.png", "shaded.png", "visibility.exr", "decided.png"}) EXPECT_TRUE(std::filesystem::exists(dir / "gs" / f)) << f;
}

TEST(ReferenceCommand, BadSceneNamesJsonPathAndExits4) {
  const auto dir = fresh_dir();
  const auto bad = dir / "bad.json";
  std::ofstream(bad) << R"({"name": "bad", "camera": {"position": [0, 4, 8], "target": [0, 0, 0]},
    "lights": [{"type": "point", "position": [0, 5, 0]}],
    "objects": [{"shape": {"type": "plane", "size": [1, 1]}}, {"shape": {"type": "plane", "size": [1, 1]}},
                {"shape": {"type": "sphere", "radius": -1}}]})";
  const CommandRun r = run("reference --scene " + bad.string() + " --out " + (dir / "bad_out").string());
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_EQ(r.output, "shadowref reference: " + bad.string() + ": objects[2].shape.radius: must be > 0\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "bad_out"));
}

TEST(ReferenceCommand, BadOptionsExit4) {
  const auto dir = fresh_dir();
  EXPECT_EQ(run("reference --scene " SHADOWREF_SCENES_DIR "/ground_sphere.json --spp 3 --out " + (dir / "x").string()).exit_code, 4);
  EXPECT_EQ(run("reference --scene /nonexistent.json --out " + (dir / "x").string()).exit_code, 4);
}

}  // namespace
