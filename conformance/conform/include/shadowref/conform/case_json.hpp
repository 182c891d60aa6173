// shadowref/conform/case_json.hpp — a judged case in report.json's case shape, the one shape that
// `shadowref conform` writes per case and `shadowref compare --json` prints
// (conformance/record/report.schema.json, $defs/case).
//
// Both commands judge through the one judge (judge.hpp); these two functions turn its judgement
// into the case's keys, so that a key the judgement gains reaches both outputs from here. What is
// particular to each stays with it: conform adds where its files and images are (report_writer.cpp),
// compare where its technique came from and its exit code (cmd/compare_command.cpp).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "shadowref/conform/judge.hpp"
#include "shadowref/record/case_record.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::conform {

// The record's keys of scene `scene` judged as `j` (null: an ERROR before a verdict, which records
// the scene file's expectation `expected` alone): technique, status, expected and why, the expected
// failure's height and signature, the causes weighed and an unmet expectation. The caller adds what
// the judgement does not know: the time, the host, the shard, the expectations files' outcome.
record::CaseRecord judged_case(const std::string& scene, const scene::Expectation& expected, const CaseJudgement* j);

// The judgement's JSON keys, written into `k`: "candidate" (the declaration as the judge read it,
// and whether it was defaulted), "comparison" (every metric, comparison_json.hpp) and
// "resolving_power" when the probes ran.
void write_judgement(const CaseJudgement& j, nlohmann::json& k);

}  // namespace shadowref::conform
