// shadow_map_techniques.cpp — the seven shadow-map techniques: a lookup (lookup.hpp) over the
// prepared scene's plain or cascaded fits (light_map.cpp), the one table that says which.
//
//   shadowmap        one nearest depth compare (depth_compare.cpp)
//   shadowmap-pcf    the 3 × 3 percentage-closer filter (pcf.cpp)
//   shadowmap-rgba8  depth packed into RGBA8, compared as integers (packed_rgba8.cpp)
//   csm, csm-pcf     cascaded shadow maps (Engel 2006; Zhang et al. 2006: mathlib/cascades.hpp) for
//                    directional lights, with the compare or the filter; other lights as the plain map
//   pcss             percentage-closer soft shadows for rect lights (pcss.cpp)
//   vsm              variance shadow maps over PCSS's penumbra for rect lights (vsm.cpp)
// The soft techniques draw lights without an area with PCF (lookup_for_light). Per light the map is
// drawn first; then one camera pass per light (Frame::light_pass) writes the picture, the mask and,
// for filtered techniques, the lit fraction (visibility.png) together.
#include "shadow_map_techniques.hpp"

#include <vector>

#include "light_map.hpp"
#include "shadowref/light_fit.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::renderer {

// The lookups the table names, each defined in its own file (lookup.hpp names PCF too).
extern const MapLookup kDepthCompareLookup;  // depth_compare.cpp
extern const MapLookup kPackedRgba8Lookup;   // packed_rgba8.cpp
extern const MapLookup kPcssLookup;          // pcss.cpp
extern const MapLookup kVsmLookup;           // vsm.cpp

namespace {

const MapTechnique kMapTechniques[] = {
    {"shadowmap", kDepthCompareLookup},   {"shadowmap-pcf", kPcfLookup}, {"shadowmap-rgba8", kPackedRgba8Lookup},
    {"csm", kDepthCompareLookup, true},   {"csm-pcf", kPcfLookup, true}, {"pcss", kPcssLookup},
    {"vsm", kVsmLookup},
};

// Every entry is a shadow-map technique of the contract, cascaded exactly where the contract says.
bool table_matches_contract() {
  for (const MapTechnique& t : kMapTechniques) {
    const outputs::TechniqueName* named = outputs::find_technique_name(t.name);
    if (!named || named->family == outputs::TechniqueFamily::ExactGeometry || named->cascaded != t.cascaded) return false;
  }
  return true;
}

void render_map_technique(Frame& frame, std::string_view name) {
  const MapTechnique& technique = *find_map_technique(name);
  const GlFunctions& gl = frame.gl;
  const Mat4<float> clip = frame.camera_clip(CameraDepth::Scene);
  std::vector<LightMap> maps;
  std::vector<const MapLookup*> lookups;
  for (std::size_t i = 0; i < frame.scene.lights.size(); ++i) {
    LightFit refit;
    lookups.push_back(&lookup_for_light(technique.lookup, frame.scene.lights[i]));
    const LightFit* fit = technique.cascaded ? &cascade_fit(frame, i, refit)
                                             : &technique_fit(frame.prepared, frame.options, false, i, refit);
    const Vec4<double>& L = frame.prepared.lights[i];
    if (frame.faults().shadow_map.light_direction_mirrored_x && L.w() == 0 && !technique.cascaded) {
      // FAULT: the view fitted, at the same size, to the direction mirrored in x.
      std::vector<const TriangleMesh<float>*> meshes;
      for (const scene::Object& o : frame.scene.objects) meshes.push_back(&o.mesh);
      LightFitOptions mirrored_options;
      mirrored_options.map_size = fit->size;
      const Vec4<double> mirrored(-L.x(), L.y(), L.z(), 0.0);
      LightFit mirrored_fit = fit_light(frame.convention(), mirrored, meshes, mirrored_options).value();
      refit = std::move(mirrored_fit);
      fit = &refit;
    }
    maps.push_back(draw_light_map(frame, i, *fit, *lookups[i]));
    frame.finish_then_check_interrupted();  // each map now, not all at the first lookup that samples them
  }
  // The picture, the masks and the lit fractions in one camera pass per light: ambient_pass lays
  // down the nearest surfaces' depth and colour, and each light's pass (GL_EQUAL: every visible
  // pixel shaded once) adds its light there and writes its mask, and for the filtered techniques its
  // lit fraction (visibility.png), into the mask attachment (Frame::light_pass).
  frame.ambient_pass(clip);
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const PassPrograms programs(frame, [&](bool tested) -> const Program& { return frame.programs.surface(lookups[i], tested); });
    programs.set([&](const Program& p) { bind_light_map(frame, i, maps[i], *lookups[i], p); });
    frame.light_pass(clip, i, &programs, &maps[i].shadow_from_world, /*masks=*/true);
    frame.result.masks.push_back(frame.read_grey(GL_GREEN, Frame::kMaskAttachment));
    if (technique.lookup.filtered) frame.result.visibility.push_back(frame.read_grey(GL_RED, Frame::kMaskAttachment));
  }
  unbind_light_maps(gl);
  frame.result.shaded = frame.read_rgb();
}

}  // namespace

const MapTechnique* find_map_technique(std::string_view name) {
  static const bool matches = table_matches_contract();
  if (!matches) throw GlError("the shadow-map technique table and outputs::kTechniques differ");
  for (const MapTechnique& t : kMapTechniques)
    if (t.name == name) return &t;
  return nullptr;
}

void render_shadowmap(Frame& frame) { render_map_technique(frame, "shadowmap"); }
void render_shadowmap_pcf(Frame& frame) { render_map_technique(frame, "shadowmap-pcf"); }
void render_shadowmap_rgba8(Frame& frame) { render_map_technique(frame, "shadowmap-rgba8"); }
void render_csm(Frame& frame) { render_map_technique(frame, "csm"); }
void render_csm_pcf(Frame& frame) { render_map_technique(frame, "csm-pcf"); }
void render_pcss(Frame& frame) { render_map_technique(frame, "pcss"); }
void render_vsm(Frame& frame) { render_map_technique(frame, "vsm"); }

}  // namespace shadowref::renderer
