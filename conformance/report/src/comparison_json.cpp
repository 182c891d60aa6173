// comparison_json.cpp — comparison results as JSON (comparison_json.hpp).
#include "shadowref/report/comparison_json.hpp"

#include "shadowref/outputs/cause.hpp"
#include "shadowref/record/run_record.hpp"

namespace shadowref::report {
namespace {

namespace key = record::key;

// A count's key, from the one table of error classes (outputs/cause.hpp).
std::string class_key(outputs::ErrorClass c) { return std::string(outputs::error_class(c).json_key); }

}  // namespace

nlohmann::json to_json(const compare::MaskMetrics& m) {
  using outputs::ErrorClass;
  return {{"width", m.width},
          {"height", m.height},
          {key::kPixels, m.pixels},
          {"decided", m.decided},
          {key::kDecidedSurface, m.decided_surface},
          {key::kWrong, m.wrong},
          {key::kWrongPercent, m.wrong_percent()},
          {class_key(ErrorClass::FalseShadow), m.false_shadow},
          {class_key(ErrorClass::FalseLight), m.false_light},
          {class_key(ErrorClass::Coverage), m.coverage},
          {"off_values", m.off_values},
          {key::kRegions, m.regions},
          {key::kLargestRegion, m.largest_region},
          {class_key(ErrorClass::Texel), m.explained_texel},
          {class_key(ErrorClass::Bias), m.explained_bias},
          {key::kUnexplained, m.unexplained},
          {"unexplained_false_light", m.unexplained_false_light},
          {class_key(ErrorClass::Acne), m.unexplained_acne},
          {"unexplained_zigzag", m.unexplained_zigzag},
          {key::kUnexplainedCore, m.unexplained_core},
          {"densest_unexplained", m.densest_unexplained},
          {key::kEdgePixels, m.edge_pixels},
          {key::kUnexplainedPercentOfEdges, 100.0 * m.unexplained_ratio()},
          {key::kExplainedPercentOfEdges, 100.0 * m.explained_ratio()},
          {"invariant_pixels", m.invariant_pixels},
          {key::kDisplaced, m.displaced}};
}

nlohmann::json to_json(const compare::VisibilityMetrics& m) {
  return {{key::kJudged, m.judged},
          {key::kPenumbra, m.penumbra},
          {"beyond_sampling", m.beyond_sampling},
          {key::kExplainedFootprint, m.explained},
          {key::kUnexplained, m.unexplained},
          {"unexplained_too_light", m.unexplained_too_light},
          {key::kUnexplainedCore, m.unexplained_core},
          {key::kUnexplainedPercentOfPenumbra, 100.0 * m.unexplained_ratio()},
          {key::kMeanPenumbraError, m.mean_penumbra_error()},
          {key::kMeanPenumbraLocalError, m.mean_penumbra_local_error()},
          // Asked only where sampling's bound alone is exceeded (visibility.hpp); else 0.
          {key::kMeanPenumbraTexelError, m.mean_penumbra_texel_error()},
          {key::kMaxError, m.max_error},
          {key::kBounds,
           {{key::kUnexplainedFailPercentOfPenumbra, 100.0 * compare::kPenumbra.unexplained_fail},
            // A grid: FAIL beyond it (a wrong width). Random taps: WARN beyond it (noise), and FAIL
            // when the local means exceed mean_penumbra_local_error_fail. Each is sampling's bound
            // plus the mean texel shift.
            {key::kMeanPenumbraErrorFail, m.mean_error_fail()},
            {key::kSampling, m.local_mean_error_bound > 0 ? "random" : "grid"},
            {key::kMeanPenumbraLocalErrorFail, m.local_mean_error_bound > 0 ? m.local_mean_error_fail() : 0.0},
            {"why", compare::kPenumbra.why}}}};
}

nlohmann::json to_json(const compare::Threshold& t) {
  return {{key::kName, t.name},
          {key::kBands, t.bands},
          {key::kUnexplainedFailPercent, 100.0 * t.unexplained_fail},
          {key::kExplainedWarnPercent, 100.0 * t.explained_warn},
          {"unexplained_core_fail", 0},
          {"displaced_fail_percent_of_edges", 100.0 * compare::kDisplaced.displaced_fail},
          {"displaced_why", compare::kDisplaced.why},
          {"densest_unexplained_fail", compare::kLocalGlitch.densest_fail},
          {"densest_unexplained_why", compare::kLocalGlitch.why},
          {key::kWhy, t.why}};
}

nlohmann::json to_json(const compare::FolderComparison& c) {
  nlohmann::json masks = nlohmann::json::array();
  for (std::size_t i = 0; i < c.masks.size(); ++i)
  {
    masks.push_back({{key::kMask, c.masks[i]}, {key::kMetrics, to_json(c.per_light[i].metrics)}});
    if (i < c.visibility.size() && c.visibility[i]) masks.back()[key::kVisibility] = to_json(c.visibility[i]->metrics);
    const compare::Displacement& d = c.per_light[i].displacement;
    if (d.fixed_unexplained > 0)
      masks.back()["displacement"] = {{"move", compare::describe(d.move)},
                                      {"dx", d.move.dx},
                                      {"dy", d.move.dy},
                                      {"grow", d.move.grow},
                                      {"unexplained_made_right", d.fixed_unexplained},
                                      {"shadow_errors", d.wrong_before},
                                      {"shadow_errors_moved_back", d.wrong_after}};
  }
  nlohmann::json j;
  j["verdict"] = compare::to_string(c.decision.verdict);
  j[key::kReasons] = c.decision.reasons;
  j[key::kThreshold] = c.threshold ? to_json(*c.threshold) : nlohmann::json();
  j[key::kTotal] = to_json(c.total);
  j["masks"] = masks;
  if (c.visibility_total) j[key::kVisibility] = to_json(*c.visibility_total);
  return j;
}

}  // namespace shadowref::report
