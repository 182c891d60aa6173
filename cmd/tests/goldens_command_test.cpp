// goldens_command_test.cpp — `shadowref goldens --check` holds the goldens' truth: a decided pixel
// flipped in a golden mask or decided image is a change (exit 2, CHANGED); an undecided pixel's
// other guess is not (exit 0, a note), since Embree's kernel for the CPU may guess it otherwise
// (reference/truth.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_command.hpp"
#include "shadowref/outputs/image_io.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldens = SHADOWREF_GOLDENS_DIR;
const char* const kScene = "ground_sphere";  // one light: mask.png beside decided.png

class GoldensCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per test: CTest runs them side by side.
    work_ = fs::path(::testing::TempDir()) /
            ("shadowref_goldens_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(work_);
    fs::create_directories(work_ / "goldens");
    fs::copy(kGoldens / kScene, work_ / "goldens" / kScene);
    mask_ = outputs::read_image8(folder() / "mask.png", 1);
    decided_ = outputs::read_image8(folder() / "decided.png", 1);
  }
  void TearDown() override { fs::remove_all(work_); }

  fs::path folder() const { return work_ / "goldens" / kScene; }
  test::CommandResult check() const {
    return test::run_command({SHADOWREF_EXE, "goldens", "--check", "--dir", (work_ / "goldens").string(), "--scenes",
                              kScene, "--jobs", "1"});
  }
  // The first pixel whose decided value is `decided` (255 or 0) and whose mask is a lit or shadowed surface.
  std::size_t first_pixel(std::uint8_t decided) const {
    for (std::size_t i = 0; i < mask_.pixels.size(); ++i)
      if (decided_.pixels[i] == decided && mask_.pixels[i] != 128) return i;
    ADD_FAILURE() << "no such pixel in the golden";
    return 0;
  }
  void flip_mask(std::size_t i) {
    outputs::Image8 m = mask_;
    m.pixels[i] = m.pixels[i] == 255 ? 0 : 255;
    outputs::write_png(m, folder() / "mask.png");
  }

  fs::path work_;
  outputs::Image8 mask_, decided_;
};

TEST_F(GoldensCheck, TheCommittedGoldenHoldsItsTruth) {
  const test::CommandResult r = check();
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("hold the same truth"), std::string::npos) << r.out;
}

TEST_F(GoldensCheck, AFlippedDecidedPixelIsAChange) {
  flip_mask(first_pixel(255));
  const test::CommandResult r = check();
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("CHANGED " + (folder() / "mask.png").string() + ": 1 decided pixel(s) differ"), std::string::npos)
      << r.out;
}

TEST_F(GoldensCheck, AFlippedDecidedImageIsAChange) {
  outputs::Image8 d = decided_;
  const std::size_t i = first_pixel(255);
  d.pixels[i] = 0;
  outputs::write_png(d, folder() / "decided.png");
  const test::CommandResult r = check();
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("CHANGED " + (folder() / "decided.png").string() + ": 1 pixel(s) differ"), std::string::npos)
      << r.out;
}

TEST_F(GoldensCheck, AnUndecidedPixelsOtherGuessIsANote) {
  flip_mask(first_pixel(0));
  const test::CommandResult r = check();
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("note    " + (folder() / "mask.png").string() + ": 1 undecided pixel(s) guessed otherwise"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("CHANGED"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace shadowref
