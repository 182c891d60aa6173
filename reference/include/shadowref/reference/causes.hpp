// shadowref/reference/causes.hpp — why a candidate's answer at a decided pixel may honestly differ
// from the reference's: the per-pixel causes of the tolerance model (docs/tolerance-model.md),
// computed from the scene, the camera and what the candidate declares (outputs/candidate.hpp).
//
// The model simulates what a correct shadow map with the declared map size and filter can honestly
// answer at the pixel centre's surface point p (normal n toward the viewer) for light L. A texel holds
// the depth of the first surface along its ray from the light (the fit of mathlib/light_fit.hpp at
// the declared map size; for a cube, the face a lookup picks; for a cascaded technique, the cascade
// of cascades.hpp holding p's camera depth, with the declared count) or, where front faces are culled,
// the depth where the ray leaves that first caster, each plus its own polygon's bias. The mask's reach
// h is 1/2 texel on the pack's grid, 1 on the candidate's own, plus the filter (at most
// kMaxMaskFilterTexels). The candidate's answer is explained by
//   * DepthBias (false light) — p's own texel gives lit with the bias and not without, the bias being
//     the declared one (constant, slope-scaled, normal offset, window depth) but never more than a
//     correct map needs there: kCorrectBiasMargin × 2h texels of the stored polygon's slope plus the
//     depth precision. A larger declared bias explains nothing more: its leak is peter-panning.
//   * TexelFootprint — a texel within h of p's (probed on rings every kProbeStep texels out to h, in
//     8 directions) gives the answer:
//     for false light with the bias above; for false shadow with the bias a correct map needs at that
//     texel's distance d from p (d texels of its polygon's slope, plus the precision), whatever is
//     declared, so the receiver's own surface never shadows p: a true boundary lies within the footprint.
//     A filter wider than that may also answer by its 1/2 threshold: its box of taps (placed within
//     the grid's uncertainty) holding at least half that give the answer, each with the bias above —
//     a thin shadow fading, a corner rounding — never a boundary moved.
//   * Acne (unexplained) — a false shadow only a texel with less than that bias gives: the receiver
//     shadowing itself.
//   * Unexplained — nothing gives it, or p faces away from the light (attached shadow).
// Declaring less (a smaller bias, a smaller filter, `pack` for `own`) never explains more.
// Exact techniques (planar, volumes) get no band: the judge never asks for them.
// Cost: one primary ray and up to 2 × 8 × 8 rays toward p's texels per asked pixel (the judge asks
// only for wrong ones).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
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

// tan θ for a polygon whose normal meets the light ray at |cos θ| = c, capped at kMaxBiasSlope.
inline double capped_tan(double c) {
  return std::min(kMaxBiasSlope, c > 0 ? std::sqrt(std::max(0.0, 1.0 - c * c)) / c : kMaxBiasSlope);
}

// The largest slope bias a correct map needs is kCorrectBiasMargin times the one that removes acne
// across the mask's reach h (in texels): a lookup whose texel centre is up to h texels from the
// point along each axis sees the receiver's own plane up to 2 h texels' depth change nearer
// (glPolygonOffset's factor 2 h). Engines set their bias by hand with a margin; ours (a factor of 2
// for nearest lookups on the pack's grid, h = 1/2; 3 for PCF, h = 3/2) stays within twice that.
inline constexpr double kCorrectBiasMargin = 2.0;

// The depth format's precision, relative to the depth from the light: 24-bit window depth under a
// perspective light at a near/far ratio of 1/1000 resolves about 6e-5 of the depth at 10 % of the
// range; 2^-14 (6.1e-5) with the interpolation's own rounding stays above it.
inline constexpr double kDepthPrecision = 1.0 / 16384.0;

// A filtered mask's reach grows with the declared filter radius by at most this many texels (a
// 1/2 threshold over a box of any radius keeps a straight boundary where one tap would put it).
inline constexpr double kMaxMaskFilterTexels = 1.0;

// A wide filter's box is sampled at most this many taps per axis (a coarser stride beyond).
inline constexpr int kMaxFilterTapsPerAxis = 13;

// The probes' spacing in texels: rings at 1/4, 1/2, ... out to the reach, 8 directions each (the
// pack's nearest reach of 1/2 is probed at 1/4 and 1/2).
inline constexpr double kProbeStep = 0.25;

// The probes' 8 directions, in texels of the light view: the axes and the diagonals, each component
// -1, 0 or 1. A ring of radius r is the square of half-side r (the max norm): the texels a lookup
// reads lie within a square of p's, since a texel is a square cell.
inline constexpr std::array<std::array<double, 2>, 8> kProbeDirections{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, 1},
                                                                        {1, -1}, {-1, -1}}};

// The grid's uncertainty, in texels of the declared map: how far from p's own texel centre the texel
// a nearest lookup reads may lie along each axis. Half a texel on a known grid (light_views: pack,
// or declared with the engine's matrices); a whole texel on the candidate's own (its turn and
// phase unknown).
inline double grid_uncertainty_texels(const outputs::CandidateDeclaration& d) {
  return d.light_views == outputs::LightViews::Own ? 1.0 : 0.5;
}

