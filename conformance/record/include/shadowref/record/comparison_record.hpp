// shadowref/record/comparison_record.hpp — a judged case's numbers as report.json holds them: a
// mask's counts (its "comparison"."total" and each light's "metrics") and a soft technique's lit
// fraction ("visibility"), typed for the readers that show them (the page), with the names of their
// keys, which report/comparison_json.cpp writes them by.
//
// Every value is optional: absent, the reader shows that the report did not say ("-"); present, it
// must be what the schema (report.schema.json) says, a count a whole number >= 0 and a ratio a
// number, or read_case refuses the case with the value's JSON path. The error classes' counts are
// named by outputs/cause.hpp's table (`json_key`), not here.
#pragma once

#include <optional>
#include <string>

namespace shadowref::record {

namespace key {
// Inside a mask's counts ("total", a light's "metrics").
inline constexpr char kPixels[] = "pixels";
inline constexpr char kDecidedSurface[] = "decided_surface";
inline constexpr char kWrongPercent[] = "wrong_percent";
inline constexpr char kRegions[] = "regions";
inline constexpr char kLargestRegion[] = "largest_region";
inline constexpr char kUnexplainedCore[] = "unexplained_core";
inline constexpr char kEdgePixels[] = "edge_pixels";
inline constexpr char kUnexplainedPercentOfEdges[] = "unexplained_percent_of_edges";
inline constexpr char kExplainedPercentOfEdges[] = "explained_percent_of_edges";
inline constexpr char kDisplaced[] = "displaced";
// Inside "visibility" (the lit fraction's numbers) and its "bounds".
inline constexpr char kJudged[] = "judged";
inline constexpr char kPenumbra[] = "penumbra";
inline constexpr char kExplainedFootprint[] = "explained_footprint";
inline constexpr char kUnexplainedPercentOfPenumbra[] = "unexplained_percent_of_penumbra";
inline constexpr char kMeanPenumbraError[] = "mean_penumbra_error";
inline constexpr char kMeanPenumbraLocalError[] = "mean_penumbra_local_error";
inline constexpr char kMeanPenumbraTexelError[] = "mean_penumbra_texel_error";
inline constexpr char kMaxError[] = "max_error";
inline constexpr char kBounds[] = "bounds";
inline constexpr char kUnexplainedFailPercentOfPenumbra[] = "unexplained_fail_percent_of_penumbra";
inline constexpr char kMeanPenumbraErrorFail[] = "mean_penumbra_error_fail";
inline constexpr char kSampling[] = "sampling";
inline constexpr char kMeanPenumbraLocalErrorFail[] = "mean_penumbra_local_error_fail";
inline constexpr char kMetrics[] = "metrics";        // a light's counts
inline constexpr char kVisibility[] = "visibility";  // a light's, or the total's, lit fraction
inline constexpr char kThreshold[] = "threshold";    // "comparison"."threshold", by its "name"
}  // namespace key

// A mask's counts as the page shows them (compare::MaskMetrics, compare/compare.hpp, says what each
// counts). The error classes' counts are under outputs::error_class(c).json_key.
struct MaskMetricsRecord {
  std::optional<long long> pixels, decided_surface, wrong, regions, largest_region;
  std::optional<long long> false_shadow, false_light, coverage, texel, bias, acne;  // by error class
  std::optional<long long> unexplained, unexplained_core, edge_pixels, displaced;
  std::optional<double> wrong_percent, unexplained_percent_of_edges, explained_percent_of_edges;
};

// A soft technique's lit fraction as the page shows it (compare::VisibilityMetrics,
// compare/visibility.hpp), in visibility units, with the bounds it was judged by.
struct VisibilityRecord {
  std::optional<long long> judged, penumbra, explained_footprint, unexplained, unexplained_core;
  std::optional<double> unexplained_percent_of_penumbra, mean_penumbra_error, mean_penumbra_local_error,
      mean_penumbra_texel_error, max_error;
  std::optional<double> unexplained_fail_percent_of_penumbra, mean_penumbra_error_fail, mean_penumbra_local_error_fail;
  std::string sampling = "grid";  // the bounds' "sampling": "grid" or "random"
};

}  // namespace shadowref::record
