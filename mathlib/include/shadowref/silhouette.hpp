// shadowref/silhouette.hpp — which faces a homogeneous light lights, and the silhouette edges
// that a shadow volume extrudes.
//
// The model (Doom 3's, see docs/dependencies.md): the shadow volume is the sum of the shadow prisms of the
// LIT faces, each prism bounded by its face (the light cap), the face extruded away from the light
// (the dark cap) and one side quad per face edge. Where two lit faces share an edge walked in
// opposite directions, their side quads cancel; what remains are the silhouette edges. So:
//   * a face is lit when plane · L >= 0 (tie rule: a face whose plane contains the light is lit;
//     a degenerate face, zero normal, is never lit: its prism encloses nothing);
//   * a silhouette edge joins a lit and an unlit face;
//   * an open edge of a lit face is a silhouette edge, so volumes of open meshes stay closed;
//   * on any edge, the side quads kept are the NET count m = (lit uses walking it one way) −
//     (lit uses walking it the other way), |m| copies in the direction of the sign. That is the
//     multiplicity that keeps the stencil count right for non-manifold edges (a fin lit on one
//     side counts once, three lit faces on one edge count their net winding) and for mis-wound
//     pairs (two lit faces walking an edge the same way give two quads).
// A face lit under this rule but facing away from the light in reality (a mis-wound face) casts
// the prism of its as-wound plane: the volume is what the mesh says, not what it means.
//
// Orientation: a silhouette edge (from, to) is walked OPPOSITE to the lit face that owns it, so
// that the side quad (from, to, to', from') — primes being the extruded vertices — is
// counter-clockwise seen from outside the volume (its front faces out). For a closed,
// consistently wound mesh, (from, to) is the edge as the unlit neighbour walks it.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <type_traits>
#include <vector>

#include <Eigen/Geometry>

#include "shadowref/adjacency.hpp"
#include "shadowref/cpu_features.hpp"
#include "shadowref/mesh.hpp"
#include "shadowref/result.hpp"

