// thresholds.cpp — which technique is judged by which threshold (the numbers are in thresholds.hpp).
#include "shadowref/compare/thresholds.hpp"

namespace shadowref::compare {
namespace {

constexpr const Threshold* kAll[] = {&kExactGeometry, &kShadowMap, &kShadowMapPcf};

}  // namespace

const Threshold& threshold_for(std::string_view technique) {
  if (technique == "shadowmap-pcf") return kShadowMapPcf;
  if (technique == "shadowmap" || technique == "shadowmap-rgba8") return kShadowMap;
  // planar, volume-* and anything unknown: the exact-geometry bound.
  return kExactGeometry;
}

std::span<const Threshold* const> all_thresholds() { return kAll; }

}  // namespace shadowref::compare
