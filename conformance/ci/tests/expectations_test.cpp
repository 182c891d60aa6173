// expectations_test.cpp — an engine team's expectations files (expectations.hpp): what is read, what
// is refused with its file and line, each outcome and its exit code, stale lines and the next file.
#include <gtest/gtest.h>

#include <fstream>
#include <unistd.h>

#include "shadowref/ci/expectations.hpp"

namespace shadowref::ci {
namespace {

namespace fs = std::filesystem;

fs::path write(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("shadowref-expectations-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

std::string refusal(const std::string& text) {
  try {
    read_expectations({write("bad.txt", text)});
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Expectations, ReadsCasesCommentsAndSections) {
  const Expectations e = read_expectations({write("fails.txt",
                                                  "# three.js: the point light's near plane (https://bugs.example/1)\n"
                                                  "light_near_caster@shadowmap,FAIL   # bug 1\n"
                                                  "\n"
                                                  "sun_horizon@shadowmap@d3d,WARN\n"
                                                  "[flakes]\n"
                                                  "^soft_.*@pcss@\n"
                                                  "[skips]\n"
                                                  "^large_sphere@\n")});
  ASSERT_EQ(e.lines.size(), 2u);
  EXPECT_EQ(e.lines[0].status, Status::Fail);
  EXPECT_NE(e.lines[0].where.find("fails.txt:2"), std::string::npos);
  EXPECT_EQ(e.lines[0].text, "light_near_caster@shadowmap,FAIL   # bug 1");
  EXPECT_NE(e.line_for("light_near_caster", "shadowmap", "reversed-z"), nullptr);  // no convention: every one
  EXPECT_NE(e.line_for("sun_horizon", "shadowmap", "d3d"), nullptr);
  EXPECT_EQ(e.line_for("sun_horizon", "shadowmap", "gl"), nullptr);
  EXPECT_TRUE(e.flaky("soft_penumbra@pcss@gl"));
  EXPECT_FALSE(e.flaky("soft_penumbra@vsm@gl"));
  EXPECT_TRUE(e.skipped("large_sphere@planar@gl"));
}

TEST(Expectations, BadInputIsOneLineNamingFileAndLine) {
  EXPECT_NE(refusal("ground_sphere@planar\n").find("bad.txt:1: "), std::string::npos);
  EXPECT_NE(refusal("# ok\nground_sphere@planar,BROKEN\n").find("bad.txt:2: unknown status 'BROKEN'"), std::string::npos);
  EXPECT_NE(refusal("ground_sphere@planar,PASS\n").find("remove the line"), std::string::npos);
  EXPECT_NE(refusal("ground_sphere@planar@vulkan,FAIL\n").find("unknown convention 'vulkan'"), std::string::npos);
  EXPECT_NE(refusal("../x@planar,FAIL\n").find("bad.txt:1: '../x'"), std::string::npos);
  EXPECT_NE(refusal("[flakes]\n(unclosed\n").find("bad.txt:2: bad regex '(unclosed'"), std::string::npos);
  EXPECT_NE(refusal("[fails]\n").find("unknown section"), std::string::npos);
  EXPECT_NE(refusal("a@planar,FAIL\na@planar@gl,WARN\n").find("bad.txt:2: case a@planar is listed already at"), std::string::npos);
  try {
    read_expectations({"/nonexistent/fails.txt"});
    ADD_FAILURE() << "accepted a missing file";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/fails.txt: cannot read the expectations file");
  }
  for (const std::string& m : {refusal("x"), refusal("[skips]\n(")}) EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

// Hostile patterns, as a CI's own files may hold: RE2 matches in linear time and builds no
// recursion from the pattern's nesting, so none of them crashes or stalls the run.
TEST(Expectations, HostileRegexesAreMatchedOrRefusedAtOnce) {
  // Backtracking blow-up for a backtracking engine: here an ordinary search.
  const Expectations e = read_expectations({write("hostile.txt", "[flakes]\n(.*)*(.*)*(.*)*(.*)*(.*)*(.*)*(.*)*x$\n")});
  EXPECT_FALSE(e.flaky(std::string(60, 'a') + "@shadowmap@gl"));
  EXPECT_TRUE(e.flaky(std::string(60, 'a') + "x"));
  // 30 000 nested groups: std::regex overflowed the stack on them. RE2 compiles them or refuses
  // the program's size, in one line either way.
  const std::string nested = std::string(30000, '(') + "a" + std::string(30000, ')');
  const std::string m = refusal("[skips]\n" + nested + "\n");
  if (m != "(accepted)") {
    EXPECT_NE(m.find("bad.txt:2: bad regex '((((("), std::string::npos) << m.substr(0, 200);
    EXPECT_EQ(m.find('\n'), std::string::npos);
    EXPECT_LT(m.size(), 400u) << "the message repeats the whole pattern";
  }
  // A pattern RE2 does not have (a back-reference) is refused, naming RE2's syntax.
  EXPECT_NE(refusal("[flakes]\n(a)\\1\n").find("(RE2 syntax)"), std::string::npos);
}

// A UTF-8 byte-order mark, which editors on Windows write first, is not part of the first line.
TEST(Expectations, AByteOrderMarkIsSkipped) {
  const Expectations e = read_expectations({write("bom.txt", "\xEF\xBB\xBFlight_near_caster@shadowmap,FAIL\r\n")});
  ASSERT_EQ(e.lines.size(), 1u);
  EXPECT_EQ(e.lines[0].scene, "light_near_caster");
  // Only at the start of the file: elsewhere it is a byte of a name, refused as one.
  EXPECT_NE(refusal("# x\n\xEF\xBB\xBF" "a@planar,FAIL\n").find("bad.txt:2: "), std::string::npos);
}

// A line limited to an environment (a FAIL known on WebGPU only): it holds for cases rendered
// there; the same case on WebGL2 is unlisted, and the line is not stale in a run without WebGPU.
TEST(Expectations, LinesLimitedToAnEnvironment) {
  const Expectations e = read_expectations({write("env.txt",
                                                  "light_near_caster@shadowmap,FAIL,api=webgpu  # three.js WebGPU only\n"
                                                  "light_near_caster@shadowmap,WARN,api=webgl2 adapter=SwiftShader\n")});
  const outputs::Environment webgpu{{"api", "webgpu"}, {"adapter", "google swiftshader"}};
  const outputs::Environment webgl2{{"api", "webgl2"}, {"adapter", "ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device))"}};
  ASSERT_NE(e.line_for("light_near_caster", "shadowmap", "gl", webgpu), nullptr);
  EXPECT_EQ(e.line_for("light_near_caster", "shadowmap", "gl", webgpu)->status, Status::Fail);
  ASSERT_NE(e.line_for("light_near_caster", "shadowmap", "gl", webgl2), nullptr) << "a condition matches case aside";
  EXPECT_EQ(e.line_for("light_near_caster", "shadowmap", "gl", webgl2)->status, Status::Warn);
  EXPECT_EQ(e.line_for("light_near_caster", "shadowmap", "gl", {}), nullptr) << "no environment declared: no condition holds";
  EXPECT_EQ(e.line_for("light_near_caster", "shadowmap", "gl", {{"api", "webgl2"}}), nullptr) << "its adapter is not given";
  // Stale only in a run of its own environment.
  EXPECT_TRUE(stale_lines(e, {"light_near_caster"}, {"shadowmap"}, "gl", {webgl2}).empty());
  const auto stale = stale_lines(e, {"ground_sphere"}, {"shadowmap"}, "gl", {{{"api", "webgl2"}}});
  EXPECT_TRUE(stale.empty()) << "no case of the run meets either line's conditions";
  const auto stale_webgpu = stale_lines(e, {"ground_sphere"}, {"shadowmap"}, "gl", {webgpu});
  ASSERT_EQ(stale_webgpu.size(), 1u);
  EXPECT_EQ(stale_webgpu[0]->status, Status::Fail);
  // A new failure seen on one API is written limited to it.
  const std::string next = expectations_update_text(
      read_expectations({write("none.txt", "")}), {{"cube_seams", "shadowmap", Status::Fail, Outcome::NewFailure, webgpu}}, {}, "gl");
  EXPECT_NE(next.find("cube_seams@shadowmap@gl,FAIL,api=webgpu  # new in this run"), std::string::npos) << next;
  // Refusals, each one line naming the line.
  EXPECT_NE(refusal("a@planar,FAIL,gpu=x\n").find("bad.txt:1: 'gpu=x': unknown environment key 'gpu'"), std::string::npos);
  EXPECT_NE(refusal("a@planar,FAIL,api\n").find("expected a condition key=value"), std::string::npos);
  EXPECT_NE(refusal("a@planar,FAIL,api=x,y\n").find("one comma too many"), std::string::npos);
  EXPECT_NE(refusal("a@planar,FAIL,api=x api=y\n").find("api is given twice"), std::string::npos);
  EXPECT_NE(refusal("a@planar,FAIL,api=webgpu\na@planar,WARN\n").find("bad.txt:2: case a@planar is listed already"),
            std::string::npos)
      << "a line for every environment overlaps one for WebGPU";
  EXPECT_EQ(refusal("a@planar,FAIL,api=webgpu\na@planar,WARN,api=webgl2\n"), "(accepted)");
}

TEST(Expectations, OutcomesAndExitCodes) {
  ExpectationLine fail{"s", "t", "", Status::Fail, "f:1", "s@t,FAIL", {}};
  ExpectationLine warn{"s", "t", "", Status::Warn, "f:1", "s@t,WARN", {}};
  EXPECT_EQ(outcome_of(Status::Fail, false, &fail, false), Outcome::Expected);
  EXPECT_EQ(outcome_of(Status::Pass, false, &fail, false), Outcome::Improvement);
  EXPECT_EQ(outcome_of(Status::XFail, false, &fail, false), Outcome::Improvement);
  EXPECT_EQ(outcome_of(Status::Warn, false, &fail, false), Outcome::Improvement);
  EXPECT_EQ(outcome_of(Status::Error, false, &fail, false), Outcome::NewFailure);  // another failure than the known one
  EXPECT_EQ(outcome_of(Status::Fail, false, &warn, false), Outcome::NewFailure);
  EXPECT_EQ(outcome_of(Status::Warn, true, &warn, false), Outcome::Expected);
  EXPECT_EQ(outcome_of(Status::Fail, false, nullptr, false), Outcome::NewFailure);
  EXPECT_EQ(outcome_of(Status::XPass, false, nullptr, false), Outcome::NewFailure);
  EXPECT_EQ(outcome_of(Status::Warn, false, nullptr, false), Outcome::NewWarning);
  EXPECT_EQ(outcome_of(Status::Warn, true, nullptr, false), Outcome::Green);  // the catalogue expects it
  EXPECT_EQ(outcome_of(Status::Fail, false, nullptr, true), Outcome::Flake);
  EXPECT_EQ(outcome_of(Status::Pass, false, nullptr, true), Outcome::Green);
  EXPECT_EQ(exit_code(std::vector<Outcome>{Outcome::Expected, Outcome::Flake, Outcome::Green}), 0);
  EXPECT_EQ(exit_code(std::vector<Outcome>{Outcome::Expected, Outcome::Improvement}), 1);
  EXPECT_EQ(exit_code(std::vector<Outcome>{Outcome::NewWarning}), 1);
  EXPECT_EQ(exit_code(std::vector<Outcome>{Outcome::Improvement, Outcome::NewFailure}), 2);
}

TEST(Expectations, StaleLinesAndTheNextFile) {
  const Expectations e = read_expectations({write("next.txt",
                                                  "# header comment\n"
                                                  "a@shadowmap,FAIL  # bug 1\n"
                                                  "b@shadowmap,FAIL  # bug 2: fixed now\n"
                                                  "gone@shadowmap,FAIL\n"
                                                  "a@planar@d3d,FAIL\n"
                                                  "[flakes]\n"
                                                  "^c@\n")});
  const auto stale = stale_lines(e, {"a", "b", "c", "d"}, {"shadowmap"}, "gl");
  ASSERT_EQ(stale.size(), 1u);
  EXPECT_EQ(stale[0]->scene, "gone");
  EXPECT_TRUE(stale_lines(e, {"a", "b", "c", "d", "gone"}, {"shadowmap"}, "gl").empty());  // another shard's scene
  const std::vector<CaseOutcome> cases = {{"a", "shadowmap", Status::Fail, Outcome::Expected, {}},
                                          {"b", "shadowmap", Status::Pass, Outcome::Improvement, {}},
                                          {"d", "shadowmap", Status::Fail, Outcome::NewFailure, {}}};
  const std::string next = expectations_update_text(e, cases, stale, "gl");
  EXPECT_NE(next.find("a@shadowmap,FAIL  # bug 1\n"), std::string::npos);  // kept with its bug link
  EXPECT_EQ(next.find("b@shadowmap"), std::string::npos);                  // the improvement's line is gone
  EXPECT_EQ(next.find("gone@"), std::string::npos);                        // so is the stale one
  EXPECT_NE(next.find("a@planar@d3d,FAIL"), std::string::npos);             // another convention's, kept
  EXPECT_NE(next.find("d@shadowmap@gl,FAIL"), std::string::npos);           // the new failure
  EXPECT_NE(next.find("[flakes]\n^c@"), std::string::npos);
  // Read back, the next file expects exactly this run's non-green cases.
  const Expectations again = read_expectations({write("again.txt", next)});
  for (const CaseOutcome& c : cases) {
    const ExpectationLine* l = again.line_for(c.scene, c.technique, "gl");
    EXPECT_EQ(outcome_of(c.status, false, l, false) == Outcome::Expected || (!l && c.status == Status::Pass), true) << c.scene;
  }
}

}  // namespace
}  // namespace shadowref::ci
