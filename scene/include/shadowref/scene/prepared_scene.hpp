// shadowref/scene/prepared_scene.hpp — a loaded scene made ready, ONCE, for one run convention:
// everything the reference and the renderer need that depends only on the scene, so that neither
// recomputes it and no timed frame pays for it.
//
//   camera      view, projection and their product in the run convention (convention.hpp), from
//               the scene camera: vertical field of view, aspect = width / height, the scene's far
//               plane or an infinite one; plus the two depth variants the stencil techniques need
//               (x and y rows identical, so every variant puts every point on the same pixel):
//               infinite with kSafeInfiniteEpsilonFloat (z-fail volumes at w = 0) and finite with
//               the far plane behind the whole scene (depth clamp);
//   lights      homogeneous points (scene::homogeneous);
//   bounds      the axis-aligned box of every vertex;
//   casters     per object: its welded caster (mathlib's ShadowCaster: adjacency and face planes),
//               its bounding sphere, whether it is a closed 2-manifold — or why it casts no volume;
//   light_fits  per light, the shadow-map views (light_fit.hpp) for the requested map size;
//   cascade_fits per light, the views of the cascaded techniques: a directional light's cascades
//               for the scene camera (cascades.hpp, default count and split weight), any other
//               light's ordinary fit (cascades are a sun's technique).
//
// Pixel (x, y) of a W × H image (row 0 at the top) has its centre at
//   ndc.x = 2 (x + 0.5) / W − 1,   ndc.y = 1 − 2 (y + 0.5) / H   (pixel_to_ndc in camera.hpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "shadowref/cascades.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/light_fit.hpp"
#include "shadowref/scene/scene.hpp"
#include "shadowref/silhouette.hpp"
#include "shadowref/volume.hpp"
#include "shadowref/volume_strategy.hpp"

namespace shadowref::scene {

// Which far plane a camera matrix has; the x and y rows never differ.
enum class CameraDepth {
  Scene,            // the scene's own far plane, or infinity
  InfiniteEpsilon,  // infinite with kSafeInfiniteEpsilonFloat: directions (w = 0) stay inside
  FiniteForClamp,   // a finite far plane behind every object, for GL_DEPTH_CLAMP
};

struct CameraMatrices {
  Mat4<double> view;             // scene → view space (view_from_scene of the convention)
  Mat4<double> projection;       // view → clip
  Mat4<double> clip_from_scene;  // projection · view
};

struct PreparedCaster {
  std::optional<ShadowCaster<float>> caster;  // empty: casts no volume (see `why_not`)
  BoundingSphere<float> sphere;
  bool closed = false;                        // a closed 2-manifold (front-face culling is safe)
  std::string why_not;                        // why there is no caster
};

struct PrepareOptions {
  int shadow_map_size = 0;  // texels per side of every shadow map; 0: automatic (light_fit.hpp)
};

struct PreparedScene {
  const Scene* scene = nullptr;                 // the loaded scene (outlives this)
  const RunConvention* convention = &kDefaultConvention;
  CameraMatrices camera;                        // CameraDepth::Scene
  CameraMatrices camera_infinite_epsilon;       // CameraDepth::InfiniteEpsilon
  CameraMatrices camera_finite_for_clamp;       // CameraDepth::FiniteForClamp
  std::vector<Vec4<double>> lights;             // homogeneous, scene order
  std::array<Vec3<double>, 2> bounds;           // {min, max}
  std::vector<PreparedCaster> casters;          // scene.objects order
  std::vector<LightFit> light_fits;             // scene.lights order
  std::vector<LightFit> cascade_fits;           // scene.lights order
  PrepareOptions options;

  const CameraMatrices& camera_for(CameraDepth depth) const;
};

// The camera of `scene` as fit_cascades takes it (scene space; aspect = width / height).
CascadeCamera cascade_camera(const Scene& scene);

// Light `light`'s cascaded fit with `count` cascades of `map_size` texels (0: the prepared map size,
// or kDirectionalAutoSize), the default split weight, snapped: fit_cascades for a directional light,
// fit_light for any other (at map_size; 0: the prepared fit). Throws std::logic_error where a matrix
// cannot be built, as prepare_scene.
LightFit cascaded_light_fit(const PreparedScene& prepared, std::size_t light, int map_size = 0,
                            int count = kDefaultCascades);

// Prepares `scene` (which must outlive the result) for `convention`. Throws std::logic_error when
// a matrix cannot be built (the loader has refused every camera and light that could cause it).
// Cost: adjacency of every mesh, and one pass over every vertex (a cube light: every triangle) per light.
PreparedScene prepare_scene(const Scene& scene, const RunConvention& convention = kDefaultConvention,
                            const PrepareOptions& options = {});

}  // namespace shadowref::scene
