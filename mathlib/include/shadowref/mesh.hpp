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
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
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

// For every vertex, the representative of its position: the smallest vertex index whose position
// is exactly equal (==, so -0 and +0 weld; the caller has rejected NaN). A vertex that is its own
// representative has map[v] == v. Exact equality on purpose: welding by a tolerance would change
// the topology depending on the mesh's scale, and an exporter that split a vertex wrote the same
// bits twice. Precondition: positions finite (validate_mesh). Cost: O(V log V), one sort of
// indices, built once per mesh.
template <class T>
std::vector<std::uint32_t> weld_map(const std::vector<Vec3<T>>& positions) {
  const auto n = static_cast<std::uint32_t>(positions.size());
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  const auto less = [&](std::uint32_t a, std::uint32_t b) {
    const Vec3<T>& p = positions[a];
    const Vec3<T>& q = positions[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return a < b;  // equal positions sorted by index: the first of a run is the smallest
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> map(n);
  for (std::uint32_t i = 0; i < n;) {
    std::uint32_t j = i + 1;
    while (j < n && positions[order[j]] == positions[order[i]]) ++j;
    for (std::uint32_t k = i; k < j; ++k) map[order[k]] = order[i];
    i = j;
  }
  return map;
}

// A copy of `mesh` with equal positions merged into one vertex (the first one, in index order) and
// unused positions dropped; `remap`, when given, receives for every old vertex its new index.
// Triangles keep their order and winding; degenerate ones are kept. Precondition: finite
// positions. Cost: O(V log V + T).
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
