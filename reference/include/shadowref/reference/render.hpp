// shadowref/reference/render.hpp — the ray-traced ground truth of a scene (docs/output-contract.md).
//
// For each pixel: one primary ray through the pixel centre and samples_per_axis² through the
// centres of a regular sub-pixel grid, each from the near plane (and to the far plane when the
// camera has one), unprojected through inverse(P · V) with P and V from the prepared scene — the
// matrices the OpenGL renderer uses, in the same run convention (camera_rays.hpp: defined in
// float, bit for bit). At each hit (pixel_surface.hpp), the visibility rule of shadow_ray.hpp for
// every light. A tile's rays are built 8 or 4 at a time into structure-of-arrays streams and
// traced with rtcIntersectNp / rtcOccludedNp.
//
//   mask      the pixel-centre answer toward the light's homogeneous point (scene::homogeneous:
//             the centre of a rect light): 255 lit, 0 shadowed, 128 no surface.
//   visibility the lit fraction over the sub-pixel samples that hit a surface and the light's
//             samples; −1 where no sub-pixel sample hits a surface.
//   decided   255 when the pixel's answer cannot honestly go the other way: every sub-pixel
//             sample gives the centre's answer (same surface-or-not, and for a rect light a
//             fraction of exactly 0 or 1, i.e. no penumbra), the centre's answer is the same with
//             the shadow ray's start nudged from 1 to 4 epsilons, the centre does not face
//             the light at a grazing angle (|facing| >= kGrazingCosine), and the pixel is FULLY
//             covered by one smooth surface: every sub-pixel sample hits the centre's object, no
//             farther from the centre's tangent plane than kCreaseSine times its distance from
//             the centre, with a normal within 30° of the centre's (no depth discontinuity or
//             fold inside the pixel: pixel_surface.hpp's same_smooth_surface). 0 otherwise.
//             The last rule is the VK-GL-CTS rasterization verifier's "partially covered" class:
//             where an edge crosses a pixel, a rasteriser may honestly resolve the centre to
//             either side, and a shadow map's texel may hold either surface's depth.
//   shaded    flat-shaded Lambert (face normals; the cosine in float, shadow_ray.hpp's
//             accumulate_lit), ambient 0.1, the spot cone as a hard cut-off, averaged over the
//             sub-pixel samples, sRGB-encoded, RGB8.
// With several lights, each light gets its own mask, visibility and decided image; the
// aggregate visibility is the mean over lights and the aggregate decided the AND.
//
// Determinism: every pixel is computed from its own rays in a fixed order, so the images do not
// depend on the thread count or the tile schedule (tested bit for bit).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shadowref/scene/prepared_scene.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::reference {

// Below this facing cosine a surface is lit or shadowed by a hair: the OpenGL renderer computes
// n · l in float from interpolated data (relative errors around 1e-6), so its sign can differ
// from ours; 1e-4 gives that a 100-fold margin, about 0.006 degrees of grazing angle.
inline constexpr double kGrazingCosine = 1e-4;

struct Options {
  int samples_per_axis = 4;  // sub-pixel grid: samples_per_axis², in [1, 16]
  int threads = 0;           // 0: all cores
  // Embree's device configuration (EmbreeScene): empty in production, where Embree picks its
  // kernel for the CPU; "isa=sse2", "isa=avx2", ... force one. Only undecided pixels may depend on it.
  std::string embree_config;
};

struct LightImages {
  std::vector<std::uint8_t> mask;      // width · height, row 0 at the top
  std::vector<float> visibility;       // width · height
  std::vector<std::uint8_t> decided;   // width · height
};

struct Images {
  int width = 0;
  int height = 0;
  std::vector<LightImages> lights;     // one per scene light, in scene order
  std::vector<float> visibility;       // the mean over lights (equal to lights[0] for one light)
  std::vector<std::uint8_t> decided;   // the AND over lights
  // 255 where the pixel is fully covered by one smooth surface (the last rule of `decided`, without
  // the light): every sub-pixel sample hits the centre's object within kCreaseSine of its tangent
  // plane. The visibility judgement (soft shadows) compares only these: elsewhere the reference's
  // fraction mixes surfaces that a candidate's centre sample cannot.
  std::vector<std::uint8_t> covered;
  std::vector<std::uint8_t> shaded;    // width · height · 3, RGB
};

struct Stats {
  std::uint64_t primary_rays = 0;
  std::uint64_t shadow_rays = 0;
  double seconds_build = 0;            // BVH build
  double seconds_render = 0;           // everything after the build
  double seconds_shadow_calls = 0;     // summed over threads: inside occlude_shadow_rays (Embree, and a byte a ray)
  double seconds_shadow_phase = 0;     // summed over threads: building, tracing and reading shadow rays
  double seconds_primary_calls = 0;    // summed over threads: inside rtcIntersect1M only
  // Summed over threads: the whole ray work of the tiles — building and tracing the primary rays,
  // the surfaces from their hits, building and tracing the shadow rays (the decided test's nudged
  // rays included) and reading their answers; not the shading sums nor the gathering of the
  // answers into pixels. Over seconds_primary_calls +
  // seconds_shadow_calls it is the cost of the reference's rays against bare Embree on the very
  // same rays (reference_bench reports it).
  double seconds_ray_work = 0;
};

// Renders the reference of the prepared scene (its camera matrices, in its run convention: rays
// start on the near plane and, with a far plane, stop at it). Throws std::invalid_argument for
// options out of range and EmbreeError when Embree fails.
Images render(const scene::PreparedScene& scene, const Options& options = {}, Stats* stats = nullptr);
// The same in the default convention (gl).
Images render(const scene::Scene& scene, const Options& options = {}, Stats* stats = nullptr);

}  // namespace shadowref::reference
