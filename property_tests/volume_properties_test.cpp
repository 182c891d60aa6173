// volume_properties_test.cpp — the laws of stencil shadow volumes (mathlib's silhouette.hpp,
// volume.hpp, stencil_count.hpp, volume_strategy.hpp), in float and double, on closed, open and
// non-manifold casters, and their teeth.
//
//   * on a closed 2-manifold the silhouette edges form closed loops: every vertex has even degree
//     (and as many silhouette edges leave it as arrive);
//   * the volume (sides and both caps) is a closed oriented surface: every directed edge of its
//     triangles is matched by the reverse edge — for every caster, open and non-manifold included;
//   * z-pass count = z-fail count wherever the eye is outside every volume;
//   * the stencil method chosen per caster (z-pass or z-fail) counts the true containment number
//     at every point of the frustum, counting from the near plane as a GPU does;
//   * in_shadow(p) equals "the segment from p to the light hits the mesh", checked with Embree's
//     rtcOccluded1 on a robust scene (for open and non-manifold casters: hits a LIT face, the law of
//     the lit-face model: a one-sided sheet casts no shadow from its back);
//   * with the eye at the light, the z-pass count is 0 everywhere (no shadow is seen from the light).
// The functions under test are gathered in VolumeFunctions so that the wrong variants (the tie rule
// reversed in the silhouette test, z-pass used with the eye inside a volume) run the same code.
#include <embree3/rtcore.h>

#include <map>

#include "mesh_generators.hpp"
#include "property_support.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/silhouette.hpp"
#include "shadowref/stencil_count.hpp"
#include "shadowref/view.hpp"
#include "shadowref/volume.hpp"
#include "shadowref/volume_strategy.hpp"

