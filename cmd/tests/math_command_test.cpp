// End-to-end tests of `shadowref math`: the JSON interface scripts rely on, the human table, and
// bad input (one line on stderr naming the problem, exit code 4, nothing on stdout).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <numbers>

#include "run_command.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/shadow_matrix.hpp"

namespace shadowref {
namespace {

using nlohmann::json;
using test::CommandResult;
using test::run_command;

CommandResult shadowref_cli(std::vector<std::string> args) {
  args.insert(args.begin(), SHADOWREF_EXE);
  return run_command(args);
}

template <class T>
Mat4<T> matrix_from_json(const json& j) {
  Mat4<T> m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = j.at("matrix").at(r).at(c).get<T>();
  return m;
}

json run_json(const std::vector<std::string>& args) {
  const CommandResult r = shadowref_cli(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  return json::parse(r.out);
}

TEST(MathCommand, ShadowMatrixJsonIsExactlyMathlibsMatrix) {
  const json j = run_json({"math", "shadow-matrix", "--plane", "0.2,1,-0.4,0.7", "--light", "1.5,6,-2,1", "--json"});
  const Mat4<double> expected = *shadow_matrix(Plane<double>{Vec4<double>(0.2, 1, -0.4, 0.7)}, Vec4<double>(1.5, 6, -2, 1));
  EXPECT_EQ(matrix_from_json<double>(j), expected);  // printed with round-trip digits: bit-exact
  EXPECT_EQ(j.at("layout"), "canonical");
  EXPECT_EQ(j.at("precision"), "double");
  EXPECT_EQ(j.at("light_type"), "point");
}

TEST(MathCommand, D3dxLayoutIsTheTransposeWithFieldsRowByRow) {
  const json c = run_json({"math", "shadow-matrix", "--plane", "0,1,0,0", "--light", "2,6,1,1", "--json"});
  const json d = run_json({"math", "shadow-matrix", "--plane", "0,1,0,0", "--light", "2,6,1,1", "--layout", "d3dx", "--json"});
  EXPECT_EQ(matrix_from_json<double>(d), matrix_from_json<double>(c).transpose());
  // _21 = −L.x · b = −2 (the classic listing), i.e. matrix[1][0].
  EXPECT_EQ(d.at("matrix").at(1).at(0).get<double>(), -2.0);
  EXPECT_EQ(d.at("matrix").at(0).at(0).get<double>(), 6.0);  // _11 = P·L − L.x a = 6
}

TEST(MathCommand, FloatPrecisionRoundTripsToTheFloatComputation) {
  const json j = run_json({"math", "shadow-matrix", "--plane", "0.3,0.9,0.1,2.5", "--light", "0.1,4.7,-3.3,1",
                           "--precision", "float", "--json"});
  const Mat4<float> expected =
      *shadow_matrix(Plane<float>{Vec4<float>(0.3f, 0.9f, 0.1f, 2.5f)}, Vec4<float>(0.1f, 4.7f, -3.3f, 1.0f));
  EXPECT_EQ(matrix_from_json<float>(j), expected);
  EXPECT_EQ(j.at("precision"), "float");
}

TEST(MathCommand, PerspectiveVariants) {
  const double fovy = 60.0 * std::numbers::pi / 180.0;
  const json inf = run_json({"math", "perspective", "--fovy-deg", "60", "--aspect", "1.5", "--near", "0.1", "--json"});
  EXPECT_EQ(inf.at("infinite"), true);
  EXPECT_EQ(matrix_from_json<double>(inf), *perspective_infinite(fovy, 1.5, 0.1));
  const json fin = run_json({"math", "perspective", "--fovy-deg", "60", "--aspect", "1.5", "--near", "0.1", "--far", "100",
                             "--hand", "lh", "--depth", "zero-to-one", "--json"});
  EXPECT_EQ(matrix_from_json<double>(fin), *perspective(fovy, 1.5, 0.1, 100.0, kDirect3D));
  const json rev = run_json({"math", "perspective", "--fovy-deg", "60", "--aspect", "1", "--near", "0.5", "--depth",
                             "zero-to-one", "--reversed", "--json"});
  EXPECT_EQ(rev.at("matrix").at(2), json::array({0.0, 0.0, 0.0, 0.5}));  // RH reversed infinite: (0, 0, 0, n)
  const json eps = run_json({"math", "perspective", "--fovy-deg", "60", "--aspect", "1", "--near", "0.5", "--infinite",
                             "--epsilon", "0.001", "--layout", "d3dx", "--json"});
  // D3DX layout: the canonical third row (0, 0, ε−1, (ε−2) n) becomes the third column.
  EXPECT_EQ(eps.at("matrix").at(2).at(2).get<double>(), 0.001 - 1.0);
  EXPECT_EQ(eps.at("matrix").at(3).at(2).get<double>(), (0.001 - 2.0) * 0.5);
}

TEST(MathCommand, PlaneFromPointsAndFromPointNormal) {
  const json a = run_json({"math", "plane", "--points", "0,1,0", "0,1,1", "1,1,0", "--json"});
  EXPECT_EQ(a.at("plane"), json::array({0.0, 1.0, 0.0, -1.0}));
  const json b = run_json({"math", "plane", "--point", "1,2,3", "--normal", "0,0,2", "--normalize", "--json"});
  EXPECT_EQ(b.at("plane"), json::array({0.0, 0.0, 1.0, -3.0}));
}

TEST(MathCommand, TextOutputIsATableForPeople) {
  const CommandResult r = shadowref_cli({"math", "shadow-matrix", "--plane", "0,1,0,0", "--light", "0,10,0,1"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("[ 10   0   0   0 ]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("[  0  -1   0  10 ]"), std::string::npos) << r.out;
}

TEST(MathCommand, HelpExitsZeroAndListsEveryOption) {
  const CommandResult r = shadowref_cli({"math", "perspective", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* opt : {"--fovy-deg", "--aspect", "--near", "--far", "--infinite", "--epsilon", "--depth", "--hand",
                          "--reversed", "--layout", "--precision", "--json"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

struct BadCase {
  std::vector<std::string> args;
  std::string must_mention;
};

TEST(MathCommand, BadInputGetsOneLineAndExitCode4) {
  const std::vector<BadCase> cases = {
      {{"math", "shadow-matrix", "--plane", "0,1,x,0", "--light", "0,5,0,1"}, "--plane"},
      {{"math", "shadow-matrix", "--plane", "0,1,0", "--light", "0,5,0,1"}, "expected 4"},
      {{"math", "shadow-matrix", "--plane", "0,1,0,0", "--light", "0,5,0,nan"}, "--light"},
      {{"math", "shadow-matrix", "--plane", "0,1,0,0", "--light", "0,1e999,0,1"}, "--light"},
      {{"math", "shadow-matrix", "--plane", "0,0,0,1", "--light", "0,5,0,1"}, "zero length"},
      {{"math", "shadow-matrix", "--plane", "0,1,0,0", "--light", "3,0,2,1"}, "lies on the plane"},
      {{"math", "shadow-matrix", "--plane", "0,1,0,0", "--light", "0,0,0,0"}, "all zeros"},
      {{"math", "shadow-matrix", "--plane", "0,1,0,0"}, "--light"},
      {{"math", "shadow-matrix", "--plane", "0,1,0,0", "--light", "0,5,0,1", "--layout", "rowmajor"}, "--layout"},
      {{"math", "perspective", "--fovy-deg", "60", "--aspect", "1", "--near", "0"}, "near must be > 0"},
      {{"math", "perspective", "--fovy-deg", "60", "--aspect", "1", "--near", "1", "--far", "0.5"}, "far must be > near"},
      {{"math", "perspective", "--fovy-deg", "60", "--aspect", "0", "--near", "1"}, "aspect"},
      {{"math", "perspective", "--fovy-deg", "180", "--aspect", "1", "--near", "1"}, "fovy"},
      {{"math", "perspective", "--fovy-deg", "60", "--aspect", "1", "--near", "1", "--reversed"}, "zero-to-one"},
      {{"math", "perspective", "--fovy-deg", "60", "--aspect", "1", "--near", "1", "--far", "9", "--infinite"}, "--infinite"},
      {{"math", "perspective", "--fovy-deg", "60", "--aspect", "1", "--near", "1", "--far", "9", "--epsilon", "0.1"}, "--epsilon"},
      {{"math", "perspective", "--fovy-deg", "60", "--aspect", "1", "--near", "1", "--epsilon", "1"}, "epsilon"},
      {{"math", "perspective", "--fovy-deg", "abc", "--aspect", "1", "--near", "1"}, "--fovy-deg"},
      {{"math", "plane", "--points", "0,0,0", "1,1,1", "2,2,2"}, "collinear"},
      {{"math", "plane", "--point", "0,0,0"}, "--normal"},
      {{"math", "plane"}, "--points"},
      {{"math", "frobnicate"}, "frobnicate"},
      {{"math"}, "subcommand"},
      {{}, "subcommand"},
  };
  for (const BadCase& c : cases) {
    const CommandResult r = shadowref_cli(c.args);
    std::string cmdline;
    for (const auto& a : c.args) cmdline += a + " ";
    EXPECT_EQ(r.exit_code, 4) << cmdline << "\n" << r.err;
    EXPECT_EQ(r.out, "") << cmdline;
    ASSERT_FALSE(r.err.empty()) << cmdline;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << cmdline << ": one line\n" << r.err;
    EXPECT_NE(r.err.find(c.must_mention), std::string::npos) << cmdline << ": should mention '" << c.must_mention << "'\n"
                                                            << r.err;
  }
}

}  // namespace
}  // namespace shadowref
