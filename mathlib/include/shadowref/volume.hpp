// shadowref/volume.hpp — stencil shadow volumes as draw-ready homogeneous vec4 vertex and uint32
// index buffers: side quads on the silhouette, the light cap and the dark cap, extruded to
// infinity (w = 0) or by a finite distance.
//
// Follows Everitt & Kilgard, "Practical and Robust Stenciled Shadow Volumes for Hardware-
// Accelerated Rendering" (2002), with the lit-face model of silhouette.hpp: light cap = the lit
// faces as wound, dark cap = the lit faces extruded and walked backwards, so every triangle of
// the volume is counter-clockwise seen from outside (its front faces out) — the orientation the
// z-pass / z-fail stencil operations assume (front faces: z-pass increments, z-fail decrements).
//
// Vertex buffer layout (N = mesh vertex count):
//   [0, N)    the mesh positions, (x, y, z, 1), in the mesh's own indices;
//   [N, 2N)   their extrusions, vertex N + i belonging to vertex i — except for a directional light
//             extruded to infinity, where every extrusion is the same point (−L.xyz, 0) and the
//             buffer is [0, N] with that one point at index N.
// Index buffer: three ranges of triangles, in this order, so that z-pass draws only the first:
//   sides, light cap, dark cap (VolumeRanges gives them, in indices).
#pragma once

#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "shadowref/result.hpp"
#include "shadowref/silhouette.hpp"