class EmbreeScene;
class CameraRays;

class CauseModel {
 public:
  // Builds the scene's BVH. Throws EmbreeError.
  explicit CauseModel(const scene::PreparedScene& scene);
  ~CauseModel();
  CauseModel(const CauseModel&) = delete;
  CauseModel& operator=(const CauseModel&) = delete;

  // The cause that explains the candidate's answer `candidate_lit` (wrong by the reference) at
  // pixel (x, y) (row 0 at the top) for light `light`, under `declared`. Not const: it reuses one
  // table of traced probes from pixel to pixel (its scratch, reset per pixel: the answer never
  // depends on an earlier call). Not thread-safe, for that reason and the light-fit cache.
  Cause explain(std::size_t light, int x, int y, const outputs::CandidateDeclaration& declared, bool candidate_lit);

  // Soft shadows (the visibility judgement, compare.hpp): the range [lo, hi] of the true lit
  // fraction of light `light` (over its samples, shadow_ray.hpp's lit_fraction) at the pixel
  // centre's surface point p and at the points of p's tangent plane that the declared map's texels
  // within R = grid_uncertainty_texels + filter_radius_texels of p's texel look at (probed at R and R/2 in 8
  // directions, as explain()): what a filter of that footprint may honestly average over. An empty
  // range (lo > hi) when the centre sees no surface. Cost: 17 · samples² shadow rays.
  struct Band {
    double lo = 1, hi = 0;
  };
  Band visibility_band(std::size_t light, int x, int y, const outputs::CandidateDeclaration& declared) const;

  // Soft shadows: the largest change of the true lit fraction of light `light` between p and the
  // points of p's tangent plane that lie h texels of the declared map away (h: the grid's
  // uncertainty, grid_uncertainty_texels; 8 directions, each h texels long: a circle, not
  // explain()'s square, causes.cpp says why). A map reads its caster at
  // texel centres, so a correct map moves a penumbra by up to h texels, the same way along a whole
  // straight edge; no filter averages that away. Where the penumbra is a few texels wide this is
  // what the map's size alone leaves in the fraction (compare/visibility.hpp, the texel shift).
  // 0 when the centre sees no surface. Cost: 9 · samples² shadow rays.
  double visibility_texel_shift(std::size_t light, int x, int y, const outputs::CandidateDeclaration& declared) const;

  // The texel of the declared map (its size, cascades, `pack` grid) that a nearest lookup at pixel
  // (x, y)'s surface point p reads for light `light`: the light view that decides p, the texel's
  // column and row on that view's grid, and p's plane (unit normal toward the viewer, offset) so that
  // callers can tell points of one receiver. nullopt where the centre sees no surface or p faces
  // away from the light (its shadow is attached, not looked up). Cost: one primary ray.
  struct TexelCell {
    int view = 0;
    long column = 0, row = 0;
    Vec3<double> n;
    double offset = 0;  // n · p
    Vec3<double> p;
    double texel = 0;  // the texel's longer side at p, in world units (a declared view's may not be square)
    // Whether `o` lies on this cell's receiver plane: the same plane through both (a cube's two faces
    // meet at an edge; a caster's top and the ground beneath it are parallel but apart). The
    // tolerances are far above the float rounding of a traced hit (about 1e-6 of the scene) and far
    // below any two surfaces' angle or gap.
    bool shares_plane(const TexelCell& o) const {
      const double gap = (o.p - p).norm();
      return n.dot(o.n) > 1.0 - 1e-6 && std::abs(n.dot(o.p) - offset) <= 1e-4 * gap;
    }
  };
  std::optional<TexelCell> texel_cell(std::size_t light, int x, int y, const outputs::CandidateDeclaration& declared) const;

  // What a map of directional light `light` may store along the light's ray through world point
  // `through` (run from beyond the scene's box): the surfaces explain() compares with — the first
  // face met (front faces drawn); the first face the ray leaves a closed caster through, or the first
  // open mesh (front faces culled); and behind an open mesh's face toward the light, the next face
  // left through (that face culled). Each as its point and geometric normal; `nothing` where one of
  // them is no surface at all (the map's far depth). Cost: up to 17 rays.
  struct Stored {
    Vec3<double> p, ng;
  };
  struct StoredAlong {
    std::vector<Stored> surfaces;
    bool nothing = false;
  };
  StoredAlong stored_along(std::size_t light, const Vec3<double>& through) const;