namespace shadowref::prop {
namespace {

template <class T>
struct VolumeFunctions {
  std::function<Result<std::size_t>(const ShadowCaster<T>&, const Vec4<T>&, Silhouette<T>&)> silhouette;
  std::function<Result<StencilMethod>(const std::array<Vec3<T>, 4>&, const Vec4<T>&, const BoundingSphere<T>&)>
      choose_method;
};

template <class T>
VolumeFunctions<T> shadowref_volume_functions() {
  return {[](const ShadowCaster<T>& c, const Vec4<T>& l, Silhouette<T>& s) { return find_silhouette(c, l, s); },
          [](const std::array<Vec3<T>, 4>& n, const Vec4<T>& l, const BoundingSphere<T>& b) {
            return choose_stencil_method(n, l, b);
          }};
}

// WRONG: the silhouette test with the tie rule reversed (an edge is a silhouette by plane · L > 0)
// while the caps keep the faces lit by plane · L >= 0 — what a geometry shader with `>` next to
// CPU-built caps does.
template <class T>
VolumeFunctions<T> tie_rule_reversed() {
  auto f = shadowref_volume_functions<T>();
  f.silhouette = [](const ShadowCaster<T>& c, const Vec4<T>& l, Silhouette<T>& out) -> Result<std::size_t> {
    const auto r = find_silhouette(c, l, out);  // facing (lit) with the right rule, for the caps
    if (!r) return r;
    std::vector<std::uint8_t> lit(c.face_planes.size());
    for (std::size_t t = 0; t < lit.size(); ++t) lit[t] = out.lit[t] && c.face_planes[t].dot(l) > T(0);
    out.edges.clear();
    const auto& adj = c.adjacency;
    for (std::size_t e = 0; e < adj.edge_count(); ++e) {
      int m = 0;
      for (std::uint32_t k = adj.edge_offsets[e]; k < adj.edge_offsets[e + 1]; ++k)
        if (lit[EdgeUse::triangle(adj.edge_uses[k])]) m += EdgeUse::reversed(adj.edge_uses[k]) ? -1 : 1;
      if (m == 0) continue;
      for (std::uint32_t k = adj.edge_offsets[e]; k < adj.edge_offsets[e + 1]; ++k) {
        const std::uint32_t u = adj.edge_uses[k];
        if (!lit[EdgeUse::triangle(u)] || EdgeUse::reversed(u) != (m < 0)) continue;
        const auto& tri = c.mesh.triangles[EdgeUse::triangle(u)];
        for (int n = std::abs(m); n > 0; --n) out.edges.push_back({tri[(EdgeUse::slot(u) + 1) % 3], tri[EdgeUse::slot(u)]});
        break;
      }
    }
    return out.edges.size();
  };
  return f;
}

// WRONG: z-pass whatever the near plane sees (the eye may be inside a volume).
template <class T>
VolumeFunctions<T> always_zpass() {
  auto f = shadowref_volume_functions<T>();
  f.choose_method = [](const std::array<Vec3<T>, 4>&, const Vec4<T>&, const BoundingSphere<T>&) -> Result<StencilMethod> {
    return StencilMethod::ZPass;
  };
  return f;
}

// The caster, silhouette and volumes of one case (nullopt when the light sits on a caster vertex).
template <class T>
struct Built {
  ShadowCaster<T> caster;
  Silhouette<T> sil;
  ShadowVolume<T> capped, sides;
};

template <class T>
std::optional<Built<T>> build(const VolumeFunctions<T>& f, const gen::MeshCase& mc, const std::type_identity_t<Vec4<T>>& light) {
  auto caster = make_shadow_caster(mc.as<T>());
  RC_ASSERT(caster.ok());
  Built<T> b{std::move(caster).value(), {}, {}, {}};
  RC_ASSERT(f.silhouette(b.caster, light, b.sil).ok());
  if (!build_shadow_volume(b.caster, b.sil, VolumeOptions<T>{}, b.capped)) return std::nullopt;
  VolumeOptions<T> sides_only;
  sides_only.light_cap = sides_only.dark_cap = false;
  if (!build_shadow_volume(b.caster, b.sil, sides_only, b.sides)) return std::nullopt;
  return b;
}

template <class T>
bool light_outside_bounds(const gen::MeshCase& mc, const Vec4<double>& l) {
  if (l.w() == 0) return true;
  const auto s = bounding_sphere(mc.mesh).value();
  return (l.head<3>() - s.center).norm() > s.radius * 1.01;
}

// Points (rounded to float) in [−half, half]³, moved off the integer grid and the axes by a fixed
// irrational-looking offset: shrinking goes toward 0, and a point at 0 would sit exactly on the
// edges and planes of boxes and axis lights, where the stencil count's documented tie rule (an edge
// crossing counts for both triangles) makes the counts meaningless.
const Vec3<double> kOffGrid(0.0137113, 0.0291437, 0.0173271);

rc::Gen<Vec3<double>> float_point(double half) {
  return rc::gen::map(gen::vec3(half), [half](const Vec3<double>& p) {
    return Vec3<double>((p + kOffGrid * half).cast<float>().cast<double>());
  });
}

// ---- Embree, the oracle of "the segment from p to the light hits the mesh" ----------------------

RTCDevice embree_device() {
  static RTCDevice device = rtcNewDevice(nullptr);
  return device;
}

class EmbreeMesh {
 public:
  EmbreeMesh(const TriangleMesh<double>& mesh, const std::vector<std::uint8_t>* only) : scene_(rtcNewScene(embree_device())) {
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);  // no misses through shared edges (docs/dependencies.md)
    RTCGeometry g = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          mesh.positions.size()));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      for (int k = 0; k < 3; ++k) v[3 * i + static_cast<std::size_t>(k)] = static_cast<float>(mesh.positions[i][k]);
    std::vector<std::array<std::uint32_t, 3>> tris;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      if (!only || (*only)[t]) tris.push_back(mesh.triangles[t]);
    auto* ix = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), std::max<std::size_t>(tris.size(), 1)));
    for (std::size_t t = 0; t < tris.size(); ++t)
      for (int k = 0; k < 3; ++k) ix[3 * t + static_cast<std::size_t>(k)] = tris[t][static_cast<std::size_t>(k)];
    if (tris.empty()) ix[0] = ix[1] = ix[2] = 0;  // a degenerate triangle: hits nothing
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene_);
  }
  ~EmbreeMesh() { rtcReleaseScene(scene_); }
  EmbreeMesh(const EmbreeMesh&) = delete;
  EmbreeMesh& operator=(const EmbreeMesh&) = delete;

  // Whether the segment from p to the light (to infinity for w = 0) hits a triangle.
  bool occluded(const Vec3<double>& p, const Vec4<double>& l) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay ray{};
    ray.org_x = static_cast<float>(p.x()), ray.org_y = static_cast<float>(p.y()), ray.org_z = static_cast<float>(p.z());
    const Vec3<double> d = l.w() == 0 ? Vec3<double>(l.head<3>()) : Vec3<double>(l.head<3>() / l.w() - p);
    ray.dir_x = static_cast<float>(d.x()), ray.dir_y = static_cast<float>(d.y()), ray.dir_z = static_cast<float>(d.z());
    ray.tnear = 0;
    ray.tfar = l.w() == 0 ? std::numeric_limits<float>::infinity() : 1.0f;
    ray.mask = 0xFFFFFFFFu;
    rtcOccluded1(scene_, &ctx, &ray);
    return ray.tfar < 0;  // −inf on a hit
  }

 private:
  RTCScene scene_;
};


