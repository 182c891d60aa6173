// shadowref/reference/shadow_ray.hpp — the visibility rule of the reference, in one place.
//
// A surface point p with unit normal n (the face normal turned toward the viewer) sees a light
// point L (homogeneous: w = 1 a position, w = 0 a direction toward the light) when
//   1. it faces L: n · (direction to L) > 0 — otherwise it is in its own ATTACHED shadow (the
//      surface itself is between p and L), shadowed without tracing; and
//   2. the segment from p + offset · n to L (to infinity for w = 0) hits nothing, where the
//      segment stops `offset` short of a point light so that geometry touching the light does
//      not count.
// Every mask, visibility and decided value of the reference follows this rule; the renderer
// traces the rays in streams, lit() traces single ones, both built by build_shadow_rays.
#pragma once

#include <embree3/rtcore.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "shadowref/conventions.hpp"
#include "shadowref/reference/ray_stream.hpp"
#include "shadowref/reference/simd_path.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::reference {

// The points a light is sampled at, homogeneous. Point, spot: its position (w = 1). Directional:
// its direction toward the light (w = 0). Rect: the centres of a samples × samples grid over the
// parallelogram (deterministic stratification: no random numbers, so outputs are reproducible),
// row by row along edge_v, each row along edge_u.
std::vector<Vec4<double>> light_samples(const scene::Light& light);

// The facing cosine n · normalize(direction to L), in [−1, 1]; L's xyz is taken as a direction
// when w = 0. A point exactly at L (distance 0) gives 0.
double facing(const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L);

// What rule 1 and the ray construction decide before any tracing.
enum class ShadowRayKind {
  Attached,  // facing <= 0: shadowed, no ray
  Touching,  // a point light within 2 offsets of the start: lit (nothing fits in between), no ray
  Trace,     // `ray` decides
};

// The shadow rays of rule 2, defined in float so that they are built 8 (AVX2) or 4 (SSE) at a
// time, with the same bits whatever the batch, thread or variant (simd_path.hpp; shadow_ray.cpp is
// compiled with -ffp-contract=off and runs with denormals flushed, as camera_rays.hpp).
// For a surface point p and unit normal n (the surface's double values rounded to float), the
// light point L rounded to float (a direction: L.xyz normalised in double first) and the offset
// rounded to float, in this order:
//   t      = L.xyz − p (a point light) or L.xyz (a direction)
//   rule 1: (n.x·t.x + n.y·t.y) + n.z·t.z > 0, else Attached (no ray)
//   org    = p + offset·n                          per component
//   a point light: g = L.xyz − org, len = sqrt((g.x·g.x + g.y·g.y) + g.z·g.z); Touching when
//          len <= 2·offset (no ray); dir = g / len, tfar = len − offset
//   a direction:   dir = L.xyz, tfar = +inf
//   tnear  = 0
// A ray that is not traced is left inactive in the stream (RayStream::set_inactive: tnear > tfar,
// so Embree skips it) and reads as its answer: Attached shadowed, Touching lit.
struct SurfacePoints {
  const float *px, *py, *pz;  // points
  const float *nx, *ny, *nz;  // unit normals toward the viewer (0: no surface, which reads Attached)
};
// The rays from `count` surface points toward L, written into `out` at first + i (`out` must hold
// first + count rays). Cost: about 25 float operations, a division and a square root a ray.
void build_shadow_rays(const SurfacePoints& points, std::size_t count, const Vec4<double>& L, double offset,
                       RayStream& out, std::size_t first, SimdPath path = best_simd_path());

// The shadow-ray stage of render()'s tiles, for one batch: the `count` rays built in `rays` (from 0,
// by build_shadow_rays) traced with rtcOccludedNp in a coherent context under flush-to-zero and
// denormals-are-zero (flush_denormals.hpp), and each answer written to lit[i]: 1 lit (Embree left
// tfar >= 0, or an inactive ray set lit), 0 shadowed. bench/reference_bench.cpp times this very
// function. Cost: Embree's, and a byte a ray.
class EmbreeScene;
void occlude_shadow_rays(const EmbreeScene& scene, RayStream& rays, std::size_t count, std::uint8_t* lit);

// One ray of the above from double inputs (rounded to float inside): its kind, and the ray in
// `ray` when Trace (left alone otherwise). build_shadow_rays() on a stream of one: the same bits.
ShadowRayKind make_shadow_ray(const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L, double offset,
                              RTCRay& ray);

// The Lambert share of the lit answers, for shading (render.cpp's shaded image, after the shadow
// rays): for each of `count` surface points i, where lit[i] is non-zero, lit_count[i] += 1 and
// direct[i] += max(0, f) with f = facing(p, n, L) computed in float. One light point for all
// points, so that the loop runs over the points, 8 or 4 at a time; each direct[i] is summed in the
// caller's order of light points, so that the result never depends on the batch. Cost: about 15
// float operations, a square root and a division a point.
void accumulate_lit(const SurfacePoints& points, std::size_t count, const Vec4<double>& L, const std::uint8_t* lit,
                    double* direct, std::uint32_t* lit_count, SimdPath path = best_simd_path());

// Rule 1 and 2 for one light point with single-ray tracing: true when lit.
bool lit(const EmbreeScene& scene, const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L, double offset);

// The lit fraction of `light` at (p, n): the mean of lit() over light_samples(light), with the
// scene's epsilon as the offset. For tests and single queries.
double lit_fraction(const EmbreeScene& scene, const Vec3<double>& p, const Vec3<double>& n, const scene::Light& light);

}  // namespace shadowref::reference
