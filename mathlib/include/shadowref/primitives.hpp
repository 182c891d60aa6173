// shadowref/primitives.hpp — procedural meshes: box, UV sphere, torus, plane.
//
// Every solid here is closed, consistently wound (counter-clockwise seen from outside, so face
// normals point out), welded (one vertex per position: no seam duplicates, one vertex per pole)
// and free of degenerate triangles: build_adjacency reports it as a closed manifold. The scene
// loader, the property tests and the benchmarks build their shapes from these. y is up.
// Errors: InvalidShape for a size that is not finite and > 0, or a tessellation below the
// minimum stated per function (or too large for 32-bit indices).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "shadowref/mesh.hpp"
#include "shadowref/result.hpp"

namespace shadowref {
namespace primitives_detail {

template <class T>
bool positive(T v) {
  return std::isfinite(v) && v > T(0);
}

// Two triangles for the quad a-b-c-d, counter-clockwise seen from its front.
inline void quad(std::vector<std::array<std::uint32_t, 3>>& tris, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                 std::uint32_t d) {
  tris.push_back({a, b, c});
  tris.push_back({a, c, d});
}

}  // namespace primitives_detail

// The axis-aligned box [lo, hi]: 8 vertices, 12 triangles, faces in the order −x, +x, −y, +y, −z,
// +z (triangles 2k and 2k + 1 are face k: remove 6 and 7 for a box open at the top).
// Vertex i has x = hi.x if bit 0 of i, y = hi.y if bit 1, z = hi.z if bit 2 (else lo).
// Errors: InvalidShape unless lo < hi in every coordinate and both are finite.
template <class T>
Result<TriangleMesh<T>> make_box(const Vec3<T>& lo, const Vec3<T>& hi) {
  using primitives_detail::positive;
  if (!lo.allFinite() || !hi.allFinite() || !positive(hi.x() - lo.x()) || !positive(hi.y() - lo.y()) ||
      !positive(hi.z() - lo.z()))
    return Error::InvalidShape;
  TriangleMesh<T> m;
  for (std::uint32_t i = 0; i < 8; ++i)
    m.positions.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  auto& t = m.triangles;
  primitives_detail::quad(t, 0, 4, 6, 2);  // −x
  primitives_detail::quad(t, 1, 3, 7, 5);  // +x
  primitives_detail::quad(t, 0, 1, 5, 4);  // −y
  primitives_detail::quad(t, 2, 6, 7, 3);  // +y
  primitives_detail::quad(t, 0, 2, 3, 1);  // −z
  primitives_detail::quad(t, 4, 5, 7, 6);  // +z
  return m;
}

// A UV sphere of `radius` centred at the origin, poles on ±y: `segments` >= 3 around, `rings` >= 2
// from pole to pole. Vertex 0 is the north pole (+y), the last vertex the south pole; ring r
// (1 .. rings − 1) holds vertices 1 + (r − 1) segments + s at longitude 2π s / segments.
// 2 + (rings − 1) segments vertices, 2 segments (rings − 1) triangles.
template <class T>
Result<TriangleMesh<T>> make_uv_sphere(T radius, std::uint32_t segments, std::uint32_t rings) {
  if (!primitives_detail::positive(radius) || segments < 3 || rings < 2 || segments > (1u << 14) || rings > (1u << 14))
    return Error::InvalidShape;
  const T pi = std::numbers::pi_v<T>;
  TriangleMesh<T> m;
  m.positions.emplace_back(T(0), radius, T(0));
  for (std::uint32_t r = 1; r < rings; ++r) {
    const T theta = pi * T(r) / T(rings);
    const T y = radius * std::cos(theta), rho = radius * std::sin(theta);
    for (std::uint32_t s = 0; s < segments; ++s) {
      const T phi = T(2) * pi * T(s) / T(segments);
      m.positions.emplace_back(rho * std::cos(phi), y, rho * std::sin(phi));
    }
  }
  const auto south = static_cast<std::uint32_t>(m.positions.size());
  m.positions.emplace_back(T(0), -radius, T(0));
  const auto at = [&](std::uint32_t r, std::uint32_t s) { return 1 + (r - 1) * segments + s % segments; };
  for (std::uint32_t s = 0; s < segments; ++s) m.triangles.push_back({0, at(1, s + 1), at(1, s)});
  for (std::uint32_t r = 1; r + 1 < rings; ++r)
    for (std::uint32_t s = 0; s < segments; ++s)
      primitives_detail::quad(m.triangles, at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s));
  for (std::uint32_t s = 0; s < segments; ++s) m.triangles.push_back({south, at(rings - 1, s), at(rings - 1, s + 1)});
  return m;
}

// A torus around the y axis centred at the origin: tube centre at distance `major` from the axis,
// tube radius `minor` < major; `major_segments` >= 3 around the axis, `minor_segments` >= 3 around
// the tube. Vertex i · minor_segments + j is at major angle 2π i / major_segments, minor angle
// 2π j / minor_segments. major_segments · minor_segments vertices, twice as many triangles.
template <class T>
Result<TriangleMesh<T>> make_torus(T major, T minor, std::uint32_t major_segments, std::uint32_t minor_segments) {
  if (!primitives_detail::positive(major) || !primitives_detail::positive(minor) || !(minor < major) ||
      major_segments < 3 || minor_segments < 3 || major_segments > (1u << 14) || minor_segments > (1u << 14))
    return Error::InvalidShape;
  const T pi = std::numbers::pi_v<T>;
  TriangleMesh<T> m;
  for (std::uint32_t i = 0; i < major_segments; ++i) {
    const T u = T(2) * pi * T(i) / T(major_segments);
    for (std::uint32_t j = 0; j < minor_segments; ++j) {
      const T v = T(2) * pi * T(j) / T(minor_segments);
      const T rho = major + minor * std::cos(v);
      m.positions.emplace_back(rho * std::cos(u), minor * std::sin(v), rho * std::sin(u));
    }
  }
  const auto at = [&](std::uint32_t i, std::uint32_t j) {
    return (i % major_segments) * minor_segments + j % minor_segments;
  };
  for (std::uint32_t i = 0; i < major_segments; ++i)
    for (std::uint32_t j = 0; j < minor_segments; ++j)
      primitives_detail::quad(m.triangles, at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
  return m;
}

// The rectangle |x| <= half_x, |z| <= half_z in the plane y = 0, facing +y: 4 vertices, 2
// triangles. Open (4 open edges), as a ground plane is.
template <class T>
Result<TriangleMesh<T>> make_plane(T half_x, T half_z) {
  if (!primitives_detail::positive(half_x) || !primitives_detail::positive(half_z)) return Error::InvalidShape;
  TriangleMesh<T> m;
  m.positions = {Vec3<T>(-half_x, 0, -half_z), Vec3<T>(half_x, 0, -half_z), Vec3<T>(half_x, 0, half_z),
                 Vec3<T>(-half_x, 0, half_z)};
  primitives_detail::quad(m.triangles, 0, 3, 2, 1);
  return m;
}

}  // namespace shadowref
