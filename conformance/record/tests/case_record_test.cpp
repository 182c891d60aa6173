// case_record_test.cpp — a case of report.json through its record (case_record.hpp): the name
// tables round-trip, a written record reads back equal, and a case of the wrong shape is refused
// with its JSON path.
#include <algorithm>
#include <fstream>

#include <gtest/gtest.h>

#include "shadowref/record/case_record.hpp"
#include "shadowref/record/run_record.hpp"

namespace shadowref::record {
namespace {

using nlohmann::json;

TEST(CaseRecord, EveryStatusAndOutcomeNameReadsBackAsItself) {
  for (Status s : kStatuses) EXPECT_EQ(status_from_string(to_string(s)), s) << to_string(s);
  for (Outcome o : kOutcomes) EXPECT_EQ(outcome_from_string(to_string(o)), o) << to_string(o);
  EXPECT_FALSE(status_from_string("pass"));  // names are case-sensitive, as report.json writes them
  EXPECT_FALSE(outcome_from_string("Green"));
  int failures = 0;
  for (Status s : kStatuses) failures += is_failure(s);
  EXPECT_EQ(failures, 3);  // FAIL, XPASS, ERROR
  EXPECT_TRUE(is_failure(Status::XPass));
  EXPECT_FALSE(is_failure(Status::XFail));
}

// Each row of the plain-key tables is a case key the schema names, and the schema requires
// exactly the rows write_case always writes: a row added without its schema entry, or written
// sometimes where the schema requires it, fails here before any report is written.
TEST(CaseRecord, EveryPlainKeyIsInTheSchema) {
  std::ifstream in(SHADOWREF_REPORT_SCHEMA);
  ASSERT_TRUE(in) << SHADOWREF_REPORT_SCHEMA;
  const json c = json::parse(in).at("$defs").at("case");
  const json& properties = c.at("properties");
  const json& required = c.at("required");
  const auto check = [&](const char* name, Written written) {
    EXPECT_TRUE(properties.contains(name)) << name << " is a row but not in the schema's case";
    const bool is_required = std::find(required.begin(), required.end(), name) != required.end();
    EXPECT_EQ(is_required, written == Written::Always) << name;
  };
  std::size_t rows = 0;
  for (const TextKey& t : kTextKeys) check(t.name, t.written), ++rows;
  for (const NumberKey& n : kNumberKeys) check(n.name, n.written), ++rows;
  EXPECT_EQ(rows, 8u);
  // A name the schema does not hold is seen as one (the check can fail).
  EXPECT_FALSE(properties.contains("not_a_case_key"));
}

CaseRecord full() {
  CaseRecord r;
  r.scene = "two_lights";
  r.technique = "shadowmap-pcf";
  r.status = Status::XFail;
  r.expected = "fail";
  r.why = "a 512 map";
  r.expected_from_height = 240;
  r.signature = "3 mask px too dark";
  r.unmet_expectation = "expected WARN not seen";
  r.causes = "texel, bias";
  r.host = "ci-7";
  r.shard = 2;
  r.seconds = 0.25;
  r.expectation = ExpectationRecord{Outcome::Expected, "XFAIL", "fails.txt:3"};
  return r;
}

TEST(CaseRecord, AWrittenRecordReadsBackEqual) {
  json k;
  write_case(full(), k);
  // What write_case leaves to others, as the writer adds them.
  k[key::kComparison] = {{key::kReasons, {"1 unexplained core pixel(s)"}},
                         {key::kThreshold, {{key::kName, "shadow-map"}}},
                         {key::kTotal, {{key::kWrong, 7}, {key::kUnexplained, 1}, {key::kWrongPercent, 0.25}, {"false_light", 3}}},
                         {key::kVisibility, {{key::kPenumbra, 90}, {key::kMeanPenumbraError, 0.03},
                                             {key::kBounds, {{key::kSampling, "random"}, {key::kMeanPenumbraErrorFail, 0.08}}}}}};
  k[key::kLights] = {{{key::kMask, "mask_1.png"}, {key::kReference, "img/two_lights/reference_mask_1.png"}, {key::kDecided, ""},
                      {key::kCandidate, "img/two_lights/shadowmap-pcf/candidate_mask_1.png"}, {key::kErrorImage, nullptr},
                      {key::kMetrics, {{key::kWrong, 7}}}}};
  k[key::kResolvingPower] = {{key::kSummary, "blind to 8x8 tiles"}, {key::kBlindTo, {"8x8 tiles"}}, {key::kUnseen, json::array()}};
  k[key::kCandidate] = {{key::kEnvironment, {{"api", "webgpu"}, {"engine", "three.js"}}}};
  const CaseRecord r = read_case(k, 0);
  const CaseRecord f = full();
  EXPECT_EQ(r.scene, f.scene);
  EXPECT_EQ(r.technique, f.technique);
  EXPECT_EQ(r.status, f.status);
  EXPECT_EQ(r.expected, f.expected);
  EXPECT_EQ(r.why, f.why);
  EXPECT_EQ(r.expected_from_height, 240);
  EXPECT_EQ(r.signature, f.signature);
  EXPECT_EQ(r.unmet_expectation, f.unmet_expectation);
  EXPECT_EQ(r.causes, f.causes);
  EXPECT_EQ(r.host, f.host);
  EXPECT_EQ(r.shard, 2);
  EXPECT_EQ(r.seconds, 0.25);
  ASSERT_TRUE(r.expectation);
  EXPECT_EQ(r.expectation->outcome, Outcome::Expected);
  EXPECT_EQ(r.expectation->expected_by(), "XFAIL at fails.txt:3");
  EXPECT_EQ(r.reasons, std::vector<std::string>{"1 unexplained core pixel(s)"});
  ASSERT_TRUE(r.resolving_power);
  EXPECT_EQ(r.resolving_power->blind_to, std::vector<std::string>{"8x8 tiles"});
  EXPECT_EQ(outputs::environment_text(r.environment), "api webgpu · engine three.js");
  ASSERT_TRUE(r.candidate);
  EXPECT_EQ(r.candidate->environment, r.environment);
  EXPECT_EQ(r.candidate->shadow_map_size, 0);  // not given: the default
  ASSERT_TRUE(r.total);
  EXPECT_EQ(r.total->wrong, 7);
  EXPECT_EQ(r.total->unexplained, 1);
  ASSERT_EQ(r.lights.size(), 1u);
  EXPECT_EQ(r.lights[0].mask, "mask_1.png");
  EXPECT_EQ(r.lights[0].reference, "img/two_lights/reference_mask_1.png");
  EXPECT_EQ(r.lights[0].decided, "");
  EXPECT_EQ(r.lights[0].candidate, "img/two_lights/shadowmap-pcf/candidate_mask_1.png");
  EXPECT_EQ(r.lights[0].error, "");  // null: none
  // The numbers the page shows: those there, typed; those not there, absent.
  EXPECT_EQ(r.threshold, "shadow-map");
  EXPECT_EQ(r.total->wrong_percent, 0.25);
  EXPECT_EQ(r.total->false_light, 3);  // under the error class's key (outputs/cause.hpp)
  EXPECT_FALSE(r.total->edge_pixels);
  ASSERT_TRUE(r.visibility);
  EXPECT_EQ(r.visibility->penumbra, 90);
  EXPECT_EQ(r.visibility->sampling, "random");
  EXPECT_EQ(r.visibility->mean_penumbra_error_fail, 0.08);
  EXPECT_FALSE(r.visibility->max_error);
  ASSERT_TRUE(r.lights[0].metrics);
  EXPECT_EQ(r.lights[0].metrics->wrong, 7);
  EXPECT_FALSE(r.lights[0].visibility);
  // Written again from what was read, the keys are the same.
  json again;
  write_case(r, again);
  json written;
  write_case(f, written);
  EXPECT_EQ(again, written);
}

TEST(CaseRecord, OptionalKeysAreLeftOutAndReadAsTheirDefaults) {
  CaseRecord r;
  r.scene = "s";
  r.technique = "planar";
  json k;
  write_case(r, k);
  for (const char* absent : {key::kHost, key::kShard, key::kExpectation, key::kError, key::kSignature,
                             key::kUnmetExpectation, key::kExpectedFromHeight})
    EXPECT_FALSE(k.contains(absent)) << absent;
  const CaseRecord back = read_case(k, 0);
  EXPECT_FALSE(back.host);
  EXPECT_FALSE(back.shard);
  EXPECT_FALSE(back.expectation);
  EXPECT_FALSE(back.resolving_power);
  EXPECT_FALSE(back.total);
  EXPECT_TRUE(back.lights.empty());
  EXPECT_EQ(back.status, Status::Pass);
  EXPECT_EQ(ExpectationRecord{}.expected_by(), "green");
  // The run's own two, which write_case leaves to the run (compare --json has neither).
  EXPECT_FALSE(k.contains(key::kFrameMs));
  EXPECT_FALSE(k.contains(key::kNotes));
  k[key::kFrameMs] = 12.5;
  k[key::kNotes] = {"reference read from the cache"};
  const CaseRecord run = read_case(k, 0);
  EXPECT_EQ(run.frame_ms, 12.5);
  EXPECT_EQ(run.notes, (std::vector<std::string>{"reference read from the cache"}));
}

// Each wrong shape is refused with the JSON path a person looks at.
TEST(CaseRecord, TheCandidateReadsBackAsTheDeclarationItWasWrittenFrom) {
  // As the judge writes it: declaration_text's object and the keys the candidate left out.
  outputs::CandidateDeclaration d = outputs::default_declaration("shadowmap-pcf");
  d.producer = "three.js";
  d.atlas_tile_size = 1024;
  d.atlas_guard_band = 4;
  d.shadow_map_size = 1016;
  d.slope_bias_texels = 0.1 + 0.2;  // a double whose shortest text is long
  d.settings_json = R"({"type":"PCFSoftShadowMap"})";
  outputs::CandidateDeclaration second = d;
  second.depth_faces = outputs::DepthFaces::Both;
  d.lights = {d, second};
  d.defaulted = {"version", "views"};
  json k = {{key::kScene, "two_lights"}, {key::kTechnique, "shadowmap-pcf"}, {key::kStatus, "PASS"}};
  k[key::kCandidate] = json::parse(outputs::declaration_text(d));
  k[key::kCandidate][key::kDefaulted] = d.defaulted;
  const CaseRecord r = read_case(k, 0);
  ASSERT_TRUE(r.candidate);
  EXPECT_EQ(outputs::declaration_text(*r.candidate), outputs::declaration_text(d));
  EXPECT_EQ(r.candidate->defaulted, d.defaulted);
  EXPECT_EQ(r.candidate->slope_bias_texels, 0.1 + 0.2);
  ASSERT_EQ(r.candidate->lights.size(), 2u);
  EXPECT_EQ(r.candidate->lights[1].depth_faces, outputs::DepthFaces::Both);
  // A case with no "candidate" has none.
  k.erase(key::kCandidate);
  EXPECT_FALSE(read_case(k, 0).candidate);
}

TEST(CaseRecord, AWrongShapeIsRefusedWithItsPath) {
  const json good = {{"scene", "s"}, {"technique", "t"}, {"status", "PASS"}};
  const auto refused = [&](json c, std::size_t index) -> std::string {
    try {
      read_case(c, index);
    } catch (const RecordError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  EXPECT_EQ(refused(good, 0), "(accepted)");
  json c = good;
  c["status"] = "MAYBE";
  EXPECT_EQ(refused(c, 3), "cases[3].status: \"MAYBE\" is not a status (PASS, WARN, FAIL, XFAIL, XPASS, ERROR)");
  c = good;
  c.erase("technique");
  EXPECT_EQ(refused(c, 1), "cases[1].technique: missing");
  c = good;
  c["scene"] = 7;
  EXPECT_EQ(refused(c, 0), "cases[0].scene: must be a string, not 7");
  c = good;
  c["seconds"] = "fast";
  EXPECT_EQ(refused(c, 0), "cases[0].seconds: must be a number >= 0, not \"fast\"");
  c["seconds"] = -1;
  EXPECT_EQ(refused(c, 0), "cases[0].seconds: must be a number >= 0, not -1");
  c = good;
  c["frame_ms"] = "slow";
  EXPECT_EQ(refused(c, 2), "cases[2].frame_ms: must be a number >= 0, not \"slow\"");
  c = good;
  c["notes"] = {"cached", 4};
  EXPECT_EQ(refused(c, 2), "cases[2].notes: must be an array of strings, not with 4");
  c = good;
  c["comparison"] = {{"reasons", json::array()}};
  EXPECT_EQ(refused(c, 4), "cases[4].comparison.total: missing or not an object");
  c["comparison"]["total"] = {{"wrong", 2.5}, {"unexplained", 0}};
  EXPECT_EQ(refused(c, 4), "cases[4].comparison.total.wrong: must be a whole number >= 0, not 2.5");
  c["comparison"]["total"] = {{"wrong", 2}};
  EXPECT_EQ(refused(c, 4), "cases[4].comparison.total.unexplained: missing");
  c["comparison"]["total"] = {{"wrong", 2}, {"unexplained", 0}, {"false_shadow", "2"}};
  EXPECT_EQ(refused(c, 4), "cases[4].comparison.total.false_shadow: must be a whole number >= 0, not \"2\"");
  c["comparison"]["total"] = {{"wrong", 2}, {"unexplained", 0}, {"wrong_percent", "0.1"}};
  EXPECT_EQ(refused(c, 4), "cases[4].comparison.total.wrong_percent: must be a number, not \"0.1\"");
  c["comparison"]["total"] = {{"wrong", 2}, {"unexplained", 0}};
  c["comparison"]["threshold"] = "strict";
  EXPECT_EQ(refused(c, 4), "cases[4].comparison.threshold: must be an object, not \"strict\"");
  c["comparison"].erase("threshold");
  c["comparison"]["visibility"] = {{"bounds", {{"sampling", 3}}}};
  EXPECT_EQ(refused(c, 4), "cases[4].comparison.visibility.bounds.sampling: must be a string, not 3");
  c["comparison"]["visibility"] = {{"penumbra", -4}};
  EXPECT_EQ(refused(c, 4), "cases[4].comparison.visibility.penumbra: must be a whole number >= 0, not -4");
  c = good;
  c["lights"] = {{{"mask", "../mask.png"}}};
  EXPECT_EQ(refused(c, 0), "cases[0].lights[0].mask: '../mask.png' is not a mask file name");
  c["lights"] = {{{"mask", "mask.png"}, {"candidate", "../../../etc/passwd"}}};
  EXPECT_EQ(refused(c, 0), "cases[0].lights[0].candidate: '../../../etc/passwd' leaves the report folder");
  c["lights"] = {{{"mask", "mask.png"}, {"error", "/etc/passwd"}}};
  EXPECT_EQ(refused(c, 0), "cases[0].lights[0].error: '/etc/passwd' leaves the report folder");
  c["lights"] = {{{"mask", "mask.png"}, {"reference", 3}}};
  EXPECT_EQ(refused(c, 0), "cases[0].lights[0].reference: must be a string, not 3");
  c["lights"] = {{{"mask", "mask.png"}, {"metrics", {{"wrong", -1}}}}};
  EXPECT_EQ(refused(c, 0), "cases[0].lights[0].metrics.wrong: must be a whole number >= 0, not -1");
  c["lights"] = {{{"mask", "mask.png"}, {"visibility", json::array()}}};
  EXPECT_EQ(refused(c, 0), "cases[0].lights[0].visibility: must be an object, not []");
  c = good;
  c["shard"] = 1e300;  // a float: no cast out of range
  EXPECT_EQ(refused(c, 0), "cases[0].shard: must be a whole number from 0 to 2147483647, not 1e+300");
  c = good;
  c["expected_from_height"] = -2;
  EXPECT_EQ(refused(c, 0), "cases[0].expected_from_height: must be a whole number from 0 to 2147483647, not -2");
  c = good;
  c["expectation"] = {{"outcome", "maybe"}};
  EXPECT_EQ(refused(c, 2), "cases[2].expectation.outcome: \"maybe\" is not an outcome");
  c = good;
  c["candidate"] = {{"shadow_map_size", "big"}};
  EXPECT_EQ(refused(c, 1), "cases[1].candidate: shadow_map_size: must be an integer");
  c["candidate"] = {{"defaulted", {"producer"}}, {"lights", {{{"producer", "x"}}}}};
  EXPECT_EQ(refused(c, 1), "cases[1].candidate: lights[0].producer: not a per-light key (give it at the top level)");
  c["candidate"] = {{"defaulted", "producer"}};
  EXPECT_EQ(refused(c, 1), "cases[1].candidate.defaulted: must be an array of strings");
  c = good;
  c["resolving_power"] = {{"blind_to", {1}}};
  EXPECT_EQ(refused(c, 0), "cases[0].resolving_power.blind_to: must be an array of strings, not with 1");
  EXPECT_EQ(refused(json::array(), 5), "cases[5]: must be an object");
  EXPECT_THROW(read_cases(json{{"cases", 1}}), RecordError);
  EXPECT_TRUE(read_cases(json::object()).empty());
}

}  // namespace
}  // namespace shadowref::record
