// shadowref/reference/causes.hpp — why a candidate's answer at a decided pixel may honestly differ
// from the reference's: the per-pixel causes of the tolerance model (docs/tolerance-model.md),
// computed from the scene, the camera and what the candidate declares (outputs/candidate.hpp).
//
// The model simulates what a shadow map with the declared map size, filter and bias can honestly
// answer at the pixel centre's surface point p (normal n toward the viewer) for light L. A texel holds
// the depth of the first surface along its ray from the light (the fit of mathlib/light_fit.hpp at
// the declared map size; for a cube, the face a lookup picks; for a cascaded technique, the cascade
// of cascades.hpp holding p's camera depth, with the declared count) or, where front faces are culled, the
// depth where the ray leaves that first caster; through it p is lit when p is not beyond that depth
// by more than the stored polygon's bias b = constant_bias + slope_bias_texels · texel · tan θ
// (glPolygonOffset's model: texel = one texel's width there in world units, θ between the stored
// polygon's normal and the light ray, tan θ capped at kMaxBiasSlope). The candidate's answer is
// explained by
//   * DepthBias — p's own texel gives it with the bias and not without: a caster–receiver contact
//     within the bias (peter-panning);
//   * TexelFootprint — a texel within R = 1 + filter_radius_texels texels of p's (probed at R and
//     R/2 in 8 directions) gives it with the bias: a true boundary, a silhouette seen from the light
//     or a slope steeper than the bias lies within the footprint (acne at grazing incidence);
//   * Unexplained — no such texel gives it, or p faces away from the light (attached shadow): an
//     error of the candidate.
// Exact techniques (planar, volumes) get no band: the judge never asks for them.
// Cost: one primary ray and up to 18 rays toward p's texels per asked pixel (the judge asks only
// for wrong ones).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <tuple>
#include <vector>

#include "shadowref/light_fit.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/cause.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::reference {

using outputs::Cause;

// tan θ above this (θ > 84°) is taken as this: at grazing incidence the slope term would explain
// any error, and a 10-fold slope is already more than any engine's slope-scaled bias allows for.
inline constexpr double kMaxBiasSlope = 10.0;

class EmbreeScene;

class CauseModel {
 public:
  // Builds the scene's BVH. Throws EmbreeError.
  explicit CauseModel(const scene::PreparedScene& scene);
  ~CauseModel();
  CauseModel(const CauseModel&) = delete;
  CauseModel& operator=(const CauseModel&) = delete;

  // The cause that explains the candidate's answer `candidate_lit` (wrong by the reference) at
  // pixel (x, y) (row 0 at the top) for light `light`, under `declared`. Not thread-safe (it
  // caches light fits per declared map size).
  Cause explain(std::size_t light, int x, int y, const outputs::CandidateDeclaration& declared, bool candidate_lit) const;

  // Soft shadows (the visibility judgement, compare.hpp): the range [lo, hi] of the true lit
  // fraction of light `light` (over its samples, shadow_ray.hpp's lit_fraction) at the pixel
  // centre's surface point p and at the points of p's tangent plane that the declared map's texels
  // within R = (0.5 or 1) + filter_radius_texels of p's texel look at (probed at R and R/2 in 8
  // directions, as explain()): what a filter of that footprint may honestly average over. An empty
  // range (lo > hi) when the centre sees no surface. Cost: 17 · samples² shadow rays.
  struct Band {
    double lo = 1, hi = 0;
  };
  Band visibility_band(std::size_t light, int x, int y, const outputs::CandidateDeclaration& declared) const;

 private:
  // The surface seen through pixel (x, y)'s centre (as the reference finds it): its point and its
  // face normal turned toward the viewer; nullopt when the centre sees none.
  struct Surface {
    Vec3<double> p, n;
  };
  std::optional<Surface> surface_at(int x, int y) const;
  // The light's views at map size `size` (0: the prepared size), cascaded with `cascades` cascades
  // (0: not cascaded).
  const LightFit& fit_for(std::size_t light, int size, int cascades) const;
  const scene::PreparedScene& scene_;
  std::unique_ptr<EmbreeScene> embree_;
  Mat4<double> inverse_clip_;
  mutable std::map<std::tuple<std::size_t, int, int>, LightFit> fits_;
};

}  // namespace shadowref::reference