// The answer of `occluded` at p when it is the same for p jittered by `jitter` in six directions;
// nullopt when p lies within the jitter of a boundary, where either answer is honest.
const Vec3<double> kJitter[6] = {{1, 0.3, 0.1}, {-0.2, 1, 0.4}, {0.3, -0.1, 1}, {-1, -0.3, 0.2}, {0.1, -1, -0.4}, {-0.3, 0.2, -1}};

std::optional<bool> decided_occlusion(const EmbreeMesh& m, const Vec3<double>& p, const Vec4<double>& l, double jitter) {
  const bool hit = m.occluded(p, l);
  for (const auto& j : kJitter)
    if (m.occluded(p + j * jitter, l) != hit) return std::nullopt;
  return hit;
}

// Whether the eye sees p (nothing of the mesh on the segment), when decided.
std::optional<bool> visible(const EmbreeMesh& m, const Vec3<double>& eye, const Vec3<double>& p, double jitter) {
  const auto o = decided_occlusion(m, p, Vec4<double>(eye.x(), eye.y(), eye.z(), 1), jitter);
  return o ? std::optional<bool>(!*o) : std::nullopt;
}

double jitter_of(const gen::MeshCase& mc) {
  // Far above float rounding (1e-7 of the scene) and far below its features.
  const auto s = bounding_sphere(mc.mesh).value();
  return 1e-4 * (s.radius + s.center.norm() + 1);
}

// ---- the properties -------------------------------------------------------------------------------

template <class T>
void silhouette_forms_closed_loops(const VolumeFunctions<T>& f) {
  const auto mc = *gen::closed_mesh();
  const auto light = *gen::caster_light();
  auto caster = make_shadow_caster(mc.as<T>());
  RC_ASSERT(caster.ok());
  RC_ASSERT(caster->adjacency.report.closed_manifold());
  Silhouette<T> sil;
  RC_ASSERT(f.silhouette(*caster, light.L.cast<T>(), sil).ok());
  std::map<std::uint32_t, int> degree, balance;
  for (const auto& e : sil.edges) {
    const std::uint32_t a = caster->adjacency.weld[e.from], b = caster->adjacency.weld[e.to];
    ++degree[a], ++degree[b], ++balance[a], --balance[b];
  }
  for (const auto& [v, d] : degree) {
    RC_LOG() << "vertex " << v << " degree " << d << " out - in " << balance[v] << "\n";
    RC_ASSERT(d % 2 == 0);
    RC_ASSERT(balance[v] == 0);
  }
}

template <class T>
void volume_is_a_closed_surface(const VolumeFunctions<T>& f) {
  const auto mc = *gen::any_mesh();
  const auto light = *gen::caster_light();
  const auto b = build(f, mc, light.L.cast<T>());
  RC_PRE(b.has_value());
  // Directed edges on welded vertices (volume.hpp's layout: vertex 2j is mesh vertex source[j],
  // 2j + 1 its extrusion, numbered n + weld here; a directional light's single apex, vertex K after
  // the K mesh vertices, is its own vertex n).
  const auto n = static_cast<std::uint32_t>(b->caster.mesh.positions.size());
  const auto& source = b->capped.source;
  const bool apex = b->capped.vertices.size() == source.size() + 1;
  const auto& welded = b->caster.adjacency.weld;
  const auto weld = [&](std::uint32_t i) {
    if (apex) return i < source.size() ? welded[source[i]] : n;
    return (i & 1u) ? n + welded[source[i >> 1]] : welded[source[i >> 1]];
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  const auto& idx = b->capped.indices;
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = weld(idx[t + static_cast<std::size_t>(k)]), c = weld(idx[t + static_cast<std::size_t>((k + 1) % 3)]);
      if (a < c) ++count[{a, c}];
      else if (a > c) --count[{c, a}];
    }
  for (const auto& [e, m] : count) {
    RC_LOG() << "edge " << e.first << "-" << e.second << " net " << m << "\n";
    RC_ASSERT(m == 0);
  }
}

