// cause_memo_test.cpp — the judge's memo of the cause model's answers (cause_memo.hpp): each
// remembered answer comes back for its own light, pixel and candidate answer alone, and nothing is
// remembered outside the image.
#include "cause_memo.hpp"

#include <gtest/gtest.h>

#include <tuple>

namespace shadowref::conform {
namespace {

using outputs::Cause;

TEST(CauseMemo, EachAnswerComesBackForItsOwnPixelLightAndCandidateAnswer) {
  CauseMemo::Table t(2, 5, 3);
  Cause c = Cause::Unexplained;
  EXPECT_FALSE(t.find(0, 1, 1, true, c)) << "an empty table knows nothing";
  // Every cause, under both candidate answers, at one pixel of each light: the two nibbles of a
  // byte and the two lights' tables stay apart.
  for (const Cause lit : {Cause::Unexplained, Cause::TexelFootprint, Cause::DepthBias, Cause::Acne})
    for (const Cause shadowed : {Cause::Unexplained, Cause::TexelFootprint, Cause::DepthBias, Cause::Acne}) {
      CauseMemo::Table m(2, 5, 3);
      m.remember(1, 4, 2, true, lit);
      EXPECT_FALSE(m.find(1, 4, 2, false, c)) << "the other answer is not known yet";
      m.remember(1, 4, 2, false, shadowed);
      ASSERT_TRUE(m.find(1, 4, 2, true, c));
      EXPECT_EQ(c, lit);
      ASSERT_TRUE(m.find(1, 4, 2, false, c));
      EXPECT_EQ(c, shadowed);
      EXPECT_FALSE(m.find(0, 4, 2, true, c)) << "light 0's table is its own";
      EXPECT_FALSE(m.find(1, 3, 2, true, c)) << "the pixel beside is its own";
      EXPECT_FALSE(m.find(1, 4, 1, true, c)) << "the pixel above is its own";
    }
}

TEST(CauseMemo, NothingOutsideTheImageIsRemembered) {
  CauseMemo::Table t(1, 4, 4);
  Cause c = Cause::Unexplained;
  for (const auto& [light, x, y] : {std::tuple<std::size_t, int, int>{0, -1, 0}, {0, 4, 0}, {0, 0, 4}, {0, 0, -1}, {1, 0, 0}}) {
    t.remember(light, x, y, true, Cause::TexelFootprint);
    EXPECT_FALSE(t.find(light, x, y, true, c)) << light << " " << x << " " << y;
  }
  EXPECT_EQ(t.bytes(), 16u);
}

}  // namespace
}  // namespace shadowref::conform
