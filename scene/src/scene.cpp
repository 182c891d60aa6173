// scene.cpp — the small queries of scene.hpp (homogeneous lights, receiver plane, bounds).
#include "shadowref/scene/scene.hpp"

#include <algorithm>

namespace shadowref::scene {

const char* to_string(LightType type) {
  switch (type) {
    case LightType::Point: return "point";
    case LightType::Directional: return "directional";
    case LightType::Spot: return "spot";
    case LightType::Rect: return "rect";
  }
  return "unknown";
}

const LengthUnit* find_length_unit(std::string_view symbol) {
  for (const LengthUnit& u : kLengthUnits)
    if (u.symbol == symbol) return &u;
  return nullptr;
}

std::string length_unit_symbols() {
  std::string t;
  for (const LengthUnit& u : kLengthUnits) t += (t.empty() ? "" : ", ") + std::string(u.symbol);
  return t;
}

Vec4<double> homogeneous(const Light& light) {
  switch (light.type) {
    case LightType::Directional: return Vec4<double>(light.direction.x(), light.direction.y(), light.direction.z(), 0);
    case LightType::Rect: {
      const Vec3<double> c = light.corner + 0.5 * (light.edge_u + light.edge_v);
      return Vec4<double>(c.x(), c.y(), c.z(), 1);
    }
    case LightType::Point:
    case LightType::Spot: break;
  }
  return Vec4<double>(light.position.x(), light.position.y(), light.position.z(), 1);
}

bool Scene::has_tag(const std::string& tag) const {
  return std::find(tags.begin(), tags.end(), tag) != tags.end();
}

std::optional<std::size_t> Scene::receiver_index() const {
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (objects[i].receiver) return i;
  return std::nullopt;
}

std::optional<Plane<double>> receiver_plane(const Scene& scene) {
  const auto i = scene.receiver_index();
  if (!i) return std::nullopt;
  const auto& m = scene.objects[*i].mesh;
  // The first non-degenerate triangle defines the plane.
  for (const auto& t : m.triangles) {
    const auto p = plane_from_points<double>(m.positions[t[0]].cast<double>(), m.positions[t[1]].cast<double>(),
                                             m.positions[t[2]].cast<double>());
    if (!p) continue;
    const auto n = normalize(*p);
    if (n) return *n;
  }
  return std::nullopt;
}

std::array<Vec3<double>, 2> bounds(const Scene& scene) {
  Vec3<double> lo = Vec3<double>::Constant(std::numeric_limits<double>::infinity());
  Vec3<double> hi = -lo;
  for (const auto& o : scene.objects)
    for (const auto& p : o.mesh.positions) {
      lo = lo.cwiseMin(p.cast<double>());
      hi = hi.cwiseMax(p.cast<double>());
    }
  if (!lo.allFinite()) return {Vec3<double>::Zero(), Vec3<double>::Zero()};
  return {lo, hi};
}

}  // namespace shadowref::scene