 private:
  // The surface seen through pixel (x, y)'s centre (as the reference finds it): its point and its
  // face normal turned toward the viewer; nullopt when the centre sees none.
  struct Surface {
    Vec3<double> p, n;
  };
  std::optional<Surface> surface_at(int x, int y) const;
  // The true lit fraction of light `light` at the pixel's surface point p (first) and at the points
  // of p's tangent plane that the declared map's texels at `offsets` (in texels of p's light view,
  // the one view or the cube face p is in) look at. Empty when the centre sees no surface.
  std::vector<double> fractions_around(std::size_t light, int x, int y, const outputs::CandidateDeclaration& d,
                                       const std::vector<std::array<double, 2>>& offsets) const;
  // p's place in the light view that decides it (the cube face, the cascade, the one view) at the
  // declared map size, and the depths and widths the probes need.
  struct Lookup {
    Vec3<double> p, n, to_light;
    double light_distance = 0;  // from p to the light; infinite for a directional light
    const LightView* view = nullptr;
    Mat4<double> m, inv;
    Vec3<double> q;                 // p in the light's NDC
    double texel_ndc = 0, zn = 0, zf = 0, axis_sign = 1;
    double depth_p = 0, texel = 0, tan_p = 0, depth_bias_world = 0;
    double texel_aspect = 1;  // a texel's world length along the view's y over its length along x
    bool perspective = false;
    // Declared matrices: their depth range is the engine's, and a correct map holds every caster
    // along a texel's ray (a near plane that clips a caster is the engine's fault, not a cause), so
    // the rays run from the light (a directional light's from `reach` before the near plane) to
    // `reach` beyond the far plane (the scene's box lies within reach of any point on them).
    bool whole_ray = false;
    Vec3<double> light_at;
    double reach = 0;
    double depth(const Vec3<double>& w) const;  // along the light's view axis
    double texel_at(double at) const;           // one texel's width at light depth `at`
  };
  // `view`: the light view to look p up in; -1: the one that decides p (light_view_of).
  std::optional<Lookup> lookup(std::size_t light, const Surface& s, const outputs::CandidateDeclaration& d,
                               int view = -1) const;
  // The cascade that declared blending mixes into p's (the next one, where p lies in the blended
  // far end of its own: "cascade_blend"), or -1.
  int blended_view(std::size_t light, const Vec3<double>& p, const outputs::CandidateDeclaration& d) const;
  // explain() in one light view.
  Cause explain_in(const Lookup& k, const outputs::CandidateDeclaration& d, bool candidate_lit);
  // The bias a map adds to the depth it stores at a polygon of normal `ng`, met along `along` at
  // light depth `at`.
  using BiasOf = std::function<double(const Vec3<double>& ng, const Vec3<double>& along, double at)>;
  // The texel rays one explain() has traced, by offset: a probe's answer depends on the bias only
  // through arithmetic on what its ray met, so each offset is traced once (causes.cpp).
  class Probes;
  template <class Bias>  // BiasOf's signature; a lambda where the caller has one (no std::function per probe)
  bool texel_gives(const Lookup& k, Probes& probes, double dx, double dy, bool candidate_lit, const Bias& bias) const;
  // Whether p's own way to the light meets no open mesh's face toward the light (traced once per
  // pixel): where it does, a map that culls open meshes' front faces loses p's own shadow.
  bool open_meshes_clear(const Lookup& k, Probes& probes) const;
  // The mask's reach in texels: the lookup's grid (pack or own) and the filter, capped.
  static double mask_reach_texels(const outputs::CandidateDeclaration& d);
  // A filter wider than kMaxMaskFilterTexels: whether its box of taps, placed at p's texel or
  // shifted by the grid's uncertainty, may have at least half of them give the candidate's answer
  // (a 1/2 threshold: thin shadows fade, corners round), each tap's stored depth carrying
  // bias_at(its offset). False for narrower filters (the rings cover them).
  bool filter_may_answer(const Lookup& k, Probes& probes, const outputs::CandidateDeclaration& d, bool candidate_lit,
                         const std::function<BiasOf(double, double)>& bias_at) const;
  // The light's views at map size `size` (0: the prepared size), cascaded with `cascades` cascades
  // (0: not cascaded).
  const LightFit& fit_for(std::size_t light, int size, int cascades) const;
  // The views the declaration's map is drawn on: its declared matrices ("light_views": "declared",
  // at its map size, a cube's faces or cascades as declared), else fit_for(its size, `cascades`).
  const LightFit& fit_of(std::size_t light, const outputs::CandidateDeclaration& d, int cascades) const;
  const scene::PreparedScene& scene_;
  std::unique_ptr<EmbreeScene> embree_;
  std::unique_ptr<CameraRays> camera_;
  // The light fits per declared (light, map size, cascades): a memo of fit_for(), which the const
  // queries share; filling it changes no answer, hence mutable (and the model not thread-safe).
  mutable std::map<std::tuple<std::size_t, int, int>, LightFit> fits_;
  // The declared fits, by light and the declared matrices' bytes (the same memo for declarations).
  mutable std::map<std::string, LightFit> declared_fits_;
  std::unique_ptr<Probes> probes_;  // explain()'s table of traced probes, reused from pixel to pixel
};

}  // namespace shadowref::reference