namespace shadowref {

// A directed silhouette edge in vertex indices of the original mesh (see the orientation above).
struct SilhouetteEdge {
  std::uint32_t from = 0;
  std::uint32_t to = 0;
  friend bool operator==(const SilhouetteEdge&, const SilhouetteEdge&) = default;
};

// The face planes of a mesh, one array per component (structure of arrays: the per-light facing
// loop reads four streams and vectorises). planes[t] gives plane t back as a Vec4.
template <class T>
struct FacePlanes {
  std::vector<T> x, y, z, w;
  std::size_t size() const { return x.size(); }
  Vec4<T> operator[](std::size_t t) const { return Vec4<T>(x[t], y[t], z[t], w[t]); }
};

// A mesh prepared once for shadow volumes: the mesh, its adjacency, its face planes and the flat
// edge list the per-light silhouette loop walks.
template <class T>
struct ShadowCaster {
  TriangleMesh<T> mesh;
  MeshAdjacency adjacency;
  // face_planes[t] = (n, −n·v0) with n = (v1 − v0) × (v2 − v0), unnormalised: plane · L needs no
  // division, and only its sign is used. Zero for a repeated-vertex triangle.
  FacePlanes<T> face_planes;
  // For adjacency edge e, edge_use_pairs[2e] and [2e + 1]: the two uses (EdgeUse values: triangle,
  // direction, slot) of a regular edge (two uses walked in opposite directions), the one walking
  // it lo -> hi first. Such an edge is a silhouette edge exactly when their triangles' lit flags
  // differ, and then the lit use names it. Irregular edges (open, non-manifold, mis-wound) have
  // both entries 0, so that this test never picks them, and are listed, in increasing order, in
  // irregular_edges: the loop visits each of them by all its uses.
  std::vector<std::uint32_t> edge_use_pairs;
  std::vector<std::uint32_t> irregular_edges;
  // The faces of each block of kSilhouetteEdgeBlock edges (block k: edges [Bk, Bk + B)), as a
  // few triangle ranges that hold every triangle its edges name: [edge_block_faces[2i],
  // edge_block_faces[2i + 1]) for i in [edge_block_face_offsets[k], edge_block_face_offsets[k + 1]).
  // When every lit flag in them is the same, no regular edge of the block joins a lit and an
  // unlit face, and find_silhouette skips the block without reading its pairs (it still walks its
  // irregular edges): most blocks, because the triangles around a vertex are near in index and
  // lit faces come in runs. A block whose triangles would need more than 4 ranges or 4B
  // triangles has no ranges and is always tested.
  std::vector<std::uint32_t> edge_block_face_offsets;
  std::vector<std::uint32_t> edge_block_faces;
};

// The edges find_silhouette tests at once, and skips at once (ShadowCaster::edge_block_faces).
// 128 rather than 64: fewer range checks, measured 2-4% faster per light at 1M triangles.
inline constexpr std::size_t kSilhouetteEdgeBlock = 128;

// Validates the mesh, builds the adjacency, the face planes and the edge list. Errors: those of
// build_adjacency. Cost: O(V + T) (build_adjacency's), once per mesh.
template <class T>
Result<ShadowCaster<T>> make_shadow_caster(TriangleMesh<T> mesh) {
  auto adj = build_adjacency(mesh);
  if (!adj) return adj.error();
  ShadowCaster<T> c{std::move(mesh), std::move(adj).value(), {}, {}, {}, {}, {}};
  const std::size_t nt = c.mesh.triangles.size();
  FacePlanes<T>& fp = c.face_planes;
  fp.x.resize(nt), fp.y.resize(nt), fp.z.resize(nt), fp.w.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = c.mesh.triangles[t];
    const Vec3<T>& p0 = c.mesh.positions[tri[0]];
    const Vec3<T> n = (c.mesh.positions[tri[1]] - p0).cross(c.mesh.positions[tri[2]] - p0);
    fp.x[t] = n.x(), fp.y[t] = n.y(), fp.z[t] = n.z(), fp.w[t] = -n.dot(p0);
  }
  const MeshAdjacency& a = c.adjacency;
  const std::size_t ne = a.edge_count();
  c.edge_use_pairs.assign(2 * ne, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::uint32_t first = a.edge_offsets[e];
    const std::uint32_t u = a.edge_uses[first], v = a.edge_uses[first + 1 < a.edge_offsets[e + 1] ? first + 1 : first];
    if (a.edge_offsets[e + 1] - first == 2 && EdgeUse::reversed(u) != EdgeUse::reversed(v)) {
      c.edge_use_pairs[2 * e] = EdgeUse::reversed(u) ? v : u;
      c.edge_use_pairs[2 * e + 1] = EdgeUse::reversed(u) ? u : v;
    } else {
      c.irregular_edges.push_back(static_cast<std::uint32_t>(e));
    }
  }
  // Each block's triangles, sorted, merged into runs (gaps of up to 8 triangles are taken in: a
  // few more flags to check, fewer ranges).
  constexpr std::size_t kMaxRanges = 4, kMaxSpan = 4 * kSilhouetteEdgeBlock;
  constexpr std::uint32_t kGap = 8;
  const std::size_t blocks = (ne + kSilhouetteEdgeBlock - 1) / kSilhouetteEdgeBlock;
  c.edge_block_face_offsets.assign(blocks + 1, 0);
  std::vector<std::uint32_t> faces;
  for (std::size_t k = 0; k < blocks; ++k) {
    const std::size_t first = k * kSilhouetteEdgeBlock, last = std::min(ne, first + kSilhouetteEdgeBlock);
    const std::size_t mark = c.edge_block_faces.size();
    c.edge_block_face_offsets[k] = static_cast<std::uint32_t>(mark / 2);
    faces.clear();
    for (std::size_t e = first; e < last; ++e)
      if (c.edge_use_pairs[2 * e] != c.edge_use_pairs[2 * e + 1])  // a regular edge (irregular ones: 0, 0)
        faces.push_back(EdgeUse::triangle(c.edge_use_pairs[2 * e])), faces.push_back(EdgeUse::triangle(c.edge_use_pairs[2 * e + 1]));
    if (faces.empty()) continue;
    std::sort(faces.begin(), faces.end());
    std::size_t span = 0;
    for (const std::uint32_t t : faces) {
      if (c.edge_block_faces.size() > mark && t <= c.edge_block_faces.back() + kGap) {
        span += std::max(c.edge_block_faces.back(), t + 1) - c.edge_block_faces.back();
        c.edge_block_faces.back() = std::max(c.edge_block_faces.back(), t + 1);
      } else {
        c.edge_block_faces.push_back(t);
        c.edge_block_faces.push_back(t + 1);
        span += 1;
      }
    }
    if (c.edge_block_faces.size() - mark > 2 * kMaxRanges || span > kMaxSpan) c.edge_block_faces.resize(mark);
  }
  c.edge_block_face_offsets[blocks] = static_cast<std::uint32_t>(c.edge_block_faces.size() / 2);
  return c;
}