template <class T>
void zpass_equals_zfail_with_the_eye_outside(const VolumeFunctions<T>& f) {
  const auto mc = *rc::gen::weightedOneOf<gen::MeshCase>({{2, gen::closed_mesh()}, {1, gen::open_mesh()}});
  const auto light = *gen::caster_light();
  RC_PRE(light_outside_bounds<T>(mc, light.L));
  const auto b = build(f, mc, light.L.cast<T>());
  RC_PRE(b.has_value());
  const Vec3<T> eye = (*float_point(10)).cast<T>();
  RC_PRE(containment_count(b->capped, eye) == 0);
  const EmbreeMesh embree(mc.mesh, nullptr);
  for (int i = 0; i < 8; ++i) {
    const Vec3<double> pd = *float_point(8);
    // z-pass draws the sides only: it is right for the points the eye SEES (a point behind the
    // caster is hidden by the caster's own depth, and the light cap it would cross is not drawn).
    const auto vis = visible(embree, Vec3<double>(eye.template cast<double>()), pd, jitter_of(mc));
    if (!vis || !*vis) continue;
    const Vec3<T> p = pd.cast<T>();
    const int zp = zpass_count(b->sides, eye, p), zf = zfail_count(b->capped, eye, p);
    RC_LOG() << "p " << str(p) << " z-pass " << zp << " z-fail " << zf << "\n";
    RC_ASSERT(zp == zf);
  }
}

template <class T>
void chosen_method_counts_the_containment(const VolumeFunctions<T>& f) {
  const auto mc = *gen::closed_mesh();
  const auto light = *gen::caster_light();
  RC_PRE(light_outside_bounds<T>(mc, light.L));
  const auto b = build(f, mc, light.L.cast<T>());
  RC_PRE(b.has_value());
  const auto sphere = bounding_sphere(mc.mesh).value();
  // Half of the eyes behind the caster as seen from the light: inside its volume.
  const Vec3<double> away = light.L.w() == 0 ? Vec3<double>(-light.L.head<3>())
                                             : Vec3<double>((sphere.center - light.L.head<3>()).normalized());
  const bool behind = *rc::gen::arbitrary<bool>();
  const Vec3<double> eye = behind ? Vec3<double>(sphere.center + away * sphere.radius * *gen::uniform(1.2, 4) + *float_point(0.5))
                                  : *float_point(10);
  const Vec3<double> target = sphere.center + *float_point(2);
  const Vec3<double> up = *gen::direction();
  const double near = *gen::uniform(0.05, 1);
  const auto view = look_at<T>(eye.cast<T>(), target.cast<T>(), up.cast<T>());
  RC_PRE(view.ok());
  const auto proj = perspective_infinite<T>(T(1), T(1), static_cast<T>(near));
  const Mat4<T> vp = *proj * *view;
  const auto rect = near_rectangle(vp);
  RC_PRE(rect.ok());
  const auto method = f.choose_method(*rect, light.L.cast<T>(), BoundingSphere<T>{sphere.center.cast<T>(), static_cast<T>(sphere.radius)});
  RC_ASSERT(method.ok());
  RC_LOG() << "eye " << str(eye) << " target " << str(target) << " near " << near << " method " << to_string(*method) << "\n";
  const Mat4<double> inv = view->template cast<double>().inverse();
  const EmbreeMesh embree(mc.mesh, nullptr);
  const double th = std::tan(0.5);
  for (int i = 0; i < 8; ++i) {
    const double x = *gen::centered(0.98) + kOffGrid.x(), y = *gen::centered(0.98) + kOffGrid.y(), t = *gen::uniform(near * 1.5, 20);
    const Vec4<double> pv(x * th * t, y * th * t, -t, 1), qv(x * th * near, y * th * near, -near, 1);
    const Vec3<double> pd = (inv * pv).head<3>();
    const auto vis = visible(embree, eye, pd, jitter_of(mc));  // the GPU counts at visible points
    if (!vis || !*vis) continue;
    const Vec3<T> p = pd.cast<T>(), q = (inv * qv).head<3>().cast<T>();
    const int want = containment_count(b->capped, p);
    const int got = *method == StencilMethod::ZPass ? zpass_count(b->sides, q, p) : zfail_count(b->capped, Vec3<T>(eye.cast<T>()), p);
    RC_LOG() << "p " << str(p) << " count " << got << " containment " << want << "\n";
    RC_ASSERT(got == want);
  }
}

