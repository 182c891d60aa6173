// causes.cpp — the per-pixel causes of the tolerance model (causes.hpp), traced with Embree and
// the reference's own visibility rule (shadow_ray.hpp).
#include "shadowref/reference/causes.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "shadowref/reference/flush_denormals.hpp"
#include "shadowref/reference/camera_rays.hpp"
#include "shadowref/reference/embree_scene.hpp"
#include "shadowref/reference/pixel_surface.hpp"
#include "shadowref/reference/shadow_ray.hpp"
#include "shadowref/cascades.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/scene/camera.hpp"

namespace shadowref::reference {
namespace {

// The first hit along the ray from `o` along the unit `dir`, up to `tfar` (Embree: geomID invalid on a miss).
RTCRayHit first_hit(RTCScene scene, const Vec3<double>& o, const Vec3<double>& dir, float tfar) {
  RTCRayHit r;
  start_ray(o, dir, tfar, r);
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect1(scene, &ctx, &r);
  return r;
}

Vec3<double> unproject(const Mat4<double>& inv, double x, double y, double z) {
  const Vec4<double> h = inv * Vec4<double>(x, y, z, 1.0);
  return h.head<3>() / h.w();
}

Vec3<double> normal_of(const RTCRayHit& r) { return Vec3<double>(r.hit.Ng_x, r.hit.Ng_y, r.hit.Ng_z); }

// How a walk along a light ray ended: at a face, at the ray's end (nothing more drawn), or after
// kWalkFaces faces without an answer (a walk too long to follow).
enum class WalkEnd { Face, Nothing, TooLong };
struct WalkStop {
  WalkEnd end;
  RTCRayHit hit;  // the face, where end is Face
  bool leaves;    // whether that face's normal points along the ray (the ray leaves a caster there)
};
constexpr int kWalkFaces = 8;

// The two walks along a map's ray that every pass with culling makes (explain()'s rule, shared by
// texel_gives and stored_along). `next_after(t)` traces the next face beyond t along the unit `dir`.
// From face `r` on: the first face the ray leaves through, or the first face of an open mesh
// (`open(geomID)`) — what a pass that culls front faces stores.
template <class NextAfter, class IsOpen>
WalkStop walk_to_exit(RTCRayHit r, const Vec3<double>& dir, double eps, const NextAfter& next_after, const IsOpen& open) {
  for (int step = 0; step < kWalkFaces; ++step) {
    const bool leaves = normal_of(r).dot(dir) > 0;
    if (leaves || open(r.hit.geomID)) return {WalkEnd::Face, r, leaves};
    r = next_after(static_cast<double>(r.ray.tfar) + eps);
    if (r.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {WalkEnd::Nothing, r, false};
  }
  return {WalkEnd::TooLong, r, false};
}

// Beyond t (an open mesh's face toward the light, culled too): the first face the ray leaves through.
template <class NextAfter>
WalkStop walk_out_behind(double t, const Vec3<double>& dir, double eps, const NextAfter& next_after) {
  RTCRayHit b{};
  for (int step = 0; step < kWalkFaces; ++step) {
    b = next_after(t + eps);
    if (b.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {WalkEnd::Nothing, b, false};
    if (normal_of(b).dot(dir) > 0) return {WalkEnd::Face, b, true};
    t = static_cast<double>(b.ray.tfar);
  }
  return {WalkEnd::TooLong, b, false};
}

}  // namespace


const LightFit& CauseModel::fit_for(std::size_t light, int size, int cascades) const {
  if (cascades == 0 && (size == 0 || size == scene_.light_fits[light].size)) return scene_.light_fits[light];
  if (cascades == kDefaultCascades && (size == 0 || size == scene_.cascade_fits[light].size))
    return scene_.cascade_fits[light];
  const auto key = std::make_tuple(light, size, cascades);
  auto it = fits_.find(key);
  if (it == fits_.end()) {
    if (cascades > 0) {
      it = fits_.emplace(key, scene::cascaded_light_fit(scene_, light, size, cascades)).first;
    } else {
      std::vector<const TriangleMesh<float>*> meshes;
      for (const scene::Object& o : scene_.scene->objects) meshes.push_back(&o.mesh);
      LightFitOptions o;
      o.map_size = size;
      it = fits_.emplace(key, fit_light(*scene_.convention, scene_.lights[light], meshes, o).value()).first;
    }
  }
  return it->second;
}

const LightFit& CauseModel::fit_of(std::size_t light, const outputs::CandidateDeclaration& d, int cascades) const {
  if (d.light_views != outputs::LightViews::Declared || d.views.empty()) return fit_for(light, d.shadow_map_size, cascades);
  std::string key(reinterpret_cast<const char*>(&light), sizeof light);
  key.append(reinterpret_cast<const char*>(&d.shadow_map_size), sizeof d.shadow_map_size);
  for (const outputs::DeclaredView& v : d.views) {
    key.append(reinterpret_cast<const char*>(v.view.data()), sizeof v.view);
    key.append(reinterpret_cast<const char*>(v.projection.data()), sizeof v.projection);
  }
  key.append(reinterpret_cast<const char*>(d.cascade_splits.data()), d.cascade_splits.size() * sizeof(double));
  auto it = declared_fits_.find(key);
  if (it != declared_fits_.end()) return it->second;
  // The judge has checked the counts (a cube's 6 for a positional light; cascades with their
  // splits for a directional one) and that each projection x view is invertible.
  LightFit fit;
  fit.size = d.shadow_map_size;
  for (const outputs::DeclaredView& v : d.views) {
    LightView view;
    view.view = Eigen::Map<const Mat4<double>>(v.view.data());  // column-major, as Eigen's default
    view.projection = Eigen::Map<const Mat4<double>>(v.projection.data());
    fit.views.push_back(view);
  }
  fit.cube = scene_.lights[light].w() != 0 && fit.views.size() == 6;
  if (!d.cascade_splits.empty() && fit.views.size() > 1) {
    fit.cascade_splits = d.cascade_splits;
    // The camera's view-axis depth of a scene point, as the pack's cascades measure it.
    fit.cascade_depth_from_scene = scene_.cascade_fits[light].cascade_depth_from_scene;
  }
  return declared_fits_.emplace(std::move(key), std::move(fit)).first->second;
}

std::optional<CauseModel::Surface> CauseModel::surface_at(int x, int y) const {
  // The pixel centre's surface, exactly as the reference finds it (pixel_surface.hpp): the same
  // ray (camera_rays.hpp), traced through the same Embree call on a stream of one.
  thread_local RayStream one;
  one.resize(1);
  const float u = CameraRays::image_point(x, 0.5), v = CameraRays::image_point(y, 0.5);
  camera_->build(&u, &v, 1, one, 0);
  one.reset_hits();
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  const RTCRayHitNp hits = one.ray_hits();
  {
    const FlushDenormalsGuard ftz;
    rtcIntersectNp(embree_->handle(), &ctx, &hits, 1);
  }
  float px, py, pz, nx, ny, nz;
  const SurfaceArrays arrays{&px, &py, &pz, &nx, &ny, &nz};
  hit_surfaces(one, 0, 1, arrays);
  const reference::Surface found = surface_of(*scene_.scene, one, 0, arrays, 0);
  if (!found.hit) return std::nullopt;
  return Surface{found.p, found.n};
}

namespace {
// The sign of view-space z that points away from the light, read from a projection: a perspective
// one's w row (w = P(3,2) z grows with distance), an orthographic one's depth row (NDC z runs from
// zn at the near plane to zf at the far one, so z grows away from the light where P(2,2) has the
// sign of zf − zn).
double view_axis_sign(const Mat4<double>& projection, double zn, double zf) {
  if (projection(3, 2) != 0) return projection(3, 2) > 0 ? 1.0 : -1.0;
  return (projection(2, 2) > 0) == (zf > zn) ? 1.0 : -1.0;
}
}  // namespace

namespace {
// The cascades a declaration's technique splits a directional light's map into (0: not cascaded).
int cascades_of(const outputs::CandidateDeclaration& d) {
  const outputs::TechniqueName* technique = outputs::find_technique_name(d.technique);
  return technique && technique->cascaded ? (d.cascades ? d.cascades : kDefaultCascades) : 0;
}
}  // namespace

std::optional<CauseModel::Lookup> CauseModel::lookup(std::size_t light, const Surface& s,
                                                     const outputs::CandidateDeclaration& d, int view) const {
  Lookup k;
  k.p = s.p;
  k.n = s.n;
  const Vec4<double>& L = scene_.lights[light];
  k.to_light = L.w() == 0 ? Vec3<double>(L.head<3>().normalized()) : Vec3<double>((L.head<3>() / L.w() - s.p).normalized());
  k.light_distance = L.w() == 0 ? std::numeric_limits<double>::infinity() : (L.head<3>() / L.w() - s.p).norm();
  // The light view that decides p: the cube face, the cascade, or the one view (light_view_of).
  const LightFit& fit = fit_of(light, d, cascades_of(d));
  k.view = &fit.views[static_cast<std::size_t>(view >= 0 ? view : light_view_of(fit, L, s.p))];
  k.m = k.view->projection * k.view->view;
  const Vec4<double> h = k.m * Vec4<double>(s.p.x(), s.p.y(), s.p.z(), 1.0);
  if (!(h.w() > 0)) return std::nullopt;
  k.q = h.head<3>() / h.w();
  k.inv = k.m.inverse();
  k.texel_ndc = 2.0 / fit.size;
  k.zn = near_ndc_z(*scene_.convention);
  k.zf = far_ndc_z(*scene_.convention);
  // Depth from the light, in world units along its view axis (the light's view looks down −z when
  // right-handed, +z when left-handed). Declared matrices say it themselves, whatever the run's
  // convention: an engine may draw its maps left-handed in a right-handed scene (Babylon.js does).
  k.axis_sign = scene_.convention->clip.hand == Handedness::Right ? -1.0 : 1.0;
  if (d.light_views == outputs::LightViews::Declared && !d.views.empty())
    k.axis_sign = view_axis_sign(k.view->projection, k.zn, k.zf);
  k.depth_p = k.depth(s.p);
  // One texel's width at p, in world units (on the plane of constant light depth through p).
  k.texel = (unproject(k.inv, k.q.x() + k.texel_ndc, k.q.y(), k.q.z()) - unproject(k.inv, k.q.x(), k.q.y(), k.q.z())).norm();
  // A declared view's texels need not be square (an off-centre box of another aspect, a warp):
  // the world length of one texel along y, in texels along x.
  k.texel_aspect = (unproject(k.inv, k.q.x(), k.q.y() + k.texel_ndc, k.q.z()) - unproject(k.inv, k.q.x(), k.q.y(), k.q.z())).norm() / k.texel;
  k.perspective = L.w() != 0;
  if (d.light_views == outputs::LightViews::Declared && !d.views.empty()) {
    k.whole_ray = true;
    k.light_at = k.perspective ? Vec3<double>(L.head<3>() / L.w()) : Vec3<double>::Zero();
    const Vec3<double> lo = scene_.bounds[0], hi = scene_.bounds[1];
    k.reach = (hi - lo).norm() + (0.5 * (lo + hi) - k.light_at).norm() + (s.p - k.light_at).norm();
  }
  k.tan_p = capped_tan(std::abs(s.n.dot(k.to_light)));
  // A window-depth bias, in world units at p: the depth the point moves when its window depth moves
  // by `depth_bias` toward the far plane (zf - zn is the NDC span of window depth 0..1: 2, 1, or -1 reversed).
  if (d.depth_bias > 0 && d.depth == outputs::StoredDepth::Distance) {
    // A distance map's bias is a distance along the light ray: its share of the map's range.
    k.depth_bias_world = d.depth_bias * d.depth_range;
  } else if (d.depth_bias > 0) {
    const double z = k.q.z() + d.depth_bias * (k.zf - k.zn);
    k.depth_bias_world = std::abs(k.depth(unproject(k.inv, k.q.x(), k.q.y(), z)) - k.depth_p);
  }
  return k;
}

std::optional<CauseModel::TexelCell> CauseModel::texel_cell(std::size_t light, int x, int y,
                                                             const outputs::CandidateDeclaration& d) const {
  const std::optional<Surface> s = surface_at(x, y);
  if (!s) return std::nullopt;
  const std::optional<Lookup> k = lookup(light, *s, d);
  if (!k || !(s->n.dot(k->to_light) > 0)) return std::nullopt;
  // NDC −1..1 spans the view's texels 0..size (the viewport transform); texel_ndc = 2 / size.
  TexelCell c;
  c.view = static_cast<int>(k->view - fit_of(light, d, cascades_of(d)).views.data());
  c.column = static_cast<long>(std::floor((k->q.x() + 1.0) / k->texel_ndc));
  c.row = static_cast<long>(std::floor((k->q.y() + 1.0) / k->texel_ndc));
  c.n = s->n;
  c.offset = s->n.dot(s->p);
  c.p = s->p;
  c.texel = k->texel * std::max(1.0, k->texel_aspect);
  return c;
}

CauseModel::StoredAlong CauseModel::stored_along(std::size_t light, const Vec3<double>& through) const {
  StoredAlong out;
  const Vec4<double>& L = scene_.lights[light];
  const Vec3<double> dir = -L.head<3>().normalized();  // the way the light travels (w = 0)
  const double eps = embree_->epsilon(), span = 4 * embree_->extent() + (through - 0.5 * (scene_.bounds[0] + scene_.bounds[1])).norm();
  const Vec3<double> o = through - span * dir;
  RTCIntersectContext c;
  rtcInitIntersectContext(&c);
  // The next face along the ray beyond t (geomID invalid: none before the ray's end).
  const auto next_after = [&](double t) {
    RTCRayHit r;
    start_ray(o, dir, static_cast<float>(2 * span), r);
    r.ray.tnear = static_cast<float>(t);
    rtcIntersect1(embree_->handle(), &c, &r);
    return r;
  };
  const auto add = [&](const RTCRayHit& r) { out.surfaces.push_back({o + static_cast<double>(r.ray.tfar) * dir, normal_of(r)}); };
  const RTCRayHit r = next_after(0);
  if (r.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    out.nothing = true;
    return out;
  }
  add(r);
  // On to the first face the ray leaves through, or the first open mesh; behind an open mesh's
  // face toward the light (culled), the next face left through. Any other end: nothing drawn.
  const auto open = [&](unsigned geom) { return !scene_.casters[geom].closed; };
  const WalkStop exit = walk_to_exit(r, dir, eps, next_after, open);
  if (exit.end == WalkEnd::Face) {
    add(exit.hit);
    if (exit.leaves) return out;
    const WalkStop behind = walk_out_behind(static_cast<double>(exit.hit.ray.tfar), dir, eps, next_after);
    if (behind.end == WalkEnd::Face) {
      add(behind.hit);
      return out;
    }
  }
  out.nothing = true;
  return out;
}

double CauseModel::Lookup::depth(const Vec3<double>& w) const {
  return axis_sign * (view->view * Vec4<double>(w.x(), w.y(), w.z(), 1.0)).z();
}

double CauseModel::Lookup::texel_at(double at) const {
  return perspective && depth_p > 0 ? texel * std::max(at, 0.0) / depth_p : texel;
}

// What the ray of one texel met: the first surface and, traced only when a probe asks, the face
// where the ray leaves that first caster.
// (Trivially constructible, no initializers: explain() keeps an array of them per pixel, and
// Probes::trace sets every field a probe reads.)
struct TexelRay {
  Vec3<double> a, dir;  // from the near plane, unit
  double length;        // to the far plane
  RTCRayHit first;
  bool hit;
  int exit;             // -1 not traced yet; 0 none (nothing behind, or beyond 8 faces); 1 at (t_exit, ng_exit)
  double t_exit;
  Vec3<double> ng_exit;
  // Where the exit is an open mesh's face toward the light: what a pass that culls it too stores
  // instead. -1 not traced yet; 0 none (or beyond 8 faces); 1 at (t_behind, ng_behind); 2 nothing (lit).
  int behind;
  double t_behind;
  Vec3<double> ng_behind;
};

class CauseModel::Probes {
 public:
  // Forgets every ray: a new pixel (generation-stamped slots, nothing to clear).
  void reset() {
    if (++generation_ == 0) {  // wrapped around: clear the stamps once
      for (Slot& slot : slots_) slot.generation = 0;
      generation_ = 1;
    }
    open_meshes_clear_ = -1;
  }
  // Whether p's own way to the light meets no open mesh facing it: -1 not traced yet, 0, 1.
  int& open_meshes_clear() { return open_meshes_clear_; }
  // The ray of the texel at map offset (dx, dy) from p's, traced on first use. Offsets on a grid of
  // 1/8 texel (the rings' quarter steps, the filter's half-texel placements) are remembered, in an
  // open-addressed table far larger than one pixel's probes (at most 65 on the rings, 845 taps of a
  // wide filter).
  TexelRay& at(const Lookup& k, RTCScene scene, double dx, double dy) {
    const double ex = dx * 8, ey = dy * 8;
    const bool on_grid = std::abs(ex - std::round(ex)) < 1e-9 && std::abs(ey - std::round(ey)) < 1e-9;
    if (!on_grid) return trace(k, scene, dx, dy, scratch_);
    const std::uint64_t key = (static_cast<std::uint64_t>(std::lround(ex)) << 32) ^ (static_cast<std::uint64_t>(std::lround(ey)) & 0xffffffffu);
    std::size_t h = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> (64 - kSlotBits));
    for (std::size_t tries = 0; tries < kSlots; ++tries, h = (h + 1) & (kSlots - 1)) {
      Slot& slot = slots_[h];
      if (slot.generation != generation_) {
        slot.generation = generation_;
        slot.key = key;
        return trace(k, scene, dx, dy, slot.ray);
      }
      if (slot.key == key) return slot.ray;
    }
    return trace(k, scene, dx, dy, scratch_);  // never: the table holds 4 times the most probes a pixel asks
  }

 private:
  static TexelRay& trace(const Lookup& k, RTCScene scene, double dx, double dy, TexelRay& ray) {
    const double mx = k.q.x() + dx * k.texel_ndc, my = k.q.y() + dy * k.texel_ndc;
    ray.a = unproject(k.inv, mx, my, k.zn);
    Vec3<double> b = unproject(k.inv, mx, my, k.zf);
    if (k.whole_ray) {
      // Back to the light (the point of the texel's ray nearest it: the ray passes through the light
      // when the declared view's eye is there) or `reach` back for a directional light, and on to
      // `reach` beyond the declared far plane.
      const Vec3<double> dir = (b - ray.a).normalized();
      const double back = k.perspective ? (ray.a - k.light_at).dot(dir) : k.reach;
      ray.a -= back * dir;
      b = ray.a + ((b - ray.a).norm() + k.reach) * dir;
    }
    ray.dir = (b - ray.a).normalized();
    ray.length = (b - ray.a).norm();
    ray.first = first_hit(scene, ray.a, ray.dir, static_cast<float>(ray.length));
    ray.hit = ray.first.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    ray.exit = -1;
    return ray;
  }
  struct Slot {
    std::uint64_t key;
    std::uint32_t generation = 0;
    TexelRay ray;
  };
  static constexpr int kSlotBits = 12;
  static constexpr std::size_t kSlots = std::size_t{1} << kSlotBits;
  std::vector<Slot> slots_ = std::vector<Slot>(kSlots);
  std::uint32_t generation_ = 0;
  int open_meshes_clear_ = -1;
  TexelRay scratch_;
};

CauseModel::CauseModel(const scene::PreparedScene& scene)
    : scene_(scene), embree_(std::make_unique<EmbreeScene>(*scene.scene)),
      camera_(std::make_unique<CameraRays>(scene)), probes_(std::make_unique<Probes>()) {}

CauseModel::~CauseModel() = default;

// What a texel at map offset (dx, dy) from p's may hold: the depth of the first surface along its
// ray, or, where the map is drawn with front faces culled (as ours is, and many engines'), the depth
// of the first surface drawn behind the culled front faces: the first back face along the ray, or
// the first open mesh (drawn two-sided, whichever side faces the light), whichever comes first. A box
// standing on a ground plane shows why the open mesh counts: a ray entering the box's near face
// reaches the ground and the box's bottom face at one depth, and either one is stored (with the
// grazing slope's offset that lights a receiver a few texels beyond the box's far base). A pass may
// also cull the front faces of open meshes as it does closed ones' (OpenSceneGraph's ShadowMap culls
// every front face): then the texel holds the first back face behind them, or nothing. That map is
// a correct one for p wherever no open mesh faces the light between p and the light: leaving the
// ground out changes only p's neighbours' taps (a wide filter then reads a receiver in front of a
// box as lit), never p's own visibility. Where an open mesh does lie in p's way the texels keep it:
// a single-sided card that casts nothing is still wrong. A miss holds "nothing": infinitely far.
// Each stored depth carries the bias `bias` gives its own polygon (normal, ray direction, light
// depth). The texel gives the candidate's answer when p, compared with any stored depth, gets it:
// lit when p is not beyond it, shadowed when p is.
template <class Bias>
bool CauseModel::texel_gives(const Lookup& k, Probes& probes, double dx, double dy, bool candidate_lit,
                             const Bias& bias) const {
  const double eps = embree_->epsilon();
  TexelRay& ray = probes.at(k, embree_->handle(), dx, dy);
  if (!ray.hit) return candidate_lit;
  const auto stored = [&](double t_hit, const Vec3<double>& ng) {
    const double at = k.depth(ray.a + t_hit * ray.dir);
    return at + bias(ng, ray.dir, at);
  };
  const auto answer = [&](double depth) { return (k.depth_p <= depth + eps) == candidate_lit; };
  const RTCRayHit& first = ray.first;
  if (answer(stored(static_cast<double>(first.ray.tfar), normal_of(first)))) return true;
  RTCIntersectContext c;
  rtcInitIntersectContext(&c);
  // The next face along the ray beyond t (geomID invalid: none before the ray's end).
  const auto next_after = [&](double t) {
    RTCRayHit next{};
    next.ray = first.ray;
    next.ray.tnear = static_cast<float>(t);
    next.ray.tfar = static_cast<float>(ray.length);
    next.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_->handle(), &c, &next);
    return next;
  };
  if (ray.exit < 0) {
    // On to the first face the ray leaves through (normal along the ray) or the first open mesh.
    const WalkStop exit = walk_to_exit(first, ray.dir, eps, next_after, [&](unsigned geom) { return !scene_.casters[geom].closed; });
    ray.exit = exit.end == WalkEnd::Face ? 1 : 0;  // nothing drawn behind the culled front faces, or a walk too long
    ray.behind = 0;
    if (exit.end == WalkEnd::Face) {
      ray.t_exit = static_cast<double>(exit.hit.ray.tfar);
      ray.ng_exit = normal_of(exit.hit);
      ray.behind = exit.leaves ? 0 : -1;  // an open mesh's front face: what lies behind it, traced on demand
    }
  }
  if (ray.exit == 1 && answer(stored(ray.t_exit, ray.ng_exit))) return true;
  if (ray.behind == 0 || !open_meshes_clear(k, probes)) return false;
  if (ray.behind < 0) {
    // Behind the open mesh's culled face: on to the first face the ray leaves through, or nothing.
    const WalkStop behind = walk_out_behind(ray.t_exit, ray.dir, eps, next_after);
    ray.behind = behind.end == WalkEnd::Face ? 1 : behind.end == WalkEnd::Nothing ? 2 : 0;
    if (behind.end == WalkEnd::Face) {
      ray.t_behind = static_cast<double>(behind.hit.ray.tfar);
      ray.ng_behind = normal_of(behind.hit);
    }
  }
  return ray.behind == 2 ? candidate_lit : ray.behind == 1 && answer(stored(ray.t_behind, ray.ng_behind));
}

bool CauseModel::open_meshes_clear(const Lookup& k, Probes& probes) const {
  int& clear = probes.open_meshes_clear();
  if (clear < 0) {
    // From p toward the light, every face met: an open mesh's face toward the light blocks it.
    const double eps = embree_->epsilon();
    RTCIntersectContext c;
    rtcInitIntersectContext(&c);
    clear = 0;
    double t = 0;
    const Vec3<double> o = k.p + 4 * eps * k.n;
    for (int step = 0; step < kWalkFaces; ++step) {
      RTCRayHit r;
      start_ray(o, k.to_light, static_cast<float>(std::min(k.light_distance, 1e30)), r);
      r.ray.tnear = static_cast<float>(t);
      rtcIntersect1(embree_->handle(), &c, &r);
      if (r.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        clear = 1;
        break;
      }
      if (!scene_.casters[r.hit.geomID].closed && normal_of(r).dot(k.to_light) > 0) break;
      t = static_cast<double>(r.ray.tfar) + eps;
    }
  }
  return clear == 1;
}

double CauseModel::mask_reach_texels(const outputs::CandidateDeclaration& d) {
  // A nearest lookup on the pack's grid reads a texel whose centre is within half a texel per axis;
  // on a grid of unknown phase (the candidate's own fit) the centre may be a whole texel away. A
  // filtered mask (lit at >= 1/2 of the taps) puts a straight boundary where the nearest lookup does,
  // give or take its tap spacing: the filter widens the mask's reach by at most kMaxMaskFilterTexels,
  // whatever radius is declared (its wider reach is judged in the lit fraction, visibility_band).
  return grid_uncertainty_texels(d) + std::min(d.filter_radius_texels, kMaxMaskFilterTexels);
}

bool CauseModel::filter_may_answer(const Lookup& k, Probes& probes, const outputs::CandidateDeclaration& d, bool candidate_lit,
                                   const std::function<BiasOf(double, double)>& bias_at) const {
  if (!(d.filter_radius_texels > kMaxMaskFilterTexels)) return false;
  // The box's taps at whole-texel offsets out to the radius (at most kMaxFilterTapsPerAxis per axis:
  // wider boxes are sampled at a coarser stride), placed at p's texel and at the 4 diagonal shifts
  // of the lookup's grid uncertainty (1/2 texel on the pack's grid, 1 on the candidate's own).
  const int radius = static_cast<int>(std::ceil(d.filter_radius_texels));
  const int stride = std::max(1, (2 * radius + 1 + kMaxFilterTapsPerAxis - 1) / kMaxFilterTapsPerAxis);
  const double h = grid_uncertainty_texels(d);
  static constexpr std::array<std::array<double, 2>, 5> kPlacements{{{0, 0}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}}};
  const int per_axis = 2 * radius / stride + 1;
  const int taps = per_axis * per_axis;
  for (const auto& place : kPlacements) {
    // The placement's verdict is settled as soon as half its taps give the answer, or so many do
    // not that the rest cannot make half: the same answer as counting them all.
    int giving = 0, asked = 0;
    for (int ty = -radius; ty <= radius && 2 * giving < taps && 2 * (giving + taps - asked) >= taps; ty += stride)
      for (int tx = -radius; tx <= radius && 2 * giving < taps && 2 * (giving + taps - asked) >= taps; tx += stride) {
        const double dx = tx + place[0] * h, dy = ty + place[1] * h;
        ++asked;
        giving += texel_gives(k, probes, dx, dy, candidate_lit, bias_at(dx, dy));
      }
    if (2 * giving >= taps) return true;
  }
  return false;
}

