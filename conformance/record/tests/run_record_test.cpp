// run_record_test.cpp — a whole report.json through its record (run_record.hpp): a shard's report
// reads into its plan, shard and cases, and a run into what the page shows of it; a report of the
// wrong shape is refused with its JSON path; every image a case shows is listed once for a reader
// that moves it.
#include <gtest/gtest.h>

#include <functional>
#include <utility>

#include "shadowref/record/run_record.hpp"

namespace shadowref::record {
namespace {

using nlohmann::json;

// A shard's report as conform writes one (its run-level keys; one case).
json shard_report() {
  return json::parse(R"({
    "version": "0.9.0", "convention": "gl", "host": "ci-2", "seconds": 12.5,
    "declarations": {"mode": "render"}, "skipped": ["level@planar@gl"],
    "plan": {"scenes": [{"scene": "two_lights", "shard": 1}, {"scene": "level", "shard": 2}],
             "shards": 2, "assignment": "weights", "techniques": ["planar", "shadowmap"], "convention": "gl",
             "catalogue": {"scenes": 2}, "control": "directional_light"},
    "shard": {"index": 2, "total": 2, "source": "given", "scenes": ["level"],
              "control": {"scene": "directional_light", "technique": "planar", "status": "PASS"}},
    "cases": [{"scene": "level", "technique": "shadowmap", "status": "XFAIL", "shaded": "img/level/shadowmap/shaded.png",
               "reference_shaded": "img/level/reference_shaded.png",
               "lights": [{"mask": "mask.png", "reference": "img/level/reference_mask.png", "decided": "",
                           "candidate": "img/level/shadowmap/candidate_mask.png", "error": "img/level/shadowmap/error.png",
                           "candidate_visibility": "img/level/shadowmap/candidate_visibility.png"}]}]
  })");
}

// What read_run says of `j` once `edit` has changed it: its one line, or "accepted".
std::string refusal(const std::function<void(json&)>& edit, json j) {
  edit(j);
  try {
    read_run(j);
  } catch (const RecordError& e) {
    return std::string(e.what());
  }
  return std::string("accepted");
}

TEST(RunRecord, AShardReadsIntoItsPlanShardAndCases) {
  const RunRecord r = read_run(shard_report());
  EXPECT_EQ(r.version, "0.9.0");
  EXPECT_EQ(r.convention, "gl");
  EXPECT_EQ(r.host, "ci-2");
  EXPECT_EQ(r.seconds, 12.5);
  ASSERT_EQ(r.plan.scenes.size(), 2u);
  EXPECT_EQ(r.plan.scenes[1].scene, "level");
  EXPECT_EQ(r.plan.scenes[1].shard, 2);
  EXPECT_EQ(r.plan.shards, 2);
  EXPECT_EQ(r.plan.techniques, (std::vector<std::string>{"planar", "shadowmap"}));
  EXPECT_EQ(r.plan.whole.at("assignment"), "weights");  // carried whole, for the shards' comparison
  EXPECT_EQ(r.catalogue, json({{"scenes", 2}}));
  EXPECT_EQ(r.declarations, json({{"mode", "render"}}));
  ASSERT_TRUE(r.shard);
  EXPECT_EQ(r.shard->index, 2);
  EXPECT_EQ(r.shard->total, 2);
  ASSERT_TRUE(r.shard->control);
  EXPECT_EQ(r.shard->control->scene, "directional_light");
  EXPECT_EQ(r.shard->control->status, Status::Pass);
  EXPECT_EQ(r.skipped, (std::vector<std::string>{"level@planar@gl"}));
  ASSERT_EQ(r.cases.size(), 1u);
  EXPECT_EQ(r.cases[0].status, Status::XFail);
}

TEST(RunRecord, AnUnsplitRunHasNoShardAndOnePlannedShard) {
  json j = shard_report();
  j.erase("shard");
  j["plan"].erase("shards");
  j.erase("host");
  const RunRecord r = read_run(j);
  EXPECT_FALSE(r.shard);
  EXPECT_EQ(r.plan.shards, 1);
  EXPECT_FALSE(r.host);
}

TEST(RunRecord, AWrongShapeIsRefusedWithItsPath) {
  const auto refused = [](const std::function<void(json&)>& edit) { return refusal(edit, shard_report()); };
  EXPECT_EQ(refused([](json& j) { j.erase("plan"); }), "plan: missing or not an object");
  EXPECT_EQ(refused([](json& j) { j["cases"] = json::object(); }), "cases: missing or not an array");
  // A shard number is a whole number from 1: never a float cast out of range, never 0.
  EXPECT_EQ(refused([](json& j) { j["plan"]["shards"] = 1e300; }),
            "plan.shards: must be a whole number from 1 to 2147483647, not 1e+300");
  EXPECT_EQ(refused([](json& j) { j["plan"]["scenes"][1]["shard"] = 0; }),
            "plan.scenes[1].shard: must be a whole number from 1 to 2147483647, not 0");
  EXPECT_EQ(refused([](json& j) { j["plan"]["scenes"][0]["scene"] = 7; }), "plan.scenes[0].scene: must be a string, not 7");
  EXPECT_EQ(refused([](json& j) { j["plan"]["scenes"] = "all"; }), "plan.scenes: must be an array, not \"all\"");
  EXPECT_EQ(refused([](json& j) { j["shard"]["index"] = -1; }), "shard.index: must be a whole number from 1 to 2147483647, not -1");
  EXPECT_EQ(refused([](json& j) { j["shard"]["total"] = 4294967296.0; }),
            "shard.total: must be a whole number from 1 to 2147483647, not 4294967296.0");
  EXPECT_EQ(refused([](json& j) { j["shard"]["control"]["status"] = "MAYBE"; }),
            "shard.control.status: \"MAYBE\" is not a status (PASS, WARN, FAIL, XFAIL, XPASS, ERROR)");
  EXPECT_EQ(refused([](json& j) { j["shard"]["control"].erase("technique"); }), "shard.control.technique: missing");
  EXPECT_EQ(refused([](json& j) { j["shard"]["control"] = 3; }), "shard.control: must be an object, not 3");
  EXPECT_EQ(refused([](json& j) { j["skipped"] = {1}; }), "skipped: must be an array of strings, not with 1");
  EXPECT_EQ(refused([](json& j) { j["seconds"] = -2; }), "seconds: must be a number >= 0, not -2");
  EXPECT_EQ(refused([](json& j) { j["convention"] = json::array(); }), "convention: must be a string, not []");
  // The cases go through read_case, with their index.
  EXPECT_EQ(refused([](json& j) { j["cases"][0]["shaded"] = "../../x.png"; }), "cases[0].shaded: '../../x.png' leaves the report folder");
  EXPECT_EQ(refused([](json& j) { j["cases"][0]["lights"][0]["visibility_error"] = "/etc/passwd"; }),
            "cases[0].lights[0].visibility_error: '/etc/passwd' leaves the report folder");
}

// What the page, JUnit and summary.md show of a run: how it drew, its thresholds, what its
// expectations files came to, its triage.
json page_report() {
  json j = shard_report();
  j.update(json::parse(R"json({
    "tool": "shadowref", "generated": "2026-12-04T01:00:00Z", "mode": "render", "backend": "llvmpipe",
    "gl_api": "egl", "gl": {"vendor": "Mesa", "renderer": "llvmpipe (LLVM 15.0.6, 256 bits)", "version": "4.5"},
    "reference": {"producer": "shadowref reference (Embree 3)", "samples_per_axis": 4},
    "scenes": ["level"], "techniques": ["shadowmap"],
    "thresholds": [{"name": "shadow-map", "bands": true, "unexplained_fail_percent_of_edges": 0.5,
                    "explained_warn_percent_of_edges": 40, "why": "texels"}],
    "expectations": {"files": ["/ci/fails.txt"], "counts": {"expected": 1, "new-failure": 0},
                     "stale": [{"line": "fails.txt:9", "text": "gone@planar,FAIL"}], "update": "expectations-update.txt"},
    "triage": {"base": "# ours\n", "cases": [{"scene": "level", "technique": "shadowmap", "line": "level@shadowmap,XFAIL"}]}
  })json"));
  return j;
}

TEST(RunRecord, WhatThePageShowsOfARun) {
  const RunRecord r = read_run(page_report());
  EXPECT_EQ(r.tool, "shadowref");
  EXPECT_EQ(r.generated, "2026-12-04T01:00:00Z");
  EXPECT_EQ(r.mode, "render");
  EXPECT_EQ(r.backend, "llvmpipe");
  EXPECT_EQ(r.gl_api, "egl");
  EXPECT_FALSE(r.candidate_dir);
  EXPECT_EQ(r.gl_renderer, "llvmpipe (LLVM 15.0.6, 256 bits)");
  EXPECT_EQ(r.gl_version, "4.5");
  EXPECT_EQ(r.samples_per_axis, 4);
  EXPECT_EQ(r.scenes, (std::vector<std::string>{"level"}));
  EXPECT_EQ(r.techniques, (std::vector<std::string>{"shadowmap"}));
  ASSERT_EQ(r.thresholds.size(), 1u);
  EXPECT_EQ(r.thresholds[0].name, "shadow-map");
  EXPECT_TRUE(r.thresholds[0].bands);
  EXPECT_EQ(r.thresholds[0].unexplained_fail_percent, 0.5);
  EXPECT_EQ(r.thresholds[0].explained_warn_percent, 40.0);
  ASSERT_TRUE(r.expectations);
  EXPECT_EQ(r.expectations->files, (std::vector<std::string>{"/ci/fails.txt"}));
  using Count = std::pair<std::string, std::size_t>;
  EXPECT_EQ(r.expectations->counts, (std::vector<Count>{{"expected", 1}, {"new-failure", 0}}));
  ASSERT_EQ(r.expectations->stale.size(), 1u);
  EXPECT_EQ(r.expectations->stale[0].line, "fails.txt:9");
  EXPECT_EQ(r.expectations->stale[0].text, "gone@planar,FAIL");
  EXPECT_EQ(r.expectations->update, "expectations-update.txt");
  EXPECT_EQ(r.triage.base, "# ours\n");
  ASSERT_EQ(r.triage.cases.size(), 1u);
  EXPECT_EQ(r.triage.cases[0].line, "level@shadowmap,XFAIL");
  EXPECT_EQ(r.shard->source, "given");
  // A candidate-dir run: no backend (null), its folder instead; no files given: no expectations.
  json c = page_report();
  c["mode"] = "candidate-dir";
  c["backend"] = nullptr;
  c["candidate_dir"] = "/packs/engine";
  c.erase("expectations");
  const RunRecord d = read_run(c);
  EXPECT_FALSE(d.backend);
  EXPECT_EQ(d.candidate_dir, "/packs/engine");
  EXPECT_FALSE(d.expectations);
}

TEST(RunRecord, WhatThePageShowsIsReadStrictlyToo) {
  const auto refused = [](const std::function<void(json&)>& edit) { return refusal(edit, page_report()); };
  EXPECT_EQ(refused([](json& j) { j["thresholds"][0]["bands"] = "yes"; }), "thresholds[0].bands: must be true or false, not \"yes\"");
  EXPECT_EQ(refused([](json& j) { j["thresholds"][0]["explained_warn_percent_of_edges"] = "40"; }),
            "thresholds[0].explained_warn_percent_of_edges: must be a number, not \"40\"");
  EXPECT_EQ(refused([](json& j) { j["thresholds"] = {1}; }), "thresholds[0]: must be an object, not 1");
  EXPECT_EQ(refused([](json& j) { j["expectations"]["counts"]["expected"] = -1; }),
            "expectations.counts.expected: must be a whole number >= 0, not -1");
  EXPECT_EQ(refused([](json& j) { j["expectations"]["stale"][0]["text"] = 3; }), "expectations.stale[0].text: must be a string, not 3");
  EXPECT_EQ(refused([](json& j) { j["expectations"] = "none"; }), "expectations: must be an object, not \"none\"");
  EXPECT_EQ(refused([](json& j) { j["triage"]["cases"][0]["line"] = json::object(); }), "triage.cases[0].line: must be a string, not {}");
  EXPECT_EQ(refused([](json& j) { j["reference"]["samples_per_axis"] = 0.5; }),
            "reference.samples_per_axis: must be a whole number from 1 to 2147483647, not 0.5");
  EXPECT_EQ(refused([](json& j) { j["gl"]["renderer"] = 1; }), "gl.renderer: must be a string, not 1");
}

TEST(RunRecord, ACaseListsEveryImageItShowsOnce) {
  const RunRecord r = read_run(shard_report());
  const std::vector<std::string> images = case_images(r.cases[0]);
  // The decided image's "" (not written) is no image; each other path once.
  EXPECT_EQ(images, (std::vector<std::string>{"img/level/shadowmap/shaded.png", "img/level/reference_shaded.png",
                                              "img/level/reference_mask.png", "img/level/shadowmap/candidate_mask.png",
                                              "img/level/shadowmap/error.png", "img/level/shadowmap/candidate_visibility.png"}));
}

}  // namespace
}  // namespace shadowref::record
