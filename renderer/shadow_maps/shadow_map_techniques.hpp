// shadow_map_techniques.hpp — which lookup each shadow-map technique draws with, over which fits.
// Private to the renderer library.
#pragma once

#include <string_view>

#include "lookup.hpp"

namespace shadowref::renderer {

struct MapTechnique {
  std::string_view name;    // the contract's name (outputs/techniques.hpp)
  const MapLookup& lookup;  // its lights' lookup (lookup_for_light: PCF for lights without an area)
  bool cascaded = false;    // directional lights' maps are the prepared scene's cascades
};

// The shadow-map technique called `name`, or nullptr (the exact techniques).
const MapTechnique* find_map_technique(std::string_view name);

}  // namespace shadowref::renderer