// Why a light cannot be used, or nullopt: NonFinite, ZeroLight, NegativeLightW (w < 0 would
// reverse every facing test; scale a point light so that w > 0).
template <class T>
std::optional<Error> validate_light(const Vec4<T>& light) {
  if (!light.allFinite()) return Error::NonFinite;
  if (light.cwiseAbs().maxCoeff() == T(0)) return Error::ZeroLight;  // not squaredNorm: it underflows
  if (light.w() < T(0)) return Error::NegativeLightW;
  return std::nullopt;
}

// The per-light output, reused from light to light (clear() keeps the capacity: no allocation
// once it has grown to the mesh's size).
template <class T>
struct Silhouette {
  Vec4<T> light = Vec4<T>::Zero();    // the light these were computed for (volume.hpp reads it)
  std::vector<std::uint8_t> lit;      // per triangle: 1 lit, 0 not
  std::size_t lit_count = 0;
  std::vector<SilhouetteEdge> edges;  // one entry per side quad: an edge of multiplicity m appears |m| times
};

namespace silhouette_detail {
#if defined(__x86_64__) && !defined(__AVX2__)
// classify_faces' loop for float compiled for AVX2 (eight faces per register), same operations in
// the same order per lane and no FMA, so bit for bit the SSE2 loop's answers.
__attribute__((target("avx2"))) inline std::size_t classify_avx2(const float* __restrict px, const float* __restrict py,
                                                                 const float* __restrict pz, const float* __restrict pw,
                                                                 float lx, float ly, float lz, float lw,
                                                                 std::uint8_t* __restrict lit, std::size_t nt) {
  std::uint32_t count = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint8_t l = ((px[t] * lx + pz[t] * lz) + (py[t] * ly + pw[t] * lw)) >= 0.0f;
    lit[t] = l;
    count += l;
  }
  return count;
}
#endif
}  // namespace silhouette_detail

