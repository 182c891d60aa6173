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
// Vertex buffer layout: only the mesh vertices the index buffer uses, K of them, in the order in
// which the silhouette edges (from, to), then the lit faces (v0, v1, v2, in triangle order, when
// a cap is drawn) first name them; ShadowVolume::source[j] is the mesh vertex of the j-th:
//   2j        mesh vertex source[j], (x, y, z, 1);
//   2j + 1    its extrusion (written for every j; the sides and the dark cap use it);
// except for a directional light extruded to infinity, where every extrusion is the same point
// (−L.xyz, 0): the buffer is then [0, K] with mesh vertex source[j] at j and that point at K.
// Why only the used vertices: a volume without caps (z-pass) uses the silhouette's vertices only,
// a few thousand of a million-vertex mesh; writing every vertex and its extrusion for each light
// was most of its cost, and is also what the GPU would have to upload.
// Index buffer: three ranges of triangles, in this order, so that z-pass draws only the first:
//   sides, light cap, dark cap (VolumeRanges gives them, in indices).
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <type_traits>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// A mesh vertex that the volume being built does not use yet (ShadowVolume::volume_vertex).
inline constexpr std::uint32_t kNoVolumeVertex = 0xFFFFFFFFu;

template <class T>
struct ShadowVolume {
  std::vector<Vec4<T>> vertices;  // homogeneous, layout at the top of this file
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> source;  // source[j]: the mesh vertex of volume vertices 2j and 2j + 1 (or j)
  VolumeRanges ranges;
  Vec4<T> light = Vec4<T>::Zero();
  // Scratch of build_shadow_volume, per mesh vertex: its j during a build, kNoVolumeVertex between
  // builds (the build resets the entries it set, so a volume costs O(what it uses), not O(V)).
  std::vector<std::uint32_t> volume_vertex;
};

namespace volume_detail {

// The numbering of the volume's vertices in order of first use: number[v] is mesh vertex v's j
// (kNoVolumeVertex before its first use), source[j] the mesh vertex of j.
struct Numbering {
  std::uint32_t* number;
  std::uint32_t* source;
  std::uint32_t used;
  std::uint32_t operator()(std::uint32_t v) {
    const std::uint32_t j = number[v];
    if (j != kNoVolumeVertex) [[likely]] return j;  // most uses: a vertex shared with an earlier face
    number[v] = used;
    source[used] = v;
    return used++;
  }
};

// Both caps in one pass over the triangles: for each lit face, in order, with a, b, c its
// vertices' numbers << kShift (their volume indices), the light cap (a, b, c) and the dark cap
// (a + 1, c + 1, b + 1), the extrusions walked backwards (see build_shadow_volume).
// The lit flags are read eight at a time: lit and unlit faces come in runs (a mesh's neighbouring
// triangles are mostly near in index), so most words are all 0 (skipped) or all 1. One copy per
// kind of cap, with the choices out of the loop (it was most of a capped volume's cost).
template <bool kLight, bool kDark, unsigned kShift>
void write_caps(const std::vector<std::array<std::uint32_t, 3>>& tris, const std::uint8_t* flags, Numbering& numbering,
                std::uint32_t* light_w, std::uint32_t* dark_w) {
  Numbering use = numbering;  // a local copy: `used` stays in a register
  const auto cap = [&](std::size_t t) {
    const auto& tri = tris[t];
    const std::uint32_t a = use(tri[0]) << kShift, b = use(tri[1]) << kShift, c = use(tri[2]) << kShift;
    if constexpr (kLight) light_w[0] = a, light_w[1] = b, light_w[2] = c, light_w += 3;
    if constexpr (kDark) dark_w[0] = a + 1, dark_w[1] = c + 1, dark_w[2] = b + 1, dark_w += 3;
  };
  const std::size_t nt = tris.size();
  constexpr std::uint64_t kAllLit = 0x0101010101010101ull;  // lit flags are 0 or 1
  std::size_t t = 0;
  for (; t + 8 <= nt; t += 8) {
    std::uint64_t word;
    std::memcpy(&word, flags + t, sizeof word);
    if (word == 0) continue;
    if (word == kAllLit) {
      for (std::size_t k = t; k < t + 8; ++k) cap(k);
    } else {
      for (std::size_t k = t; k < t + 8; ++k)
        if (flags[k]) cap(k);
    }
  }
  for (; t < nt; ++t)
    if (flags[t]) cap(t);
  numbering = use;
}

}  // namespace volume_detail

