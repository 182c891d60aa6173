// shadowref/mesh.hpp — the indexed triangle mesh every part of shadowref shares, its validation and
// the welding of equal positions.
//
// Positions plus uint32 triangles; a triangle's vertices are counter-clockwise seen from its
// front (outside) side, so its face normal is (v1 − v0) × (v2 − v0). The type itself enforces
// nothing: validate_mesh() says whether a mesh can be used, weld_map() finds equal positions
// (meshes exported with split vertices: UV seams, flat-shaded normals), adjacency lives in
// adjacency.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <type_traits>
#include <vector>

#include "shadowref/conventions.hpp"
#include "shadowref/result.hpp"

namespace shadowref {

template <class T>
struct TriangleMesh {
  std::vector<Vec3<T>> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// The largest mesh the shadow-volume code accepts. Why: a volume's vertex buffer can hold every
// position twice (the mesh and its extrusion) in uint32 indices, and an edge use packs a triangle
// index with 3 bits of edge slot and direction (adjacency.hpp).
inline constexpr std::size_t kMaxMeshVertices = (std::size_t{1} << 31) - 2;
inline constexpr std::size_t kMaxMeshTriangles = std::size_t{1} << 29;

// Why a mesh cannot be used, or nullopt when it can: EmptyMesh (no triangles), MeshTooLarge,
// IndexOutOfRange (a triangle names a vertex >= positions.size()), NonFinite (a position that a
// triangle uses is NaN or infinite; unused positions are not looked at). Repeated indices and
// zero-area triangles are allowed here: they are reported by build_adjacency (degenerate).
// Cost: O(V + T).
template <class T>
std::optional<Error> validate_mesh(const TriangleMesh<T>& mesh) {
  if (mesh.triangles.empty()) return Error::EmptyMesh;
  if (mesh.positions.size() > kMaxMeshVertices || mesh.triangles.size() > kMaxMeshTriangles)
    return Error::MeshTooLarge;
  const std::size_t n = mesh.positions.size();
  for (const auto& t : mesh.triangles)
    for (std::uint32_t v : t)
      if (v >= n) return Error::IndexOutOfRange;
  for (const auto& t : mesh.triangles)
    for (std::uint32_t v : t)
      if (!mesh.positions[v].allFinite()) return Error::NonFinite;
  return std::nullopt;
}

namespace mesh_detail {

// The bits one coordinate is hashed by: exactly equal coordinates give equal bits. + 0 first:
// -0 + +0 = +0 (round to nearest), so -0 and +0, which are equal and weld, hash alike (one more
// reason the project builds without -ffast-math). Scalars other than float are hashed through
// double: equal values convert to equal doubles, and weld_map's exact comparison decides.
template <class T>
std::uint64_t coordinate_bits(T x) {
  x += T(0);
  if constexpr (std::is_same_v<T, float>) return std::bit_cast<std::uint32_t>(x);
  else return std::bit_cast<std::uint64_t>(static_cast<double>(x));
}

}  // namespace mesh_detail

// For every vertex, the representative of its position: the smallest vertex index whose position
// is exactly equal (==, so -0 and +0 weld). A vertex that is its own representative has
// map[v] == v. Exact equality on purpose: welding by a tolerance would change the topology
// depending on the mesh's scale, and an exporter that split a vertex wrote the same bits twice.
// A NaN position equals nothing, not even itself: it is its own representative (validate_mesh
// rejects NaN only where a triangle uses it).
// Algorithm: one pass in index order through an open-addressing hash table of vertex indices
// (linear probing and multiplicative hashing, Knuth, TAOCP vol. 3, §6.4, Algorithm L; load at
// most 1/2) that keeps the first vertex of every position: the hash-table weld of meshoptimizer's
// indexgenerator.cpp (buildPositionRemap, hashLookup), but on values rather than bytes, so that
// -0 and +0 weld. Cost: O(V) expected time (no sort), a table of 2 to 4 uint32 per vertex as
// scratch; built once per mesh.
template <class T>
std::vector<std::uint32_t> weld_map(const std::vector<Vec3<T>>& positions) {
  const auto n = static_cast<std::uint32_t>(positions.size());
  std::vector<std::uint32_t> map(n);
  constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;  // n <= kMaxMeshVertices < kEmpty
  unsigned bits = 4;
  while ((std::size_t{1} << bits) < 2 * std::size_t{n}) ++bits;
  const std::size_t mask = (std::size_t{1} << bits) - 1;
  std::vector<std::uint32_t> table(mask + 1, kEmpty);
  for (std::uint32_t v = 0; v < n; ++v) {
    const Vec3<T>& p = positions[v];
    std::uint64_t h = (mesh_detail::coordinate_bits(p.x()) * 0x9E3779B97F4A7C15ull) ^
                      (mesh_detail::coordinate_bits(p.y()) * 0xC2B2AE3D27D4EB4Full) ^
                      (mesh_detail::coordinate_bits(p.z()) * 0x165667B19E3779F9ull);
    h = (h ^ (h >> 31)) * 0x9E3779B97F4A7C15ull;  // the top bits, the slot, depend on every input bit
    std::size_t i = static_cast<std::size_t>(h >> (64 - bits));
    std::uint32_t rep = v;
    for (;; i = (i + 1) & mask) {
      const std::uint32_t e = table[i];
      if (e == kEmpty) {
        table[i] = v;
        break;
      }
      if (positions[e] == p) {
        rep = e;
        break;
      }
    }
    map[v] = rep;
  }
  return map;
}

// A copy of `mesh` with equal positions merged into one vertex (the first one, in index order) and
// unused positions dropped; `remap`, when given, receives for every old vertex its new index.
// Triangles keep their order and winding; degenerate ones are kept. Precondition: finite
// positions. Cost: O(V + T) expected (weld_map).
template <class T>
TriangleMesh<T> weld(const TriangleMesh<T>& mesh, std::vector<std::uint32_t>* remap = nullptr) {
  const std::vector<std::uint32_t> rep = weld_map(mesh.positions);
  constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> index(mesh.positions.size(), kUnset);
  TriangleMesh<T> out;
  out.triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    std::array<std::uint32_t, 3> u{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t r = rep[t[k]];
      if (index[r] == kUnset) {
        index[r] = static_cast<std::uint32_t>(out.positions.size());
        out.positions.push_back(mesh.positions[r]);
      }
      u[k] = index[r];
    }
    out.triangles.push_back(u);
  }
  if (remap) {
    remap->resize(mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) (*remap)[v] = index[rep[v]];
  }
  return out;
}

}  // namespace shadowref
