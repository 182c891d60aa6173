// case_json.cpp — a judged case's keys, shared by report.json and `compare --json` (case_json.hpp).
#include "shadowref/conform/case_json.hpp"

#include "shadowref/tolerance/resolving_power.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/report/comparison_json.hpp"

namespace shadowref::conform {

record::CaseRecord judged_case(const std::string& scene, const scene::Expectation& expected, const CaseJudgement* j) {
  record::CaseRecord k;
  k.scene = scene;
  k.expected = !expected.pass ? "fail" : expected.warn ? "warn" : "pass";
  k.why = expected.why;
  k.expected_from_height = expected.from_height;
  if (!j) return k;
  k.technique = j->technique;
  k.status = j->status;
  k.signature = j->signature;
  k.causes = j->causes;
  k.unmet_expectation = j->unmet_expectation;
  return k;
}

void write_judgement(const CaseJudgement& j, nlohmann::json& k) {
  namespace key = record::key;
  k[key::kCandidate] = nlohmann::json::parse(outputs::declaration_text(j.declaration));
  k[key::kCandidate]["defaulted"] = j.declaration.defaulted;
  k[key::kComparison] = report::to_json(j.comparison);
  if (j.resolving_power) k[key::kResolvingPower] = tolerance::resolving_power_json(*j.resolving_power);
}

}  // namespace shadowref::conform
