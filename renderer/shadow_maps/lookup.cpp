// lookup.cpp — the list of the shadow-map lookups (lookup.hpp), and which one draws a light.
#include "lookup.hpp"

#include "shadowref/scene/scene.hpp"

namespace shadowref::renderer {

const MapLookup* map_lookup(Lookup id) {
  switch (id) {
    case Lookup::None: return nullptr;
    case Lookup::DepthCompare: return &kDepthCompareLookup;
    case Lookup::Pcf: return &kPcfLookup;
    case Lookup::PackedRgba8: return &kPackedRgba8Lookup;
    case Lookup::Pcss: return &kPcssLookup;
    case Lookup::Vsm: return &kVsmLookup;
  }
  return nullptr;
}

std::string_view lookup_name(Lookup id) {
  switch (id) {
    case Lookup::None: return "none";
    case Lookup::DepthCompare: return "depth-compare";
    case Lookup::Pcf: return "pcf";
    case Lookup::PackedRgba8: return "packed-rgba8";
    case Lookup::Pcss: return "pcss";
    case Lookup::Vsm: return "vsm";
  }
  return "none";
}

const MapLookup& lookup_for_light(const MapLookup& lookup, const scene::Light& light) {
  return lookup.needs_area_light && light.type != scene::LightType::Rect ? kPcfLookup : lookup;
}

}  // namespace shadowref::renderer
