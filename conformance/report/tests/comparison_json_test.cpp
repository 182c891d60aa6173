// comparison_json_test.cpp — report.json's mask metrics: every count the error classes' table names
// (outputs/cause.hpp) is a key of a mask's metrics, with that class's count.
#include <gtest/gtest.h>

#include "shadowref/outputs/cause.hpp"
#include "shadowref/report/comparison_json.hpp"

namespace shadowref::report {
namespace {

TEST(ComparisonJson, EveryErrorClassKeyIsAMetricWithItsCount) {
  compare::MaskMetrics m;
  m.false_shadow = 1;
  m.unexplained_acne = 2;
  m.false_light = 3;
  m.coverage = 4;
  m.explained_texel = 5;
  m.explained_bias = 6;
  const nlohmann::json j = to_json(m);
  std::size_t expected = 1;
  for (const outputs::ErrorClassRow& r : outputs::kErrorClasses) {
    if (r.json_key.empty()) continue;
    ASSERT_TRUE(j.contains(std::string(r.json_key))) << r.name;
    EXPECT_EQ(j[std::string(r.json_key)].get<std::size_t>(), expected++) << r.name;
  }
  EXPECT_EQ(expected, 7u);
}

}  // namespace
}  // namespace shadowref::report
