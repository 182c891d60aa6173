// light_map.hpp — one light's shadow map, whatever its lookup: its views (one, a cube's six faces
// or the cascades, from the prepared scene's fits, turned or moved for own views, shrunk into an
// atlas tile's guard band), the matrices from the world to its texels, its storage (kept across
// renders), and the depth pass that draws it with the lookup's state. Private to the renderer.
#pragma once

#include <cstddef>
#include <vector>

#include "lookup.hpp"
#include "shadowref/light_fit.hpp"

namespace shadowref::renderer {

// Shadow-map storage kept from one render to the next: 2D array textures and renderbuffers, each of
// one format and size. Why: llvmpipe zeroes a fresh texture's memory and the kernel faults in every
// page of it, at each allocation; for the 2048-texel maps of a conformance run that was about a
// third of the drawing's time (perf: clear_page_erms, memset under glTexImage3D). A map's every layer
// is cleared before it is drawn (draw_light_map), so a reused one carries nothing over.
class MapStoragePool {
 public:
  explicit MapStoragePool(const GlFunctions& gl) : gl_(gl) {}
  ~MapStoragePool();  // deletes them all: the context must be current
  MapStoragePool(const MapStoragePool&) = delete;
  MapStoragePool& operator=(const MapStoragePool&) = delete;
  // A 2D array texture of `layers` layers of size × size texels of `internal_format` (contents
  // undefined), bound to GL_TEXTURE_2D_ARRAY on the active unit; `format` and `type` as glTexImage3D's.
  GLuint texture(GLenum internal_format, GLenum format, GLenum type, int size, int layers);
  // A size × size renderbuffer of `internal_format`, bound to GL_RENDERBUFFER.
  GLuint renderbuffer(GLenum internal_format, int size);
  // Gives back what texture() or renderbuffer() handed out, for a later map of the same kind.
  void give_back(GLuint id, bool is_texture);

 private:
  struct Entry {
    bool is_texture;
    GLenum internal_format;
    int size, layers;
    GLuint id;
    bool in_use;
  };
  // The unused entry of that kind, now in use; null when there is none.
  Entry* reuse(bool is_texture, GLenum internal_format, int size, int layers);
  const GlFunctions& gl_;
  std::vector<Entry> entries_;
};

// One light's map: the textures (2D arrays, one layer per view) and the matrices that map world
// points into them. Gives its storage back to the pool when destroyed.
struct LightMap {
  MapStoragePool* pool = nullptr;  // where texture and moments go back
  GLuint texture = 0;
  GLuint moments = 0;              // MapStorage::RawDepthAndMoments: the RG32F moments, the same layers
  int size = 0;                    // texels per side, an atlas tile's guard band included
  MapLayout layout = MapLayout::Single;
  float distance_range = 0;        // > 0: a cube holding distance over this range (RenderOptions::cube_depth)
  Vec3<float> light_position = Vec3<float>::Zero();  // the cube's centre, for its distances
  Mat4<float> shadow_from_world;   // B · P_light · V_light (the single view)
  std::vector<Mat4<float>> face_from_world;  // the same per cube face or cascade
  // Cascades: the camera-depth row, and the depths each cascade is picked for (shader u_cascade_*).
  Vec4<float> cascade_depth = Vec4<float>::Zero();
  Vec4<float> cascade_begin = Vec4<float>::Constant(-3e38f), cascade_end = Vec4<float>::Constant(-3e38f);
  // The inverse of each face_from_world, and 1 / view depth = a · window depth + b per layer.
  std::vector<Mat4<float>> world_from_face;
  std::vector<float> inv_view_depth;  // (a, b) per layer
  LightMap() = default;
  LightMap(LightMap&& o) noexcept;
  LightMap(const LightMap&) = delete;
  LightMap& operator=(const LightMap&) = delete;
  LightMap& operator=(LightMap&&) = delete;
  ~LightMap();
};

// The cascades of the directional light `i` for the cascaded techniques: the prepared ones, or,
// when a CascadeFaults switch changes how they are fitted, a refit (into `refit`) with that one change.
const LightFit& cascade_fit(const Frame& frame, std::size_t i, LightFit& refit);

// The fit light `i`'s map is drawn with, before any fault switch: the prepared scene's cascades for a
// cascaded technique; for a directional light under RenderOptions::lispsm (and a technique that is
// not cascaded), its LiSPSM warp (mathlib/lispsm.hpp, fitted into `storage` at the prepared fit's
// size); else the prepared scene's fit. The one choice both the drawing and the declaration read.
const LightFit& technique_fit(const scene::PreparedScene& prepared, const RenderOptions& options, bool cascaded,
                              std::size_t i, LightFit& storage);
// Whether RenderOptions::lispsm warps light `i`'s map under a technique (cascaded or not).
bool lispsm_warps(const scene::PreparedScene& prepared, const RenderOptions& options, bool cascaded, std::size_t i);

// The projection with which a view of a fit of `fit_size` texels is drawn into a map of `map_size`
// texels (fit_size plus a guard band on each side): `projection` turned and moved as RenderOptions'
// own views ask, and shrunk into the map's middle fit_size texels (no fault applied). With the
// view's own matrix, at map_size, it is what "light_views": "declared" gives the judge.
Mat4<double> drawn_projection(const RenderOptions& o, const Mat4<double>& projection, int fit_size, int map_size);

// Whether `lookup`'s cube holds distances under `options` (RenderOptions::cube_depth), and the
// range they are stored over: the largest distance from the light to a corner of the scene's box,
// with 1 % to spare, so that every caster's distance lies below 1 (the clear value: nothing there).
bool holds_distance(const RenderOptions& options, const MapLookup& lookup, bool cube);
double cube_distance_range(const scene::PreparedScene& prepared, std::size_t light);

// Light `light`'s map for `lookup` over `fit`: matrices, storage, and the depth pass, every view
// into its layer with the lookup's state (offset, faces, program) and the teeth's fault switches.
// Appends what the pass drew with, read back from GL, to frame.result.drawn_maps.
LightMap draw_light_map(Frame& frame, std::size_t light, const LightFit& fit, const MapLookup& lookup);

// Binds `map` for the camera pass of `lookup` and sets `program`'s map uniforms (and the lookup's
// light uniforms); unbind_light_maps unbinds every unit a map may use.
void bind_light_map(const Frame& frame, std::size_t light, const LightMap& map, const MapLookup& lookup,
                    const Program& program);
void unbind_light_maps(const GlFunctions& gl);

}  // namespace shadowref::renderer