namespace shadowref {

// The extrusion of a point V (w = 1, or any w) away from the homogeneous light L to infinity:
// (V.xyz · L.w − L.xyz · V.w, 0) — the direction from the light through V (for w = 0 lights, −L.xyz
// for every V). Degenerate: V at the light gives (0, 0, 0, 0), which is no point at all; callers
// check (build_shadow_volume returns LightOnCaster). Cost: 3 multiply-adds.
template <class T>
Vec4<T> extrude_to_infinity(const Vec4<T>& v, const Vec4<T>& light) {
  return Vec4<T>(v.x() * light.w() - light.x() * v.w(), v.y() * light.w() - light.y() * v.w(),
                 v.z() * light.w() - light.z() * v.w(), T(0));
}

// The finite extrusion of the point p away from L by `distance`: p + distance · d / |d| with
// d = p · L.w − L.xyz (w = 1 result). The older method: a receiver farther than `distance` from
// the caster is missed, which is worst when the light is close to the caster (the extrusion does
// not grow with the distance from the light) — one of the catalogue's expected failures.
// Degenerate: p at the light gives p itself (d = 0: no direction); build_shadow_volume reports it.
template <class T>
Vec4<T> extrude_finite(const Vec3<T>& p, const Vec4<T>& light, T distance) {
  const Vec3<T> d = p * light.w() - light.template head<3>();
  const T len = d.norm();
  if (!(len > T(0))) return Vec4<T>(p.x(), p.y(), p.z(), T(1));
  const Vec3<T> q = p + d * (distance / len);
  return Vec4<T>(q.x(), q.y(), q.z(), T(1));
}

template <class T>
struct VolumeOptions {
  bool light_cap = true;             // z-fail needs both caps; z-pass draws sides only
  bool dark_cap = true;              // ignored (none needed) for a directional light to infinity
  std::optional<T> finite_distance;  // nullopt: extrude to infinity (w = 0); else by this distance
};

// Where each part lies in ShadowVolume::indices: [first, first + count), counts in indices (3 per
// triangle).
struct VolumeRanges {
  std::uint32_t side_first = 0, side_count = 0;
  std::uint32_t light_cap_first = 0, light_cap_count = 0;
  std::uint32_t dark_cap_first = 0, dark_cap_count = 0;
  std::uint32_t triangle_count() const { return (side_count + light_cap_count + dark_cap_count) / 3; }
};

template <class T>
struct ShadowVolume {
  std::vector<Vec4<T>> vertices;  // homogeneous, layout at the top of this file
  std::vector<std::uint32_t> indices;
  VolumeRanges ranges;
  Vec4<T> light = Vec4<T>::Zero();
};

// Builds the volume of `caster` for the light and silhouette in `sil` (find_silhouette's output
// for the same caster) into `out`, reusing its buffers (no allocation once they have grown).
// Sides: 2 triangles per silhouette edge (from, to, to', from'), or 1 triangle (from, to, ∞) for a
// directional light to infinity (both far corners are the same point). Light cap: the lit faces.
// Dark cap: the lit faces extruded, reversed. Errors: DistanceNotPositive (finite_distance <= 0),
// NonFinite (a non-finite distance), LightOnCaster (a vertex the volume uses coincides with the
// light: it has no extrusion direction; the buffers are then filled but not drawable).
// Cost: O(V + silhouette + lit faces).
template <class T>
Result<VolumeRanges> build_shadow_volume(const ShadowCaster<T>& caster, const Silhouette<T>& sil,
                                         const VolumeOptions<T>& options, ShadowVolume<T>& out) {
  assert(sil.lit.size() == caster.mesh.triangles.size());
  if (options.finite_distance) {
    if (!std::isfinite(*options.finite_distance)) return Error::NonFinite;
    if (!(*options.finite_distance > T(0))) return Error::DistanceNotPositive;
  }
  const Vec4<T>& light = sil.light;
  const auto& pos = caster.mesh.positions;
  const auto n = static_cast<std::uint32_t>(pos.size());
  const bool directional = light.w() == T(0);
  const bool single_apex = directional && !options.finite_distance;  // all extrusions meet at one point
  out.light = light;

  // Vertices: the mesh, then its extrusions (one pass over the positions); count the vertices
  // with no extrusion direction (at the light).
  out.vertices.resize(single_apex ? n + 1 : 2 * std::size_t{n});
  Vec4<T>* vert = out.vertices.data();
  std::size_t no_direction = 0;
  if (single_apex) {
    for (std::uint32_t i = 0; i < n; ++i) vert[i] = Vec4<T>(pos[i].x(), pos[i].y(), pos[i].z(), T(1));
    vert[n] = Vec4<T>(-light.x(), -light.y(), -light.z(), T(0));
  } else if (!options.finite_distance) {
    for (std::uint32_t i = 0; i < n; ++i) {
      const Vec4<T> v(pos[i].x(), pos[i].y(), pos[i].z(), T(1));
      const Vec4<T> e = extrude_to_infinity(v, light);
      no_direction += (e.x() == T(0) && e.y() == T(0) && e.z() == T(0)) ? 1 : 0;
      vert[i] = v;
      vert[n + i] = e;
    }
  } else {
    const T dist = *options.finite_distance;
    for (std::uint32_t i = 0; i < n; ++i) {
      const Vec3<T> d = pos[i] * light.w() - light.template head<3>();
      no_direction += (d.x() == T(0) && d.y() == T(0) && d.z() == T(0)) ? 1 : 0;
      vert[i] = Vec4<T>(pos[i].x(), pos[i].y(), pos[i].z(), T(1));
      vert[n + i] = extrude_finite(pos[i], light, dist);
    }
  }

  // Indices: sides, light cap, dark cap.
  const bool dark = options.dark_cap && !single_apex;
  const std::size_t lit = sil.lit_count;
  const std::size_t side_indices = (single_apex ? 3 : 6) * sil.edges.size();
  out.indices.resize(side_indices + (options.light_cap ? 3 * lit : 0) + (dark ? 3 * lit : 0));
  std::uint32_t* w = out.indices.data();
  for (const SilhouetteEdge& e : sil.edges) {
    if (single_apex) {
      *w++ = e.from, *w++ = e.to, *w++ = n;
    } else {
      *w++ = e.from, *w++ = e.to, *w++ = n + e.to;
      *w++ = e.from, *w++ = n + e.to, *w++ = n + e.from;
    }
  }
  // Both caps in one pass over the triangles (the pass is memory-bound).
  const auto& tris = caster.mesh.triangles;
  std::uint32_t* light_w = w;
  std::uint32_t* dark_w = w + (options.light_cap ? 3 * lit : 0);
  if (options.light_cap || dark)
    for (std::size_t t = 0; t < tris.size(); ++t) {
      if (!sil.lit[t]) continue;
      const auto& tri = tris[t];
      if (options.light_cap) *light_w++ = tri[0], *light_w++ = tri[1], *light_w++ = tri[2];
      if (dark) *dark_w++ = n + tri[0], *dark_w++ = n + tri[2], *dark_w++ = n + tri[1];
    }
  assert((dark ? dark_w : light_w) == out.indices.data() + out.indices.size());

  VolumeRanges& r = out.ranges;
  r.side_first = 0;
  r.side_count = static_cast<std::uint32_t>(side_indices);
  r.light_cap_first = r.side_count;
  r.light_cap_count = options.light_cap ? static_cast<std::uint32_t>(3 * lit) : 0;
  r.dark_cap_first = r.light_cap_first + r.light_cap_count;
  r.dark_cap_count = dark ? static_cast<std::uint32_t>(3 * lit) : 0;

  // Rare path: some vertex sits on the light; an error only if the volume uses it.
  if (no_direction > 0) {
    for (std::uint32_t i : out.indices) {
      if (i < n) continue;
      const Vec3<T> d = pos[i - n] * light.w() - light.template head<3>();
      if (d.x() == T(0) && d.y() == T(0) && d.z() == T(0)) return Error::LightOnCaster;
    }
  }
  return r;
}

}  // namespace shadowref
