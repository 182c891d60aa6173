// shapes.cpp — the staircase of shapes.hpp, as a list of convex polygons whose
// vertices are welded by exact position, then fan-triangulated; exact welding is enough because
// every shared corner is computed by the same expression on both sides.
#include "shadowref/scene/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

namespace shadowref::scene {
namespace {

// Collects polygons into an indexed mesh, sharing vertices with identical coordinates.
class MeshBuilder {
 public:
  std::uint32_t vertex(const Vec3<double>& p) {
    const auto key = std::make_tuple(p.x(), p.y(), p.z());
    const auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    const auto i = static_cast<std::uint32_t>(mesh_.positions.size());
    mesh_.positions.push_back(p);
    index_.emplace(key, i);
    return i;
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) { mesh_.triangles.push_back({a, b, c}); }
  // A convex polygon, counter-clockwise from outside, fanned from its first vertex.
  void polygon(const std::vector<Vec3<double>>& corners) {
    std::vector<std::uint32_t> ids;
    ids.reserve(corners.size());
    for (const auto& c : corners) ids.push_back(vertex(c));
    for (std::size_t i = 1; i + 1 < ids.size(); ++i) triangle(ids[0], ids[i], ids[i + 1]);
  }
  TriangleMesh<double> take() { return std::move(mesh_); }

 private:
  TriangleMesh<double> mesh_;
  std::map<std::tuple<double, double, double>, std::uint32_t> index_;
};

}  // namespace

TriangleMesh<double> make_stairs(int steps, const Vec3<double>& size) {
  const double w = size.x() / 2;
  auto z_at = [&](int i) { return -size.z() / 2 + size.z() * i / steps; };
  auto y_at = [&](int i) { return size.y() * i / steps; };
  MeshBuilder b;
  for (int i = 0; i < steps; ++i) {
    const double z0 = z_at(i), z1 = z_at(i + 1), y0 = y_at(i), y1 = y_at(i + 1);
    b.polygon({{-w, y1, z0}, {-w, y1, z1}, {w, y1, z1}, {w, y1, z0}});  // tread, +y
    b.polygon({{-w, y0, z0}, {-w, y1, z0}, {w, y1, z0}, {w, y0, z0}});  // riser, −z
    b.polygon({{-w, 0, z0}, {w, 0, z0}, {w, 0, z1}, {-w, 0, z1}});      // bottom strip, −y
    // Side walls: column i is the pentagon (z0,0) (z1,0) (z1,y1) (z0,y1) (z0,y0); the corner
    // (z0, y0) keeps the wall T-junction free. Fanned from (z1, 0), which is never collinear
    // with two of the others. For i = 0, y0 = 0 and the pentagon is a quad.
    for (const double x : {w, -w}) {
      const Vec3<double> p0(x, 0, z1), p1(x, y1, z1), p2(x, y1, z0), p3(x, y0, z0), p4(x, 0, z0);
      std::vector<Vec3<double>> fan = i == 0 ? std::vector<Vec3<double>>{p0, p1, p2, p4}
                                             : std::vector<Vec3<double>>{p0, p1, p2, p3, p4};
      if (x > 0) std::reverse(fan.begin() + 1, fan.end());  // +x wall: the other winding
      b.polygon(fan);
    }
  }
  const double zb = z_at(steps), h = y_at(steps);
  b.polygon({{-w, 0, zb}, {w, 0, zb}, {w, h, zb}, {-w, h, zb}});  // back wall, +z
  return b.take();
}

}  // namespace shadowref::scene
