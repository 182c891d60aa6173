// determinism_test.cpp — the reference's outputs are bit-identical across runs and thread counts
// (render.hpp): in memory, and as files.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "shadowref/reference/render.hpp"
#include "shadowref/reference/write_images.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace shadowref::reference {
namespace {

const std::filesystem::path kScenes = SHADOWREF_SCENES_DIR;

void expect_identical(const Images& a, const Images& b) {
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_EQ(a.lights[i].mask, b.lights[i].mask);
    EXPECT_EQ(a.lights[i].decided, b.lights[i].decided);
    // Bitwise, not ==: the same float bits, including −1 for no surface.
    ASSERT_EQ(a.lights[i].visibility.size(), b.lights[i].visibility.size());
    EXPECT_EQ(0, std::memcmp(a.lights[i].visibility.data(), b.lights[i].visibility.data(), a.lights[i].visibility.size() * sizeof(float)));
  }
  EXPECT_EQ(a.shaded, b.shaded);
  EXPECT_EQ(a.decided, b.decided);
  EXPECT_EQ(a.covered, b.covered);
  EXPECT_EQ(0, std::memcmp(a.visibility.data(), b.visibility.data(), a.visibility.size() * sizeof(float)));
}

std::string bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Scenes with soft shadows, several lights and many triangles, where scheduling could leak in.
class Determinism : public ::testing::TestWithParam<const char*> {};

TEST_P(Determinism, OneThreadEqualsAllThreads) {
  const scene::Scene s = scene::load_scene(kScenes / (std::string(GetParam()) + ".json"));
  Options one;
  one.samples_per_axis = 2;
  one.threads = 1;
  Options all = one;
  all.threads = 0;
  const Images a = render(s, one);
  const Images b = render(s, all);
  expect_identical(a, b);
  expect_identical(b, render(s, all));  // and two runs on all threads
}

INSTANTIATE_TEST_SUITE_P(Reference, Determinism, ::testing::Values("ground_sphere", "two_lights", "cornell_box", "stairs_room"));

TEST(Determinism, FilesAreByteIdentical) {
  const scene::Scene s = scene::load_scene(kScenes / "two_lights.json");
  Options o;
  o.samples_per_axis = 2;
  const auto dir = std::filesystem::path(::testing::TempDir()) / "shadowref_determinism";
  std::filesystem::remove_all(dir);
  const auto names = write_images(render(s, o), dir / "a");
  o.threads = 1;
  EXPECT_EQ(write_images(render(s, o), dir / "b"), names);
  ASSERT_EQ(names.size(), 10u);  // 3 per light, the two aggregates, covered.png and shaded.png
  for (const auto& n : names) {
    EXPECT_FALSE(bytes(dir / "a" / n).empty()) << n;
    EXPECT_EQ(bytes(dir / "a" / n), bytes(dir / "b" / n)) << n;
  }
  // No temporary file is left behind.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir / "a")) ++files;
  EXPECT_EQ(files, names.size());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace shadowref::reference
