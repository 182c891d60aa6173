// shadowref/report/comparison_json.hpp — the comparison's numbers as JSON, the one spelling that
// `shadowref compare --json`, report.json and the HTML report share.
#pragma once

#include <nlohmann/json.hpp>

#include "shadowref/compare/compare.hpp"

namespace shadowref::report {

// {"pixels", "decided", "decided_surface", "wrong", "wrong_percent", "false_shadow",
//  "false_light", "coverage", "off_values", "regions", "largest_region"}
nlohmann::json to_json(const compare::MaskMetrics& m);
// Soft shadows: {"judged", "penumbra", "beyond_sampling", "explained_footprint", "unexplained",
//  "unexplained_core", "unexplained_percent_of_penumbra", "mean_penumbra_error", "mean_penumbra_local_error",
//  "mean_penumbra_texel_error", "max_error", "bounds"}
nlohmann::json to_json(const compare::VisibilityMetrics& m);
// {"name", "pass_fraction", "fail_fraction", "pass_region", "fail_region", "why"}
nlohmann::json to_json(const compare::Threshold& t);
// {"verdict", "reasons", "threshold", "total", "masks": [{"mask", "metrics", "visibility"?}], "visibility"?}
nlohmann::json to_json(const compare::FolderComparison& c);

}  // namespace shadowref::report