Cause CauseModel::explain(std::size_t light, int x, int y, const outputs::CandidateDeclaration& d, bool candidate_lit) {
  const std::optional<Surface> surface = surface_at(x, y);
  if (!surface) return Cause::Unexplained;
  const std::optional<Lookup> found = lookup(light, *surface, d);
  // Rule 1 of the visibility rule (shadow_ray.hpp): a surface facing away from the light is in its
  // own shadow whatever a map holds; no footprint or bias lights it.
  if (!found || !(surface->n.dot(found->to_light) > 0)) return Cause::Unexplained;
  const Cause own = explain_in(*found, d, candidate_lit);
  // A blended cascade's pixel shows a mix of two cascades' answers: where both agree, the mix
  // thresholded gives that answer; where they differ, either. So either cascade may explain it.
  const int next = own == Cause::Unexplained ? blended_view(light, surface->p, d) : -1;
  if (next < 0) return own;
  const std::optional<Lookup> blended = lookup(light, *surface, d, next);
  return blended ? explain_in(*blended, d, candidate_lit) : own;
}

int CauseModel::blended_view(std::size_t light, const Vec3<double>& p, const outputs::CandidateDeclaration& d) const {
  if (!(d.cascade_blend > 0)) return -1;
  const LightFit& fit = fit_of(light, d, cascades_of(d));
  const std::vector<double>& s = fit.cascade_splits;
  if (fit.cube || s.size() < 3) return -1;
  const double depth = fit.cascade_depth_from_scene.dot(Vec4<double>(p.x(), p.y(), p.z(), 1.0));
  const int i = cascade_of(s, depth);
  if (i < 0 || i + 2 >= static_cast<int>(s.size())) return -1;  // outside, or the last cascade: no next one
  const auto u = static_cast<std::size_t>(i);
  return depth >= s[u + 1] - d.cascade_blend * (s[u + 1] - s[u]) ? i + 1 : -1;
}

