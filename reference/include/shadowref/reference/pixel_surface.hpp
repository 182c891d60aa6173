// shadowref/reference/pixel_surface.hpp — the surface seen through a point of a pixel, defined once:
// the reference's images (render.hpp) and the cause model (causes.hpp) both find it here, so the
// two can never disagree about which surface a pixel shows (at the camera's far plane, on a
// degenerate triangle, at a fold).
//
// The ray leaves the near plane (what a rasteriser clips at) through the pixel point's NDC
// (scene::pixel_to_ndc), unprojected through inverse(P · V) of the prepared camera in its run
// convention, toward the point halfway to the far plane in clip depth (finite even with an infinite
// far), and ends at the far plane when the camera has one. The surface is the first hit: its point
// (from the barycentrics, in double), its face normal turned toward the viewer (two-sided; a
// zero-area triangle's normal is the reversed ray), its object and albedo.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>

#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::reference {

struct Surface {
  bool hit = false;
  Vec3<double> p = Vec3<double>::Zero();
  Vec3<double> n = Vec3<double>::Zero();  // unit face normal, toward the viewer
  Vec3<float> albedo = Vec3<float>::Zero();
  std::uint32_t object = 0;  // the scene object hit (Embree's geomID)
};

// Sub-samples of one pixel see one smooth surface only when each lies on the centre's object, no
// farther from the centre's tangent plane than kCreaseSine times its distance from the centre, and
// with a normal within asin(kCreaseSine) = 30° of the centre's: boxes, stairs and walls fold by 90°,
// while the catalogue's tessellated spheres and tori (≥ 24 segments) bend by at most 15° per facet.
// The normal test catches a fold whose other face lies almost in the centre's plane near the edge
// (a plate's top face seen a hair below its front edge: millimetres behind the front plane, yet
// another face that a rasteriser snapping vertices to 1/16 px may show at the centre).
inline constexpr double kCreaseSine = 0.5;
inline constexpr double kCreaseCosine = 0.86602540378443865;  // sqrt(1 - kCreaseSine²)
bool same_smooth_surface(const Surface& centre, const Surface& sample, double epsilon);

// The pixel point's camera ray for `scene` (pixel (x, y), row 0 at the top, at (sx, sy) inside it),
// written into `rh` as Embree wants it (geomID invalid: no hit yet).
void pixel_ray(const scene::PreparedScene& scene, const Mat4<double>& inverse_clip, int x, int y, double sx, double sy,
               RTCRayHit& rh);

// The surface `rh` hit after tracing (hit false on a miss).
Surface surface_of(const scene::Scene& scene, const RTCRayHit& rh);

}  // namespace shadowref::reference
