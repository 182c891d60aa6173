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
// traces the rays in streams, lit() traces single ones, both through make_shadow_ray.
#pragma once

#include <embree3/rtcore.h>

#include <vector>

#include "shadowref/conventions.hpp"
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
struct ShadowRay {
  ShadowRayKind kind = ShadowRayKind::Attached;
  RTCRay ray{};
};

// The shadow ray of rule 2 from p toward L. `offset` > 0 is the start offset along n (the
// reference uses 1 and 4 epsilons); the ray is in float, as Embree wants it.
ShadowRay make_shadow_ray(const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L, double offset);

// Rule 1 and 2 for one light point with single-ray tracing: true when lit.
class EmbreeScene;
bool lit(const EmbreeScene& scene, const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L, double offset);

// The lit fraction of `light` at (p, n): the mean of lit() over light_samples(light), with the
// scene's epsilon as the offset. For tests and single queries.
double lit_fraction(const EmbreeScene& scene, const Vec3<double>& p, const Vec3<double>& n, const scene::Light& light);

}  // namespace shadowref::reference