// Builds the volume of `caster` for the light and silhouette in `sil` (find_silhouette's output
// for the same caster) into `out`, reusing its buffers (no allocation once they have grown).
// Sides: 2 triangles per silhouette edge (from, to, to', from'), or 1 triangle (from, to, ∞) for a
// directional light to infinity (both far corners are the same point). Light cap: the lit faces.
// Dark cap: the lit faces extruded, reversed. Errors: DistanceNotPositive (finite_distance <= 0),
// NonFinite (a non-finite distance), LightOnCaster (a vertex the volume uses coincides with the
// light: it has no extrusion direction; the buffers are then filled but not drawable).
// Cost: O(silhouette) without caps; O(T) to find the lit faces, plus O(lit faces), with caps.
// Memory: out.volume_vertex grows to V entries once.
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
  const std::size_t n = pos.size();
  const bool directional = light.w() == T(0);
  const bool single_apex = directional && !options.finite_distance;  // all extrusions meet at one point
  const bool dark = options.dark_cap && !single_apex;
  const bool caps = options.light_cap || dark;
  const std::size_t lit = sil.lit_count;
  out.light = light;

  // Every allocation first: once volume_vertex entries are set, nothing may throw before they
  // are reset.
  const std::size_t side_indices = (single_apex ? 3 : 6) * sil.edges.size();
  out.indices.resize(side_indices + (options.light_cap ? 3 * lit : 0) + (dark ? 3 * lit : 0));
  const std::size_t most = std::min(n, 2 * sil.edges.size() + (caps ? 3 * lit : 0));  // vertices used, at most
  out.source.resize(most);
  out.vertices.reserve(single_apex ? most + 1 : 2 * most);
  if (out.volume_vertex.size() < n) out.volume_vertex.resize(n, kNoVolumeVertex);

  // Number the used vertices in order of first use: j for a new vertex, its number otherwise.
  std::uint32_t* number = out.volume_vertex.data();
  std::uint32_t* source = out.source.data();
  volume_detail::Numbering use{number, source, 0};

  // Indices: sides (their far corners once K is known when single_apex), light cap, dark cap.
  std::uint32_t* w = out.indices.data();
  for (const SilhouetteEdge& e : sil.edges) {
    const std::uint32_t a = use(e.from), b = use(e.to);
    if (single_apex) {
      *w++ = a, *w++ = b, *w++ = 0;  // the apex: set below
    } else {
      *w++ = 2 * a, *w++ = 2 * b, *w++ = 2 * b + 1;
      *w++ = 2 * a, *w++ = 2 * b + 1, *w++ = 2 * a + 1;
    }
  }
  std::uint32_t* light_w = w;
  std::uint32_t* dark_w = w + (options.light_cap ? 3 * lit : 0);
  const auto& tris = caster.mesh.triangles;
  const std::uint8_t* flags = sil.lit.data();
  // The volume index of vertex j is j << 1 (its extrusion (j << 1) + 1), or j with a single apex.
  if (options.light_cap && dark) volume_detail::write_caps<true, true, 1>(tris, flags, use, light_w, dark_w);
  else if (dark) volume_detail::write_caps<false, true, 1>(tris, flags, use, light_w, dark_w);
  else if (options.light_cap && single_apex) volume_detail::write_caps<true, false, 0>(tris, flags, use, light_w, dark_w);
  else if (options.light_cap) volume_detail::write_caps<true, false, 1>(tris, flags, use, light_w, dark_w);
  const std::uint32_t used = use.used;
  assert(side_indices + (options.light_cap ? 3 * lit : 0) + (dark ? 3 * lit : 0) == out.indices.size());
  if (single_apex)
    for (std::size_t i = 2; i < side_indices; i += 3) out.indices[i] = used;

  // Vertices: each used one and its extrusion; reset the numbering; count the vertices with no
  // extrusion direction (at the light).
  out.source.resize(used);
  out.vertices.resize(single_apex ? std::size_t{used} + 1 : 2 * std::size_t{used});
  // Written coordinate by coordinate: building Vec4s from a Vec3 here went through the stack.
  T* vert = out.vertices.empty() ? nullptr : out.vertices.front().data();  // Vec4<T>: four packed Ts
  static_assert(sizeof(Vec4<T>) == 4 * sizeof(T));
  const T lx = light.x(), ly = light.y(), lz = light.z(), lw = light.w();
  std::size_t no_direction = 0;
  if (single_apex) {
    for (std::uint32_t j = 0; j < used; ++j) {
      const Vec3<T>& p = pos[source[j]];
      number[source[j]] = kNoVolumeVertex;
      T* o = vert + 4 * std::size_t{j};
      o[0] = p.x(), o[1] = p.y(), o[2] = p.z(), o[3] = T(1);
    }
    T* o = vert + 4 * std::size_t{used};
    o[0] = -lx, o[1] = -ly, o[2] = -lz, o[3] = T(0);
  } else if (!options.finite_distance) {
#if defined(__SSE2__)
    if constexpr (std::is_same_v<T, float>) {
      const __m128 l4 = _mm_setr_ps(lx, ly, lz, lw), w4 = _mm_set1_ps(lw), zero = _mm_setzero_ps();
      for (std::uint32_t j = 0; j < used; ++j) {
        const float* p = pos[source[j]].data();
        number[source[j]] = kNoVolumeVertex;
        const __m128 v = _mm_setr_ps(p[0], p[1], p[2], 1.0f);
        const __m128 e = _mm_sub_ps(_mm_mul_ps(v, w4), l4);  // lane 3: 1 · L.w − L.w = 0
        no_direction += _mm_movemask_ps(_mm_cmpeq_ps(e, zero)) == 0xF ? 1 : 0;
        _mm_storeu_ps(vert + 8 * std::size_t{j}, v);
        _mm_storeu_ps(vert + 8 * std::size_t{j} + 4, e);
      }
    } else
#endif
    for (std::uint32_t j = 0; j < used; ++j) {
      const Vec3<T>& p = pos[source[j]];
      number[source[j]] = kNoVolumeVertex;
      const T x = p.x(), y = p.y(), z = p.z();
      // extrude_to_infinity with V.w = 1.
      const T ex = x * lw - lx * T(1), ey = y * lw - ly * T(1), ez = z * lw - lz * T(1);
      no_direction += (ex == T(0) && ey == T(0) && ez == T(0)) ? 1 : 0;
      T* o = vert + 8 * std::size_t{j};
      o[0] = x, o[1] = y, o[2] = z, o[3] = T(1);
      o[4] = ex, o[5] = ey, o[6] = ez, o[7] = T(0);
    }
  } else {
    const T dist = *options.finite_distance;
    for (std::uint32_t j = 0; j < used; ++j) {
      const Vec3<T>& p = pos[source[j]];
      number[source[j]] = kNoVolumeVertex;
      const Vec3<T> d = p * lw - light.template head<3>();
      no_direction += (d.x() == T(0) && d.y() == T(0) && d.z() == T(0)) ? 1 : 0;
      const Vec4<T> e = extrude_finite(p, light, dist);
      T* o = vert + 8 * std::size_t{j};
      o[0] = p.x(), o[1] = p.y(), o[2] = p.z(), o[3] = T(1);
      o[4] = e.x(), o[5] = e.y(), o[6] = e.z(), o[7] = e.w();
    }
  }

  VolumeRanges& r = out.ranges;
  r.side_first = 0;
  r.side_count = static_cast<std::uint32_t>(side_indices);
  r.light_cap_first = r.side_count;
  r.light_cap_count = options.light_cap ? static_cast<std::uint32_t>(3 * lit) : 0;
  r.dark_cap_first = r.light_cap_first + r.light_cap_count;
  r.dark_cap_count = dark ? static_cast<std::uint32_t>(3 * lit) : 0;

  // Rare path: some used vertex sits on the light; an error only if the volume uses its extrusion
  // (odd indices; a single apex has no vertex at the light: directional).
  if (no_direction > 0) {
    for (std::uint32_t i : out.indices) {
      if ((i & 1u) == 0) continue;
      const Vec3<T> d = pos[out.source[i >> 1]] * light.w() - light.template head<3>();
      if (d.x() == T(0) && d.y() == T(0) && d.z() == T(0)) return Error::LightOnCaster;
    }
  }
  return r;
}

}  // namespace shadowref
