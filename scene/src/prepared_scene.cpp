// prepared_scene.cpp — the per-scene, per-convention work done once (prepared_scene.hpp).
#include "shadowref/scene/prepared_scene.hpp"

#include <algorithm>
#include <numbers>
#include <stdexcept>

#include "shadowref/adjacency.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/volume_strategy.hpp"

namespace shadowref::scene {
namespace {

template <class T>
T value_or_throw(Result<T> r, const char* what) {
  if (!r) throw std::logic_error(std::string(what) + ": " + r.message());
  return std::move(r).value();
}

CameraMatrices camera_matrices(const Scene& s, const RunConvention& c, std::optional<double> far, double epsilon) {
  CameraMatrices m;
  m.view = value_or_throw(view_matrix<double>(s.camera, c), "camera view");
  m.projection = value_or_throw(projection_matrix<double>(s.camera, s.width, s.height, c, epsilon, far), "camera projection");
  m.clip_from_scene = m.projection * m.view;
  return m;
}

}  // namespace

const CameraMatrices& PreparedScene::camera_for(CameraDepth depth) const {
  switch (depth) {
    case CameraDepth::Scene: return camera;
    case CameraDepth::InfiniteEpsilon: return camera_infinite_epsilon;
    case CameraDepth::FiniteForClamp: return camera_finite_for_clamp;
  }
  return camera;
}

CascadeCamera cascade_camera(const Scene& s) {
  CascadeCamera c;
  c.eye = s.camera.position;
  c.forward = (s.camera.target - s.camera.position).normalized();
  c.fovy = s.camera.fovy_deg * std::numbers::pi / 180.0;
  c.aspect = static_cast<double>(s.width) / s.height;
  c.near = s.camera.near;
  if (s.camera.far) c.far = *s.camera.far;
  return c;
}

LightFit cascaded_light_fit(const PreparedScene& p, std::size_t light, int map_size, int count) {
  const Vec4<double>& L = p.lights.at(light);
  if (L.w() != 0.0) {
    if (map_size == 0 || map_size == p.light_fits.at(light).size) return p.light_fits[light];
    std::vector<const TriangleMesh<float>*> meshes;
    for (const Object& o : p.scene->objects) meshes.push_back(&o.mesh);
    LightFitOptions fit_options;
    fit_options.map_size = map_size;
    return value_or_throw(fit_light(*p.convention, L, meshes, fit_options), "light fit");
  }
  CascadeOptions options;
  options.count = count;
  options.map_size = map_size ? map_size : p.options.shadow_map_size ? p.options.shadow_map_size : kDirectionalAutoSize;
  return value_or_throw(fit_cascades(*p.convention, L.head<3>(), p.bounds, cascade_camera(*p.scene), options), "cascade fit");
}

PreparedScene prepare_scene(const Scene& s, const RunConvention& c, const PrepareOptions& options) {
  PreparedScene p;
  p.scene = &s;
  p.convention = &c;
  p.options = options;
  p.bounds = bounds(s);
  p.camera = camera_matrices(s, c, s.camera.far, 0.0);
  // Shadow volumes with an infinite far plane: the dark cap at w = 0 must stay strictly inside.
  p.camera_infinite_epsilon = camera_matrices(s, c, s.camera.far, s.camera.far ? 0.0 : kSafeInfiniteEpsilonFloat);
  // For depth clamp: a finite far plane behind every object (twice the farthest bounding-box
  // corner), so that only the volumes' points at infinity lie beyond it and get clamped.
  double farthest = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3<double> corner((k & 1) ? p.bounds[1].x() : p.bounds[0].x(), (k & 2) ? p.bounds[1].y() : p.bounds[0].y(),
                              (k & 4) ? p.bounds[1].z() : p.bounds[0].z());
    farthest = std::max(farthest, (corner - s.camera.position).norm());
  }
  p.camera_finite_for_clamp =
      camera_matrices(s, c, s.camera.far ? s.camera.far : std::optional<double>(std::max(2.0 * farthest, 4.0 * s.camera.near)), 0.0);

  for (const Light& l : s.lights) p.lights.push_back(homogeneous(l));

  std::vector<const TriangleMesh<float>*> meshes;
  for (const Object& o : s.objects) {
    meshes.push_back(&o.mesh);
    PreparedCaster pc;
    const Result<MeshAdjacency> adj = build_adjacency(o.mesh);
    pc.closed = adj && adj->report.closed_manifold();
    Result<ShadowCaster<float>> caster = make_shadow_caster(o.mesh);
    const Result<BoundingSphere<float>> sphere = bounding_sphere(o.mesh);
    if (caster && sphere) {
      pc.caster = std::move(caster).value();
      pc.sphere = *sphere;
    } else {
      pc.why_not = caster ? sphere.message() : caster.message();
    }
    p.casters.push_back(std::move(pc));
  }

  LightFitOptions fit_options;
  fit_options.map_size = options.shadow_map_size;
  fit_options.camera_tan_per_pixel = std::tan(s.camera.fovy_deg * std::numbers::pi / 360.0) / s.height;
  for (const Vec4<double>& L : p.lights) p.light_fits.push_back(value_or_throw(fit_light(c, L, meshes, fit_options), "light fit"));
  for (std::size_t i = 0; i < p.lights.size(); ++i) p.cascade_fits.push_back(cascaded_light_fit(p, i));
  return p;
}

}  // namespace shadowref::scene