Cause CauseModel::explain_in(const Lookup& k, const outputs::CandidateDeclaration& d, bool candidate_lit) {
  Probes& probes = *probes_;
  probes.reset();
  const double reach = mask_reach_texels(d);
  const double precision = std::abs(k.depth_p) * kDepthPrecision;
  // The slope term of a stored polygon (normal ng, met along `along` at light depth `at`): one
  // texel's depth change across it, glPolygonOffset's model.
  const auto slope = [&](const Vec3<double>& ng, const Vec3<double>& along, double at) {
    return k.texel_at(at) * capped_tan(std::abs(ng.normalized().dot(along)));
  };
  const auto none = [](const Vec3<double>&, const Vec3<double>&, double) { return 0.0; };
  // The probes: rings every kProbeStep texels out to the reach, so that a smaller reach probes a
  // subset of a larger one's texels (declaring less never explains more).
  std::vector<double> rings;
  for (double r = kProbeStep; r <= reach + 1e-9; r += kProbeStep) rings.push_back(r);
  if (candidate_lit) {
    // False light: the bias explains a leak only up to what a correct map needs there (the slope
    // bias that removes acne across the mask's reach, with kCorrectBiasMargin, and the depth
    // format's precision), and only what the candidate declares: min(declared, needed).
    const double normal_offset = (d.normal_offset + d.normal_offset_texels * k.texel) * std::sqrt(1.0 + k.tan_p * k.tan_p);
    const auto bias = [&](const Vec3<double>& ng, const Vec3<double>& along, double at) {
      const double s = slope(ng, along, at);
      const double declared = d.constant_bias + d.slope_bias_texels * s + normal_offset + k.depth_bias_world;
      const double needed = kCorrectBiasMargin * 2.0 * reach * s + precision;
      return std::min(declared, needed);
    };
    // Depth bias: the texel of p itself (a contact within the bias comes out lit: peter-panning).
    if (texel_gives(k, probes, 0, 0, true, bias) && !texel_gives(k, probes, 0, 0, true, none)) return Cause::DepthBias;
    for (const double r : rings)
      for (const auto& dv : kProbeDirections)
        if (texel_gives(k, probes, dv[0] * r, dv[1] * r, true, bias)) return Cause::TexelFootprint;
    if (filter_may_answer(k, probes, d, true, [&](double, double) { return BiasOf(bias); })) return Cause::TexelFootprint;
    return Cause::Unexplained;
  }
  // False shadow: a texel within the reach holds an occluder nearer than p by more than the bias a
  // correct map needs at that texel's distance from p (its depth change across that distance, and
  // the precision): the receiver's own surface never qualifies, whatever bias is declared. A false
  // shadow that only the receiver's own surface, stored with less bias than that, casts is acne.
  for (const double r : rings)
    for (const auto& dv : kProbeDirections) {
      const double distance = r * std::hypot(dv[0], dv[1] * k.texel_aspect);
      const auto needed = [&](const Vec3<double>& ng, const Vec3<double>& along, double at) {
        return distance * slope(ng, along, at) + precision;
      };
      if (texel_gives(k, probes, dv[0] * r, dv[1] * r, false, needed)) return Cause::TexelFootprint;
    }
  const auto needed_at = [&](double dx, double dy) -> BiasOf {
    const double distance = std::hypot(dx, dy * k.texel_aspect);
    return [&slope, distance, precision](const Vec3<double>& ng, const Vec3<double>& along, double at) {
      return distance * slope(ng, along, at) + precision;
    };
  };
  if (filter_may_answer(k, probes, d, false, needed_at)) return Cause::TexelFootprint;
  for (const double r : rings)
    for (const auto& dv : kProbeDirections)
      if (texel_gives(k, probes, dv[0] * r, dv[1] * r, false, none)) return Cause::Acne;
  return Cause::Unexplained;
}

}  // namespace shadowref::reference

