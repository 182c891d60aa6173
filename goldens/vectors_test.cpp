// vectors_test.cpp — mathlib reproduces every committed golden vector (goldens/vectors/*.json):
// the hand-derived closed forms and the generated ones (made by make_vectors.cpp from oracles
// independent of mathlib). Each file's d3dx entry must also be its canonical entry transposed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "shadowref/projection.hpp"
#include "shadowref/shadow_matrix.hpp"

namespace shadowref {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

Mat4<double> matrix(const json& rows) {
  Mat4<double> m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = rows.at(r).at(c).get<double>();
  return m;
}

ClipConvention convention(const json& c) {
  return {c.at("hand") == "lh" ? Handedness::Left : Handedness::Right,
          c.at("depth") == "zero-to-one" ? DepthRange::ZeroToOne : DepthRange::NegOneToOne,
          c.at("reversed").get<bool>() ? DepthOrder::Reversed : DepthOrder::Standard};
}

Result<Mat4<double>> compute(const json& c) {
  const std::string kind = c.at("kind");
  if (kind == "shadow") {
    const auto p = c.at("plane").get<std::array<double, 4>>();
    const auto l = c.at("light").get<std::array<double, 4>>();
    return shadow_matrix(Plane<double>{Vec4<double>(p[0], p[1], p[2], p[3])}, Vec4<double>(l[0], l[1], l[2], l[3]));
  }
  const double eps = c.value("epsilon", 0.0);
  if (kind == "perspective") {
    if (c.at("far").is_null()) return perspective_infinite<double>(c.at("fovy"), c.at("aspect"), c.at("near"), convention(c), eps);
    return perspective<double>(c.at("fovy"), c.at("aspect"), c.at("near"), c.at("far"), convention(c));
  }
  if (kind == "frustum")
    return frustum<double>(c.at("left"), c.at("right"), c.at("bottom"), c.at("top"), c.at("near"), c.at("far"), convention(c));
  if (kind == "frustum_infinite")
    return frustum_infinite<double>(c.at("left"), c.at("right"), c.at("bottom"), c.at("top"), c.at("near"), convention(c), eps);
  if (kind == "ortho")
    return ortho<double>(c.at("left"), c.at("right"), c.at("bottom"), c.at("top"), c.at("near"), c.at("far"), convention(c));
  ADD_FAILURE() << "unknown kind " << kind;
  return Error::NonFinite;
}

TEST(GoldenVectors, MathlibReproducesEveryCommittedVector) {
  int files = 0, cases = 0;
  for (const auto& entry : fs::directory_iterator(SHADOWREF_VECTORS_DIR)) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    std::ifstream in(entry.path());
    const json doc = json::parse(in);
    const bool hand = entry.path().filename() == "hand_derived.json";
    for (const json& c : doc.at("cases")) {
      ++cases;
      const std::string where = entry.path().filename().string() + ": " + c.at("name").get<std::string>();
      const Mat4<double> canonical = matrix(c.at("canonical")), d3dx = matrix(c.at("d3dx"));
      EXPECT_EQ(d3dx, canonical.transpose()) << where << ": d3dx must be the transpose";
      const auto ours = compute(c);
      ASSERT_TRUE(ours.ok()) << where << ": " << ours.message();
      if (hand) {
        EXPECT_EQ(*ours, canonical) << where << " (hand-derived values are exact in binary)";
        continue;
      }
      // Generated values were rounded once to double from long double or come from GLM's double
      // arithmetic in another expression order; mathlib rounds in double too. 8 ulps of the
      // matrix's largest entry bounds the difference of two such evaluations of a 4-term formula.
      const double tol = 8 * std::numeric_limits<double>::epsilon() * std::max(1.0, canonical.cwiseAbs().maxCoeff());
      EXPECT_LE((*ours - canonical).cwiseAbs().maxCoeff(), tol) << where << "\nours:\n" << *ours << "\ngolden:\n" << canonical;
    }
  }
  EXPECT_GE(files, 3) << "hand_derived.json and the two generated files";
  EXPECT_GE(cases, 100);
}

}  // namespace
}  // namespace shadowref
