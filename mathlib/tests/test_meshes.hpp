// test_meshes.hpp — the hand-made meshes the shadow-volume tests share: a cube and its broken
// variants (open top, a non-manifold fin, one mis-wound triangle, split vertices), and an
// independent ray–triangle oracle for "how many lit faces lie between p and the light".
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "shadowref/mesh.hpp"
#include "shadowref/primitives.hpp"

namespace shadowref::test {

// The cube [-1, 1]^3 of make_box: faces −x, +x, −y, +y, −z, +z, two triangles each.
template <class T>
TriangleMesh<T> cube() {
  return make_box(Vec3<T>(-1, -1, -1), Vec3<T>(1, 1, 1)).value();
}

// The cube without its top (+y) face: 4 open edges around the top square, the box's "crack".
template <class T>
TriangleMesh<T> open_box() {
  TriangleMesh<T> m = cube<T>();
  m.triangles.erase(m.triangles.begin() + 6, m.triangles.begin() + 8);
  return m;
}

// The cube with a fin: a quad from the top front edge (vertices 6 = (-1, 1, 1), 7 = (1, 1, 1)) up
// and out to y = z = 2. Edge 6-7 then has three triangles (non-manifold); the fin's three outer
// edges are open. The fin faces (0, 1, -1)/sqrt2·(-1): its normal is (7-6) x (9-6).
template <class T>
TriangleMesh<T> cube_with_fin() {
  TriangleMesh<T> m = cube<T>();
  m.positions.emplace_back(-1, 2, 2);  // 8
  m.positions.emplace_back(1, 2, 2);   // 9
  m.triangles.push_back({6, 7, 9});
  m.triangles.push_back({6, 9, 8});
  return m;
}

// The cube with triangle 0 (half of the −x face) walked backwards: its three edges are mis-wound.
template <class T>
TriangleMesh<T> miswound_cube() {
  TriangleMesh<T> m = cube<T>();
  std::swap(m.triangles[0][1], m.triangles[0][2]);
  return m;
}

// The cube as exported with flat normals: 4 vertices per face (24), equal positions repeated.
template <class T>
TriangleMesh<T> split_cube() {
  const TriangleMesh<T> c = cube<T>();
  TriangleMesh<T> m;
  for (const auto& t : c.triangles) {
    std::array<std::uint32_t, 3> u{};
    for (int k = 0; k < 3; ++k) {
      u[k] = static_cast<std::uint32_t>(m.positions.size());
      m.positions.push_back(c.positions[t[k]]);
    }
    m.triangles.push_back(u);
  }
  return m;
}

// Whether the open segment a -> b crosses triangle (v0, v1, v2) strictly inside (Möller–Trumbore in
// double; an oracle independent of stencil_count.hpp's 4D determinants). `b_at_infinity`: b is a
// direction and the segment is the ray a + t b, t > 0.
inline bool segment_hits(const Vec3<double>& a, const Vec3<double>& b, bool b_at_infinity, const Vec3<double>& v0,
                         const Vec3<double>& v1, const Vec3<double>& v2) {
  const Vec3<double> dir = b_at_infinity ? b : Vec3<double>(b - a);
  const Vec3<double> e1 = v1 - v0, e2 = v2 - v0;
  const Vec3<double> pv = dir.cross(e2);
  const double det = e1.dot(pv);
  if (det == 0.0) return false;
  const Vec3<double> tv = a - v0;
  const double u = tv.dot(pv) / det;
  if (u <= 0.0 || u >= 1.0) return false;
  const Vec3<double> qv = tv.cross(e1);
  const double v = dir.dot(qv) / det;
  if (v <= 0.0 || u + v >= 1.0) return false;
  const double t = e2.dot(qv) / det;
  return t > 0.0 && (b_at_infinity || t < 1.0);
}

// The number of faces with plane · L >= 0 (the lit faces of silhouette.hpp) crossed by the
// segment from p to the light (the ray toward it for w = 0): the winding number the shadow volume
// must have at p, by the lit-prism model.
template <class T>
int lit_faces_toward_light(const TriangleMesh<T>& m, const Vec4<T>& light, const Vec3<T>& p) {
  const Vec3<double> a = p.template cast<double>();
  const bool directional = light.w() == T(0);
  const Vec3<double> b = directional ? Vec3<double>(light.template head<3>().template cast<double>())
                                     : Vec3<double>(light.template head<3>().template cast<double>() / double(light.w()));
  int count = 0;
  for (const auto& t : m.triangles) {
    const Vec3<double> v0 = m.positions[t[0]].template cast<double>(), v1 = m.positions[t[1]].template cast<double>(),
                       v2 = m.positions[t[2]].template cast<double>();
    const Vec3<double> n = (v1 - v0).cross(v2 - v0);
    const double pl = n.dot(light.template head<3>().template cast<double>()) - n.dot(v0) * double(light.w());
    if (n.squaredNorm() == 0.0 || pl < 0.0) continue;
    count += segment_hits(a, b, directional, v0, v1, v2) ? 1 : 0;
  }
  return count;
}

}  // namespace shadowref::test
