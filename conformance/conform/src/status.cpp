// status.cpp — the status rules of a judged case and the run's exit code (status.hpp).
#include "shadowref/conform/status.hpp"

#include "shadowref/ci/expectations.hpp"

#include <algorithm>
#include <cstdio>

namespace shadowref::conform {

Status status_of(compare::Verdict verdict, bool expected_pass) {
  if (expected_pass) {
    switch (verdict) {
      case compare::Verdict::Pass: return Status::Pass;
      case compare::Verdict::QualityWarning: return Status::Warn;
      case compare::Verdict::Fail: return Status::Fail;
    }
  }
  // An expected failure must fail outright: a pass or a mere quality warning means the known
  // limitation did not show, so the expectation (or the scene) is broken.
  return verdict == compare::Verdict::Fail ? Status::XFail : Status::XPass;
}

std::string unmet_expectation(const scene::Expectation& expected, Status status) {
  if (expected.pass && expected.warn && status == Status::Pass)
    return "expected WARN not seen (PASS): every wrong pixel explained and fewer of them than the quality bound";
  return "";
}

int exit_code(const std::vector<Status>& statuses, const std::vector<bool>& expected_warnings) {
  // The one rule is the expectations' (expectations.hpp): without a file, a failure is a new
  // failure and an unexpected WARN a new warning.
  std::vector<Outcome> outcomes;
  for (std::size_t i = 0; i < statuses.size(); ++i)
    outcomes.push_back(ci::outcome_of(statuses[i], i < expected_warnings.size() && expected_warnings[i], nullptr, false));
  return ci::exit_code(outcomes);
}

std::string unpredicted_errors(const compare::FolderComparison& c, scene::PredictedErrors predicted, std::string& seen) {
  const bool light = predicted == scene::PredictedErrors::TooLight;
  const char* other_name = light ? "too dark (false shadow)" : "too light (false light)";
  std::string problem;
  const auto add = [&](const std::string& s) { problem += (problem.empty() ? "" : "; ") + s; };
  char buf[256];
  // The unexplained pixels of the other kind, and those in cores (all cores less the predicted
  // kind's: a core of one kind is a core of both).
  const auto other_of = [light](const compare::MaskMetrics& m) {
    return light ? m.unexplained - m.unexplained_false_light : m.unexplained_false_light;
  };
  const auto other_core_of = [light](const compare::MaskMetrics& m) {
    return light ? m.unexplained_core - std::min(m.unexplained_core, m.unexplained_false_light_core) : m.unexplained_false_light_core;
  };
  // Each light's mask alone, as the verdict judges it (compare::decide_lights).
  for (std::size_t i = 0; i < c.per_light.size(); ++i) {
    const compare::MaskMetrics& m = c.per_light[i].metrics;
    const std::size_t other = other_of(m), other_core = other_core_of(m);
    const double ratio = m.edge_pixels ? static_cast<double>(other) / static_cast<double>(m.edge_pixels) : 0.0;
    if (other_core > 0 || (c.threshold && ratio > c.threshold->unexplained_fail)) {
      std::snprintf(buf, sizeof buf, "%s: %zu px %s unexplained (%.2f %% of the edge pixels, %zu in cores)",
                    c.per_light.size() > 1 ? c.masks[i].c_str() : "mask", other, other_name, 100.0 * ratio, other_core);
      add(buf);
    }
  }
  const compare::MaskMetrics& m = c.total;
  const std::size_t mask_other = other_of(m);
  std::size_t vis_predicted = 0;
  if (c.visibility_total) {
    const compare::VisibilityMetrics& v = *c.visibility_total;
    const std::size_t other = light ? v.unexplained - v.unexplained_too_light : v.unexplained_too_light;
    const std::size_t other_core = light ? v.unexplained_core - std::min(v.unexplained_core, v.unexplained_too_light_core)
                                         : v.unexplained_too_light_core;
    vis_predicted = v.unexplained - other;
    const double ratio = v.penumbra ? static_cast<double>(other) / static_cast<double>(v.penumbra) : 0.0;
    if (other_core > 0 || ratio > compare::kPenumbra.unexplained_fail) {
      std::snprintf(buf, sizeof buf, "lit fraction: %zu px %s unexplained (%.2f %% of the penumbra, %zu in cores)", other,
                    other_name, 100.0 * ratio, other_core);
      add(buf);
    }
  }
  std::snprintf(buf, sizeof buf, "%zu mask px and %zu lit-fraction px %s, unexplained", m.unexplained - mask_other,
                vis_predicted, light ? "too light" : "too dark");
  seen = buf;
  return problem;
}

}  // namespace shadowref::conform