// Facing of every face for `light`: out.lit[t] = plane_t · L >= 0, and 0 for degenerate faces.
// plane_t · L is summed as (x Lx + z Lz) + (y Ly + w Lw), the order of Eigen's Vec4 dot on SSE
// and AVX, so that face_planes[t].dot(L) >= 0 gives the same answer bit for bit.
// Cost: 4 multiplies and 3 adds per triangle, a flat loop over the four plane arrays, which GCC
// vectorises with SSE2; for float on a CPU with AVX2 (asked once: cpu_features.hpp) the same
// loop compiled for AVX2, eight faces per register, with the same operations per lane and no FMA:
// the same flags bit for bit (silhouette_test), measured 1.3-1.8x faster for the sides-only volume
// at 100k and 1M triangles (geometry_bench).
template <class T>
void classify_faces(const ShadowCaster<T>& caster, const Vec4<T>& light, Silhouette<T>& out) {
  const FacePlanes<T>& fp = caster.face_planes;
  const std::size_t nt = fp.size();
  out.light = light;
  out.lit.resize(nt);
  const T lx = light.x(), ly = light.y(), lz = light.z(), lw = light.w();
  const T* __restrict px = fp.x.data();
  const T* __restrict py = fp.y.data();
  const T* __restrict pz = fp.z.data();
  const T* __restrict pw = fp.w.data();
  std::uint8_t* __restrict lit = out.lit.data();
  std::uint32_t count = 0;  // nt <= kMaxMeshTriangles
#if defined(__x86_64__) && !defined(__AVX2__)
  if constexpr (std::is_same_v<T, float>) {
    if (cpu_has_avx2()) {
      out.lit_count = silhouette_detail::classify_avx2(px, py, pz, pw, lx, ly, lz, lw, lit, nt);
      count = static_cast<std::uint32_t>(out.lit_count);
      for (std::uint32_t t : caster.adjacency.degenerate_triangles) {
        count -= lit[t];
        lit[t] = 0;
      }
      out.lit_count = count;
      return;
    }
  }
#endif
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint8_t l = ((px[t] * lx + pz[t] * lz) + (py[t] * ly + pw[t] * lw)) >= T(0);
    lit[t] = l;
    count += l;
  }
  // A zero plane would be lit by the tie rule (0 >= 0); degenerate faces are never lit.
  for (std::uint32_t t : caster.adjacency.degenerate_triangles) {
    count -= lit[t];
    lit[t] = 0;
  }
  out.lit_count = count;
}

namespace silhouette_detail {

// The side quads of adjacency edge e, by its uses (any edge: regular or not).
template <class T>
void emit_edge(const ShadowCaster<T>& caster, const std::uint8_t* lit, std::size_t e, std::vector<SilhouetteEdge>& out) {
  const MeshAdjacency& adj = caster.adjacency;
  const std::uint32_t* uses = adj.edge_uses.data();
  const std::uint32_t first = adj.edge_offsets[e], last = adj.edge_offsets[e + 1];
  int m = 0;  // net lit uses: +1 walking lo -> hi, −1 walking hi -> lo
  for (std::uint32_t k = first; k < last; ++k)
    if (lit[EdgeUse::triangle(uses[k])]) m += EdgeUse::reversed(uses[k]) ? -1 : 1;
  if (m == 0) return;
  // A lit use walking in the net direction names the edge in its own (original) vertices.
  const bool want_reversed = m < 0;
  for (std::uint32_t k = first; k < last; ++k) {
    const std::uint32_t u = uses[k];
    if (!lit[EdgeUse::triangle(u)] || EdgeUse::reversed(u) != want_reversed) continue;
    const auto& tri = caster.mesh.triangles[EdgeUse::triangle(u)];
    const std::uint32_t s = EdgeUse::slot(u);
    const SilhouetteEdge edge{tri[(s + 1) % 3], tri[s]};  // opposite to the lit face's walk
    for (int c = std::abs(m); c > 0; --c) out.push_back(edge);
    return;
  }
}

}  // namespace silhouette_detail

