// shadowref/renderer/renderer.hpp — the OpenGL renderer as a library: one context, every shadow
// technique, the masks and the shaded picture of docs/output-contract.md, and render.json.
//
// Usage:
//   Renderer r(GlApi::OSMesa, Driver::Llvmpipe);       // one per process and driver
//   RenderResult res = r.render(scene::prepare_scene(scene, convention), "volume-zfail");
//   write_outputs(res, r.info(), scene, "out/ground_sphere/volume-zfail");
// Every matrix comes from the prepared scene (camera, light fits: mathlib through scene/, the very
// matrices the reference uses), in the run convention it was prepared for; every depth test, clear
// value, compare function and offset sign comes from mathlib's convention.hpp; shadow volumes come
// from mathlib's volume construction.
//
// Masks: mask i answers "is the surface seen through this pixel centre lit by light i?": 255 lit,
// 0 shadowed, 128 no surface. The image is the scene's resolution, row 0 at the top; GL renders
// into a W × H viewport whose fragments sit at the pixel centres, with the scene's own view and
// projection (the depth rows of the projection may differ per technique: zfail's epsilon,
// zfail-clamp's finite far; x and y, hence the pixel → surface mapping, never do). Depth buffers are
// 24-bit fixed point, or 32-bit float where the convention asks (reversed-z); 0..1 clip depth is
// set with glClipControl.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/renderer/faults.hpp"
#include "shadowref/renderer/gl_context.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/scene/prepared_scene.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::renderer {

using outputs::Image8;

struct RenderOptions {
  // Used by the Scene overload of render(), which prepares the scene itself: the run convention
  // and the texels per side of each light's shadow map (0: automatic, mathlib's light_fit.hpp).
  const RunConvention* convention = &kDefaultConvention;
  int shadow_map_size = 0;
  int frames = 1;              // frames rendered; frame_ms is their median (the first is output)
  // 0: every filter on its fixed grid (PCF's 3 x 3 box, PCSS's 8 x 8 taps over the light). N (a
  // square, outputs/limits.hpp): PCF and PCSS's filter take N taps of a Vogel disk turned per pixel by
  // noise, as engines commonly do; PCF's disk reaches sqrt(2) texels. A correct render, declared
  // "sampling": "random" with light_taps sqrt(N). VSM's filter stays a grid.
  int random_taps = 0;
  // The faces the hard shadow maps' depth pass draws on closed casters: back (front faces culled,
  // the default: a lit surface is never compared with itself), front (back faces culled: the first
  // surfaces, as many engines draw them, held off themselves by the slope bias alone) or both. Open
  // casters are always drawn two-sided; PCSS and VSM always draw the first surfaces. Declared as
  // "depth_faces". Each is a correct render.
  outputs::DepthFaces depth_faces = outputs::DepthFaces::Back;
  // Texels each light's map gains along every side beyond its view, as a shadow atlas's tile has: the
  // map is (fit size + 2 G) texels, the projection's x and y scaled by size / (size + 2 G) so that the
  // view keeps its texel grid (the pack's), and the band holds what lies beyond it. Declared per
  // light as "atlas_tile": {"size": size + 2 G, "guard_band": G}. 0: none.
  int guard_band_texels = 0;
  // Light views of our own, as engines fit theirs: each view turned about its axis by
  // view_turn_degrees (its projection's x and y scaled by 1 / (|cos| + |sin|), so that the turned view
  // still covers the fit's: texels up to √2 wider) and its texel grid moved by view_phase_texels of a
  // texel along both axes (the view scaled by size / (size + 2) first, so that no edge texel is lost).
  // Either one declares "light_views": "own" (the judge then knows neither the grid's turn nor its
  // phase). 0 and 0: the pack's views.
  double view_turn_degrees = 0.0;
  double view_phase_texels = 0.0;
  // Declare the light matrices as engines that know theirs may: "light_views": "declared", each
  // light's views (view and projection, as drawn: turned and moved as above, a guard band's map whole)
  // at its map's size, and a cascaded light's splits. The judge then knows the exact texel grid, the
  // pack's views or our own alike.
  bool declare_light_matrices = false;
  // Directional lights' maps of the techniques that are not cascaded warped by light space
  // perspective shadow maps (mathlib/lispsm.hpp): texels small near the camera, large far from it,
  // in one map of the same size. Declared "light_views": "own" for those lights, or their matrices
  // with declare_light_matrices.
  bool lispsm = false;
  // The hard maps' normal offset (three.js and Babylon `normalBias`, Unity's "normal bias"): each
  // lookup moves along the surface normal, turned toward the light, by this many texels of the map
  // at the point. Declared as "normal_offset_texels". 0: none.
  double normal_offset_texels = 0.0;
  // What a point or spot light's cube holds under the depth-texture maps (shadowmap, shadowmap-pcf, csm's and
  // csm-pcf's cubes, and pcss's and vsm's point lights, drawn with PCF; shadowmap-rgba8 packs window
  // depth whatever this says): Window, the light
  // projection's window depth (the default), or Distance, the distance from the light over a range
  // (cube_distance_range), written with gl_FragDepth as engines' distance cubes are (three.js
  // MeshDistanceMaterial, Babylon's useDistance). The shader adds glPolygonOffset's model by hand: a
  // slope term from the distance's derivatives and a constant step. Declared per light as "depth":
  // "distance" with its "depth_range" and "depth_bias". Directional lights' views keep window depth.
  outputs::StoredDepth cube_depth = outputs::StoredDepth::Window;
  // Deliberate bugs for the conformance suite's teeth (faults.hpp); all off: production.
  Faults faults;
};

