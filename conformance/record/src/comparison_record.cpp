// comparison_record.cpp — a judged case's counts and lit fraction read into their records
// (comparison_record.hpp), each value of the wrong type a RecordError at its JSON path.
#include "shadowref/record/comparison_record.hpp"

#include <utility>

#include "read_json.hpp"
#include "shadowref/outputs/cause.hpp"

namespace shadowref::record::detail {
namespace {

using nlohmann::json;

std::string class_key(outputs::ErrorClass c) { return std::string(outputs::error_class(c).json_key); }

}  // namespace

MaskMetricsRecord read_mask_metrics(const json& m, const std::string& where) {
  if (!m.is_object()) throw RecordError(where + ": must be an object, not " + m.dump());
  MaskMetricsRecord r;
  const std::pair<const char*, std::optional<long long> MaskMetricsRecord::*> counts[] = {
      {key::kPixels, &MaskMetricsRecord::pixels},         {key::kDecidedSurface, &MaskMetricsRecord::decided_surface},
      {key::kWrong, &MaskMetricsRecord::wrong},           {key::kRegions, &MaskMetricsRecord::regions},
      {key::kLargestRegion, &MaskMetricsRecord::largest_region}, {key::kUnexplained, &MaskMetricsRecord::unexplained},
      {key::kUnexplainedCore, &MaskMetricsRecord::unexplained_core}, {key::kEdgePixels, &MaskMetricsRecord::edge_pixels},
      {key::kDisplaced, &MaskMetricsRecord::displaced}};
  for (const auto& [k, field] : counts) r.*field = count_at(m, k, where);
  using outputs::ErrorClass;
  const std::pair<ErrorClass, std::optional<long long> MaskMetricsRecord::*> classes[] = {
      {ErrorClass::FalseShadow, &MaskMetricsRecord::false_shadow}, {ErrorClass::FalseLight, &MaskMetricsRecord::false_light},
      {ErrorClass::Coverage, &MaskMetricsRecord::coverage},        {ErrorClass::Texel, &MaskMetricsRecord::texel},
      {ErrorClass::Bias, &MaskMetricsRecord::bias},                {ErrorClass::Acne, &MaskMetricsRecord::acne}};
  for (const auto& [c, field] : classes) r.*field = count_at(m, class_key(c).c_str(), where);
  r.wrong_percent = number_at(m, key::kWrongPercent, where);
  r.unexplained_percent_of_edges = number_at(m, key::kUnexplainedPercentOfEdges, where);
  r.explained_percent_of_edges = number_at(m, key::kExplainedPercentOfEdges, where);
  return r;
}

VisibilityRecord read_visibility(const json& v, const std::string& where) {
  if (!v.is_object()) throw RecordError(where + ": must be an object, not " + v.dump());
  VisibilityRecord r;
  const std::pair<const char*, std::optional<long long> VisibilityRecord::*> counts[] = {
      {key::kJudged, &VisibilityRecord::judged}, {key::kPenumbra, &VisibilityRecord::penumbra},
      {key::kExplainedFootprint, &VisibilityRecord::explained_footprint}, {key::kUnexplained, &VisibilityRecord::unexplained},
      {key::kUnexplainedCore, &VisibilityRecord::unexplained_core}};
  for (const auto& [k, field] : counts) r.*field = count_at(v, k, where);
  const std::pair<const char*, std::optional<double> VisibilityRecord::*> numbers[] = {
      {key::kUnexplainedPercentOfPenumbra, &VisibilityRecord::unexplained_percent_of_penumbra},
      {key::kMeanPenumbraError, &VisibilityRecord::mean_penumbra_error},
      {key::kMeanPenumbraLocalError, &VisibilityRecord::mean_penumbra_local_error},
      {key::kMeanPenumbraTexelError, &VisibilityRecord::mean_penumbra_texel_error},
      {key::kMaxError, &VisibilityRecord::max_error}};
  for (const auto& [k, field] : numbers) r.*field = number_at(v, k, where);
  const auto b = v.find(key::kBounds);
  if (b == v.end() || b->is_null()) return r;
  const std::string at = path_at(where, key::kBounds);
  if (!b->is_object()) throw RecordError(at + ": must be an object, not " + b->dump());
  r.unexplained_fail_percent_of_penumbra = number_at(*b, key::kUnexplainedFailPercentOfPenumbra, at);
  r.mean_penumbra_error_fail = number_at(*b, key::kMeanPenumbraErrorFail, at);
  r.mean_penumbra_local_error_fail = number_at(*b, key::kMeanPenumbraLocalErrorFail, at);
  r.sampling = text_at(*b, key::kSampling, at, "grid");
  return r;
}

}  // namespace shadowref::record::detail
