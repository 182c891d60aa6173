// thresholds.cpp — which technique is judged by which threshold (the numbers are in thresholds.hpp):
// by the family the contract's technique list gives it.
#include "shadowref/compare/thresholds.hpp"

#include "shadowref/outputs/techniques.hpp"

namespace shadowref::compare {
namespace {

constexpr const Threshold* kAll[] = {&kExactGeometry, &kShadowMap, &kShadowMapPcf, &kSoftShadow};

}  // namespace

const Threshold& threshold_for(std::string_view technique) {
  const outputs::TechniqueName* t = outputs::find_technique_name(technique);
  if (!t) return kExactGeometry;  // an engine team's own technique: the strictest bound
  switch (t->family) {
    case outputs::TechniqueFamily::ExactGeometry: return kExactGeometry;
    case outputs::TechniqueFamily::ShadowMap: return kShadowMap;
    case outputs::TechniqueFamily::ShadowMapPcf: return kShadowMapPcf;
    case outputs::TechniqueFamily::SoftShadow: return kSoftShadow;
  }
  return kExactGeometry;
}

std::span<const Threshold* const> all_thresholds() { return kAll; }

}  // namespace shadowref::compare