template <class T>
void in_shadow_equals_segment_hits_the_mesh(const VolumeFunctions<T>& f) {
  const auto mc = *gen::any_mesh();
  const auto light = *gen::caster_light();
  RC_PRE(light_outside_bounds<T>(mc, light.L));
  const auto b = build(f, mc, light.L.cast<T>());
  RC_PRE(b.has_value());
  const bool closed = b->caster.adjacency.report.closed_manifold();
  const EmbreeMesh embree(mc.mesh, closed ? nullptr : &b->sil.lit);
  const auto sphere = bounding_sphere(mc.mesh).value();
  int decided = 0;
  for (int i = 0; i < 8; ++i) {
    const Vec3<double> p = *rc::gen::oneOf(float_point(8), rc::gen::map(float_point(1.5), [&](const Vec3<double>& v) {
      return Vec3<double>((sphere.center + v * sphere.radius).cast<float>().cast<double>());
    }));
    const auto occluded = decided_occlusion(embree, p, light.L, jitter_of(mc));
    if (!occluded) continue;  // p is within the jitter of a shadow boundary: either answer is honest
    const bool hit = *occluded;
    ++decided;
    const bool shadowed = in_shadow(b->capped, Vec3<T>(p.cast<T>()));
    RC_LOG() << "p " << str(p) << " embree " << (hit ? "occluded" : "free") << " in_shadow " << shadowed << " ("
             << (closed ? "closed mesh" : "lit faces only") << ")\n";
    RC_ASSERT(shadowed == hit);
  }
  RC_PRE(decided > 0);
}

template <class T>
void zpass_is_zero_from_the_light(const VolumeFunctions<T>& f) {
  const auto mc = *gen::any_mesh();
  const auto light = *gen::caster_light();
  RC_PRE(light.L.w() != 0 && light_outside_bounds<T>(mc, light.L));
  const auto b = build(f, mc, light.L.cast<T>());
  RC_PRE(b.has_value());
  const Vec3<T> eye = light.L.head<3>().cast<T>();
  const EmbreeMesh embree(mc.mesh, nullptr);
  for (int i = 0; i < 8; ++i) {
    const Vec3<double> pd = *float_point(8);
    const auto vis = visible(embree, Vec3<double>(light.L.head<3>()), pd, jitter_of(mc));
    if (!vis || !*vis) continue;  // every VISIBLE point: the hidden ones are not drawn
    const Vec3<T> p = pd.cast<T>();
    const int zp = zpass_count(b->sides, eye, p);
    RC_LOG() << "p " << str(p) << " z-pass " << zp << "\n";
    RC_ASSERT(zp == 0);
  }
}

// ---- registration ---------------------------------------------------------------------------------

template <class T>
class VolumeProperties : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(VolumeProperties, Scalars);

#define SHADOWREF_VOLUME_PROPERTY(name) \
  TYPED_TEST(VolumeProperties, name) { check_property([] { name<TypeParam>(shadowref_volume_functions<TypeParam>()); }); }

SHADOWREF_VOLUME_PROPERTY(silhouette_forms_closed_loops)
SHADOWREF_VOLUME_PROPERTY(volume_is_a_closed_surface)
SHADOWREF_VOLUME_PROPERTY(zpass_equals_zfail_with_the_eye_outside)
SHADOWREF_VOLUME_PROPERTY(chosen_method_counts_the_containment)
SHADOWREF_VOLUME_PROPERTY(in_shadow_equals_segment_hits_the_mesh)
SHADOWREF_VOLUME_PROPERTY(zpass_is_zero_from_the_light)

// The teeth of the volume properties.
constexpr int kTeethCases = 1000;

TYPED_TEST(VolumeProperties, Teeth_TieRuleReversedIsCaughtByVolumeIsAClosedSurface) {
  const auto f = tie_rule_reversed<TypeParam>();
  expect_counterexample([&] { volume_is_a_closed_surface<TypeParam>(f); }, kTeethCases);
}
TYPED_TEST(VolumeProperties, Teeth_ZPassWithTheEyeInsideIsCaughtByChosenMethodCountsTheContainment) {
  const auto f = always_zpass<TypeParam>();
  expect_counterexample([&] { chosen_method_counts_the_containment<TypeParam>(f); }, kTeethCases);
}

}  // namespace
}  // namespace shadowref::prop
