// truth_test.cpp — compare_truth (truth.hpp): what it counts as a change of the truth (a decided
// pixel's value, a pixel decided in one reference only) and what only as another guess.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "shadowref/reference/truth.hpp"

namespace shadowref::reference {
namespace {

TEST(CompareTruth, CountsDecidedTruthAndGuessesApart) {
  const std::vector<std::uint8_t> mask_a{255, 0, 255, 128}, decided_a{255, 255, 0, 255};
  EXPECT_TRUE(compare_truth(mask_a, decided_a, mask_a, decided_a).agree());
  // pixel 2 is undecided: its guess may differ
  std::vector<std::uint8_t> mask_b = mask_a;
  mask_b[2] = 0;
  TruthComparison c = compare_truth(mask_a, decided_a, mask_b, decided_a);
  EXPECT_TRUE(c.agree());
  EXPECT_EQ(c.guesses_differ, 1u);
  EXPECT_EQ(c.first, -1);
  // pixel 1 is decided: its value is the truth
  mask_b[1] = 255;
  c = compare_truth(mask_a, decided_a, mask_b, decided_a);
  EXPECT_FALSE(c.agree());
  EXPECT_EQ(c.truth_differ, 1u);
  EXPECT_EQ(c.first, 1);
  // a pixel decided in one only
  std::vector<std::uint8_t> decided_b = decided_a;
  decided_b[3] = 0;
  c = compare_truth(mask_a, decided_a, mask_a, decided_b);
  EXPECT_FALSE(c.agree());
  EXPECT_EQ(c.decided_differ, 1u);
  EXPECT_EQ(c.first, 3);
  EXPECT_THROW(compare_truth(mask_a, decided_a, mask_a, std::vector<std::uint8_t>{0}), std::invalid_argument);
}

}  // namespace
}  // namespace shadowref::reference
