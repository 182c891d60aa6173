// declaration.cpp — what a shadow-map technique declares in candidate.json (outputs/candidate.hpp):
// per light, from the very fields of the lookup that light is drawn with (lookup.hpp) and the
// options the light map reads (light_map.cpp), so that the declaration cannot drift from the
// drawing. renderer_test holds every declared light against RenderResult::drawn_maps, the state
// read back from GL.
#include <algorithm>
#include <cmath>
#include <string>

#include "light_map.hpp"
#include "shadow_map_techniques.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::renderer {
namespace {

// `d` with what `lookup` draws and filters with under `options` (the teeth's offset faults included:
// a deliberately wrong render declares what it does, honestly, and the judge must fail it all the same).
void declare_lookup(const MapLookup& lookup, const RenderOptions& options, outputs::CandidateDeclaration& d) {
  const ShadowMapFaults& faults = options.faults.shadow_map;
  d.slope_bias_texels = lookup.offset_factor;
  d.depth_bias = double{lookup.offset_units} * kWindowDepthPerUnit;
  if (faults.no_polygon_offset) d.slope_bias_texels = d.depth_bias = 0;
  if (faults.large_constant_offset) d.depth_bias = double{kPeterPanUnits} * kWindowDepthPerUnit;
  if (faults.constant_offset_world > 0) {
    d.depth_bias = 0;
    d.constant_bias = faults.constant_offset_world;
  }
  d.filter_radius_texels = lookup.filter_radius_texels;
  if (lookup.random_kernel && options.random_taps > 0) {  // a rotated Vogel disk: its taps and its PCF radius
    d.sampling = outputs::Sampling::Random;
    d.light_taps = static_cast<int>(std::lround(std::sqrt(options.random_taps)));
    d.filter_radius_texels = kRandomPcfRadiusTexels;
  }
  d.depth_faces = lookup.draws_first_surfaces ? outputs::DepthFaces::Both : options.depth_faces;
  d.normal_offset_texels = lookup.normal_offset ? options.normal_offset_texels : 0.0;
}

}  // namespace

bool declare_shadow_map(std::string_view technique, const scene::PreparedScene& prepared, const RenderOptions& options,
                        outputs::CandidateDeclaration& declaration) {
  const MapTechnique* t = find_map_technique(technique);
  if (!t) return false;
  declare_lookup(t->lookup, options, declaration);
  // Per light: its own lookup (PCF for a light without an area under a soft technique); a guard
  // band makes each map an atlas tile around the view of its fit, and a distance cube stores
  // distances over its range, with the offset's constant in those units (kDistanceFragment).
  const scene::Scene& scene = *prepared.scene;
  const int g = options.guard_band_texels;
  std::vector<outputs::CandidateDeclaration> lights;
  bool differ = false;
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    outputs::CandidateDeclaration light = declaration;
    const MapLookup& lookup = lookup_for_light(t->lookup, scene.lights[i]);
    declare_lookup(lookup, options, light);
    if (g > 0) {
      const int size = (t->cascaded ? prepared.cascade_fits[i] : prepared.light_fits[i]).size;
      light.atlas_tile_size = size + 2 * g;
      light.atlas_guard_band = g;
      light.shadow_map_size = size;
    }
    if (holds_distance(options, lookup, prepared.light_fits[i].cube)) {
      light.depth = outputs::StoredDepth::Distance;
      light.depth_range = cube_distance_range(prepared, i);
      // The distance pass draws the lookup's offset by hand, fault switches aside (light_map.cpp).
      light.slope_bias_texels = lookup.offset_factor;
      light.depth_bias = double{lookup.offset_units} / 16777215.0;  // kDistanceFragment's constant step
    }
    // A LiSPSM warp (RenderOptions::lispsm) is a view of our own: undeclared, the judge knows only
    // its size.
    if (lispsm_warps(prepared, options, t->cascaded, i)) light.light_views = outputs::LightViews::Own;
    if (options.declare_light_matrices) {
      LightFit storage;
      const LightFit& fit = technique_fit(prepared, options, t->cascaded, i, storage);
      const int map_size = fit.size + 2 * g;
      light.light_views = outputs::LightViews::Declared;
      light.shadow_map_size = map_size;  // the whole map: the guard band is in the drawn projection
      light.atlas_tile_size = light.atlas_guard_band = 0;
      light.views.clear();
      for (const LightView& v : fit.views) {
        outputs::DeclaredView d;
        const Mat4<double> projection = drawn_projection(options, v.projection, fit.size, map_size);
        std::copy(v.view.data(), v.view.data() + 16, d.view.begin());  // Eigen stores column-major
        std::copy(projection.data(), projection.data() + 16, d.projection.begin());
        light.views.push_back(d);
      }
      if (fit.views.size() > 1 && !fit.cube) light.cascade_splits = fit.cascade_splits;
    }
    differ = differ || outputs::declaration_text(light) != outputs::declaration_text(declaration);
    lights.push_back(std::move(light));
  }
  if (differ) declaration.lights = std::move(lights);
  return true;
}

}  // namespace shadowref::renderer