// What one light's shadow-map depth pass drew with, read back from the GL state at its draw calls
// (not from the options): the evidence that candidate.json declares what was drawn (renderer_test
// holds each declared light against it).
struct DrawnMap {
  std::string lookup;         // the camera pass's lookup: "depth-compare", "pcf", "packed-rgba8", "pcss", "vsm"
  int texels = 0;             // the map's texels per side (GL_TEXTURE_WIDTH), an atlas tile's guard band included
  float slope_factor = 0.0f;  // the offset's slope factor: GL_POLYGON_OFFSET_FACTOR, or the depth shader's own
                              // where GL's is off (a packed depth, a distance cube); a magnitude
  float offset_units = 0.0f;  // its constant, in the same place; a magnitude
  // The window depth (a distance cube: the range's fraction) one of those units moves the stored
  // depth: 2^-24 for GL's offset on a 24-bit map and for the shaders' own, 0 where the unit is
  // relative to the depth itself (GL's offset on a float map, which no depth_bias can declare).
  double unit_depth = 0.0;
  // The faces drawn on closed casters (from GL_CULL_FACE and its mode); nullopt when the pass drew none.
  std::optional<outputs::DepthFaces> closed_faces;
  bool distance = false;      // the layers hold distances (kDistanceFragment), not window depth
};

struct RenderResult {
  std::string technique;
  std::vector<Image8> masks;   // one per light (grey)
  // The filtered techniques' lit fraction per light (grey, round(255 · fraction); the background is
  // mask.png's to say): visibility.png / visibility_<i>.png. Empty for the others.
  std::vector<Image8> visibility;
  Image8 shaded;               // RGB
  std::vector<double> frame_ms;  // the time of each frame, all passes to glFinish and read-back
  std::vector<std::string> notes;  // what the technique could not do on this scene, and why
  outputs::CandidateDeclaration declaration;  // what write_outputs puts in candidate.json
  std::vector<DrawnMap> drawn_maps;           // shadow-map techniques: one per light, in order
  std::string faults;              // describe(options.faults): the fault switches on, "" in production
  double median_frame_ms() const;
};

struct GlInfo {
  GlApi api = GlApi::OSMesa;
  Driver driver = Driver::Llvmpipe;
  std::string vendor, renderer, version;
};

class Renderer;
struct Frame;

// One technique: its command-line name, one sentence for --help, and its implementation.
struct Technique {
  std::string_view name;
  std::string_view description;
  void (*render)(Frame& frame);
};

// Every technique, in the order --help lists them.
std::span<const Technique> techniques();
// The technique called `name`, or nullptr.
const Technique* find_technique(std::string_view name);

class Renderer {
 public:
  // Creates the context (create_gl_context) and compiles the shaders. Throws GlError.
  Renderer(GlApi api, Driver driver);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const GlInfo& info() const;
  // Renders the prepared scene (its convention, its shadow-map fits) with the technique `name`;
  // only the frames are timed: everything that depends on the scene alone was done by
  // prepare_scene. Throws std::invalid_argument for an unknown technique, GlError for a GL failure.
  RenderResult render(const scene::PreparedScene& scene, std::string_view technique, const RenderOptions& options = {});
  // Prepares `scene` in options.convention with options.shadow_map_size, then renders it.
  RenderResult render(const scene::Scene& scene, std::string_view technique, const RenderOptions& options = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes mask.png (one light) or mask_<i>.png (several), shaded.png, candidate.json (what the judge's
// tolerance model needs: technique, convention, map size, filter, bias) and render.json into `dir`:
// first into a temporary sibling folder, renamed to `dir` when complete, so that a reader never
// sees half a result. An existing `dir` is replaced. Throws std::runtime_error on file errors.
void write_outputs(const RenderResult& result, const GlInfo& info, const scene::Scene& scene,
                   const std::filesystem::path& dir);

}  // namespace shadowref::renderer