// The silhouette edges of `caster` for the homogeneous light `light` (w = 1 point, w = 0
// directional; any w > 0 is the point xyz / w), with the rules and orientation at the top of this
// file, in the order of the adjacency's edges. Fills `out` (facing and edges). Errors: those of
// validate_light. Cost: O(T + E), no allocation once `out` has grown. The edge pass goes
// kSilhouetteEdgeBlock edges at a time: a block whose faces are all lit or all unlit
// (edge_block_faces: a few runs of lit flags, checked eight at a time) is skipped; the others are
// a flat loop over their edge_use_pairs: one load of the pair, two lit lookups and an xor per
// edge, stored as a byte, with no branch; the bytes are scanned eight at a time, and only the few
// differing edges are named (one random access each). The irregular edges are walked by all
// their uses, in edge order.
template <class T>
Result<std::size_t> find_silhouette(const ShadowCaster<T>& caster, const Vec4<T>& light, Silhouette<T>& out) {
  if (const auto bad = validate_light(light)) return *bad;
  classify_faces(caster, light, out);
  out.edges.clear();
  const std::uint8_t* lit = out.lit.data();
  const std::uint32_t* pairs = caster.edge_use_pairs.data();
  const std::uint32_t* irregular = caster.irregular_edges.data();
  const std::uint32_t* irregular_end = irregular + caster.irregular_edges.size();
  const std::size_t ne = caster.adjacency.edge_count();
  constexpr std::size_t kBlock = kSilhouetteEdgeBlock;
  alignas(8) std::uint8_t differ[kBlock];  // per edge of the block: 1 when its two faces differ
  const std::uint32_t* range_offsets = caster.edge_block_face_offsets.data();
  const std::uint32_t* ranges = caster.edge_block_faces.data();
  for (std::size_t base = 0; base < ne; base += kBlock) {
    const std::size_t end = std::min(ne, base + kBlock);
    // Skip the block when all the faces its edges name are lit, or all unlit.
    if (const std::uint32_t* r = ranges + 2 * range_offsets[base / kBlock], *r_end = ranges + 2 * range_offsets[base / kBlock + 1];
        r != r_end) {
      const std::uint8_t first = lit[r[0]];
      const std::uint64_t same = first * 0x0101010101010101ull;  // eight copies of the flag
      std::uint64_t seen = 0;  // a bit of a flag that differs from `first`
      for (; r != r_end; r += 2) {
        const std::uint32_t a = r[0], b = r[1];
        if (b - a < 8) {
          for (std::uint32_t t = a; t < b; ++t) seen |= lit[t] ^ first;
          continue;
        }
        std::uint64_t word;
        for (std::uint32_t t = a; t + 8 <= b; t += 8) {
          std::memcpy(&word, lit + t, sizeof word);
          seen |= word ^ same;
        }
        std::memcpy(&word, lit + b - 8, sizeof word);  // the last eight, overlapping
        seen |= word ^ same;
      }
      if (seen == 0) {  // no regular edge of the block is a silhouette edge
        while (irregular != irregular_end && *irregular < end)
          silhouette_detail::emit_edge(caster, lit, *irregular++, out.edges);
        continue;
      }
    }
    const std::uint32_t* p = pairs + 2 * base;
    const std::size_t n = end - base;
    if (n % 8 != 0) std::memset(differ + (n & ~std::size_t{7}), 0, 8);  // a partial last word reads as "same"
    for (std::size_t i = 0; i < n; ++i) {
      std::uint64_t pair;  // both uses in one load (in either order: the xor is symmetric)
      std::memcpy(&pair, p + 2 * i, sizeof pair);
      differ[i] = lit[EdgeUse::triangle(static_cast<std::uint32_t>(pair))] ^ lit[EdgeUse::triangle(static_cast<std::uint32_t>(pair >> 32))];
    }
    for (std::size_t word = 0; word < n; word += 8) {
      std::uint64_t bits;  // eight 0/1 bytes: all zero but near the silhouette
      std::memcpy(&bits, differ + word, sizeof bits);
      if (bits == 0) [[likely]] continue;
      for (std::size_t i = word; i < std::min(n, word + 8); ++i) {
        if (!differ[i]) continue;
        const auto e = static_cast<std::uint32_t>(base + i);
        while (irregular != irregular_end && *irregular < e)
          silhouette_detail::emit_edge(caster, lit, *irregular++, out.edges);
        // A regular edge with one lit face: one quad, named by the lit use (as emit_edge would).
        const std::uint32_t u = lit[EdgeUse::triangle(pairs[2 * e])] ? pairs[2 * e] : pairs[2 * e + 1];
        const auto& tri = caster.mesh.triangles[EdgeUse::triangle(u)];
        const std::uint32_t s = EdgeUse::slot(u);
        out.edges.push_back(SilhouetteEdge{tri[(s + 1) % 3], tri[s]});  // opposite to the lit face's walk
      }
    }
    while (irregular != irregular_end && *irregular < end)
      silhouette_detail::emit_edge(caster, lit, *irregular++, out.edges);
  }
  return out.edges.size();
}

}  // namespace shadowref