namespace shadowref::reference {

std::vector<double> CauseModel::fractions_around(std::size_t light, int x, int y, const outputs::CandidateDeclaration& d,
                                                 const std::vector<std::array<double, 2>>& offsets) const {
  std::vector<double> out;
  const std::optional<Surface> surface = surface_at(x, y);
  if (!surface) return out;
  const Vec3<double>& p = surface->p;
  const Vec3<double>& n = surface->n;
  const scene::Light& source = scene_.scene->lights[light];
  out.push_back(lit_fraction(*embree_, p, n, source));
  // The texels around p's in the map of the light's centre (the one view, or the cube face p is in).
  const double zn = near_ndc_z(*scene_.convention), zf = far_ndc_z(*scene_.convention);
  const Vec4<double>& L = scene_.lights[light];
  const LightFit& fit = fit_of(light, d, 0);
  const LightView& view = fit.views[static_cast<std::size_t>(light_view_of(fit, L, p))];
  const Mat4<double> m = view.projection * view.view;
  const Vec4<double> h = m * Vec4<double>(p.x(), p.y(), p.z(), 1.0);
  if (!(h.w() > 0)) return out;
  const Vec3<double> q = h.head<3>() / h.w();
  const Mat4<double> inv = m.inverse();
  const double texel_ndc = 2.0 / fit.size;
  for (const auto& o : offsets) {
    const double mx = q.x() + o[0] * texel_ndc, my = q.y() + o[1] * texel_ndc;
    const Vec3<double> a = unproject(inv, mx, my, zn), b = unproject(inv, mx, my, zf);
    // Where that texel's ray crosses p's tangent plane (the receiver a filter compares against).
    const double denom = n.dot(b - a);
    if (std::abs(denom) < 1e-12) continue;
    const double t = n.dot(p - a) / denom;
    out.push_back(lit_fraction(*embree_, a + t * (b - a), n, source));
  }
  return out;
}

CauseModel::Band CauseModel::visibility_band(std::size_t light, int x, int y,
                                             const outputs::CandidateDeclaration& d) const {
  const double radius = grid_uncertainty_texels(d) + d.filter_radius_texels;
  std::vector<std::array<double, 2>> offsets;
  for (const double r : {0.5 * radius, radius})
    for (const auto& dv : kProbeDirections) offsets.push_back({dv[0] * r, dv[1] * r});
  Band band;
  for (const double v : fractions_around(light, x, y, d, offsets)) {
    band.lo = std::min(band.lo, v);
    band.hi = std::max(band.hi, v);
  }
  return band;
}

double CauseModel::visibility_texel_shift(std::size_t light, int x, int y,
                                          const outputs::CandidateDeclaration& d) const {
  // A circle of radius h (the Euclidean norm: the diagonals at h / sqrt(2) per axis), where explain()
  // and visibility_band() reach a square (kProbeDirections' max norm). Why two norms: explain() asks
  // which texels a lookup may read, and those lie in a square cell around p's; this asks how far a
  // correct map may move a straight penumbra, h across its edge in any direction. Not unified: each
  // feeds verdicts (the masks' causes; the soft techniques' texel allowance), which must not change.
  const double h = grid_uncertainty_texels(d);
  const double k = h * 0.5 * std::sqrt(2.0);
  std::vector<std::array<double, 2>> offsets;
  for (const auto& dv : kProbeDirections) {
    const double r = dv[0] != 0 && dv[1] != 0 ? k : h;
    offsets.push_back({dv[0] * r, dv[1] * r});
  }
  const std::vector<double> f = fractions_around(light, x, y, d, offsets);
  double shift = 0;
  for (std::size_t i = 1; i < f.size(); ++i) shift = std::max(shift, std::abs(f[i] - f[0]));
  return shift;
}

}  // namespace shadowref::reference
