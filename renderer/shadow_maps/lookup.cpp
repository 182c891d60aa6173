// lookup.cpp — which shadow-map lookup draws a light (lookup.hpp).
#include "lookup.hpp"

#include "shadowref/scene/scene.hpp"

namespace shadowref::renderer {

const MapLookup& lookup_for_light(const MapLookup& lookup, const scene::Light& light) {
  return lookup.needs_area_light && light.type != scene::LightType::Rect ? kPcfLookup : lookup;
}

}  // namespace shadowref::renderer
