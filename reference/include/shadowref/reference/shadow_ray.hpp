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

#include <limits>
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
// The shadow ray of rule 2 from p toward L, written into `ray` when the answer is Trace (`ray` is
// left alone otherwise). `offset` > 0 is the start offset along n (the reference uses 1 and 4
// epsilons); the ray is in float, as Embree wants it. Cost: one square root and one division per
// component (a point light) or the normalisation of L (a directional light). Inline, and writing
// straight into the caller's stream slot, because the reference builds one per sample and light
// sample: returning the 48-byte ray by value made every copy into the stream a store-forwarding
// stall (the fields are written 4 and 8 bytes at a time, then read 16 at a time): perf put half
// of reference_bench's BM_ShadowRays_Ours samples on that one copy.
inline ShadowRayKind make_shadow_ray(const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L, double offset,
                                     RTCRay& ray) {
  const bool directional = L[3] == 0;
  // Rule 1 needs only the sign of n · (direction to L): facing() > 0 exactly when this is > 0,
  // the division by the (positive) distance cannot change a sign, and a distance of 0 gives 0.
  const Vec3<double> to_light = directional ? Vec3<double>(L.head<3>()) : Vec3<double>(L.head<3>() - p);
  if (!(n.dot(to_light) > 0)) return ShadowRayKind::Attached;
  const Vec3<double> o = p + offset * n;
  Vec3<double> d;
  double tfar = std::numeric_limits<double>::infinity();
  if (directional) {
    d = L.head<3>().normalized();
  } else {
    d = L.head<3>() - o;
    const double len = d.norm();
    if (len <= 2 * offset) return ShadowRayKind::Touching;
    d /= len;
    tfar = len - offset;
  }
  ray.org_x = static_cast<float>(o.x());
  ray.org_y = static_cast<float>(o.y());
  ray.org_z = static_cast<float>(o.z());
  ray.dir_x = static_cast<float>(d.x());
  ray.dir_y = static_cast<float>(d.y());
  ray.dir_z = static_cast<float>(d.z());
  ray.tnear = 0.0f;
  ray.tfar = static_cast<float>(tfar);
  ray.mask = 0xFFFFFFFFu;
  ray.flags = 0;
  return ShadowRayKind::Trace;
}

// Rule 1 and 2 for one light point with single-ray tracing: true when lit.
class EmbreeScene;
bool lit(const EmbreeScene& scene, const Vec3<double>& p, const Vec3<double>& n, const Vec4<double>& L, double offset);

// The lit fraction of `light` at (p, n): the mean of lit() over light_samples(light), with the
// scene's epsilon as the offset. For tests and single queries.
double lit_fraction(const EmbreeScene& scene, const Vec3<double>& p, const Vec3<double>& n, const scene::Light& light);

}  // namespace shadowref::reference
