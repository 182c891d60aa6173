// shadowref/silhouette.hpp — which faces a homogeneous light lights, and the silhouette edges
// that a shadow volume extrudes.
//
// The model (Doom 3's, see PITFALLS.md): the shadow volume is the sum of the shadow prisms of the
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

#include <array>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "shadowref/adjacency.hpp"
#include "shadowref/mesh.hpp"
#include "shadowref/result.hpp"

namespace shadowref {

// A directed silhouette edge in vertex indices of the original mesh (see the orientation above).
struct SilhouetteEdge {
  std::uint32_t from = 0;
  std::uint32_t to = 0;
  friend bool operator==(const SilhouetteEdge&, const SilhouetteEdge&) = default;
};

// A mesh prepared once for shadow volumes: the mesh, its adjacency, and its face planes.
template <class T>
struct ShadowCaster {
  TriangleMesh<T> mesh;
  MeshAdjacency adjacency;
  // face_planes[t] = (n, −n·v0) with n = (v1 − v0) × (v2 − v0), unnormalised: plane · L needs no
  // division, and only its sign is used. Zero for a repeated-vertex triangle.
  std::vector<Vec4<T>> face_planes;
};

// Validates the mesh, builds the adjacency and the face planes. Errors: those of build_adjacency.
// Cost: O(V log V + T log T), once per mesh.
template <class T>
Result<ShadowCaster<T>> make_shadow_caster(TriangleMesh<T> mesh) {
  auto adj = build_adjacency(mesh);
  if (!adj) return adj.error();
  ShadowCaster<T> c{std::move(mesh), std::move(adj).value(), {}};
  c.face_planes.resize(c.mesh.triangles.size());
  for (std::size_t t = 0; t < c.mesh.triangles.size(); ++t) {
    const auto& tri = c.mesh.triangles[t];
    const Vec3<T>& p0 = c.mesh.positions[tri[0]];
    const Vec3<T> n = (c.mesh.positions[tri[1]] - p0).cross(c.mesh.positions[tri[2]] - p0);
    c.face_planes[t] = Vec4<T>(n.x(), n.y(), n.z(), -n.dot(p0));
  }
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

// Facing of every face for `light`: out.lit[t] = plane_t · L >= 0, and 0 for degenerate faces.
// Cost: 4 multiply-adds per triangle.
template <class T>
void classify_faces(const ShadowCaster<T>& caster, const Vec4<T>& light, Silhouette<T>& out) {
  const std::size_t nt = caster.face_planes.size();
  out.light = light;
  out.lit.resize(nt);
  std::size_t count = 0;
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint8_t lit = caster.face_planes[t].dot(light) >= T(0) ? 1 : 0;
    out.lit[t] = lit;
    count += lit;
  }
  // A zero plane would be lit by the tie rule (0 >= 0); degenerate faces are never lit.
  for (std::uint32_t t : caster.adjacency.degenerate_triangles) {
    count -= out.lit[t];
    out.lit[t] = 0;
  }
  out.lit_count = count;
}

// The silhouette edges of `caster` for the homogeneous light `light` (w = 1 point, w = 0
// directional; any w > 0 is the point xyz / w), with the rules and orientation at the top of this
// file, in the order of the adjacency's edges. Fills `out` (facing and edges). Errors: those of
// validate_light. Cost: O(T + E), no allocation once `out` has grown; the only random access is
// lit[triangle] per edge use.
template <class T>
Result<std::size_t> find_silhouette(const ShadowCaster<T>& caster, const Vec4<T>& light, Silhouette<T>& out) {
  if (const auto bad = validate_light(light)) return *bad;
  classify_faces(caster, light, out);
  out.edges.clear();
  const MeshAdjacency& adj = caster.adjacency;
  const auto& tris = caster.mesh.triangles;
  const std::uint8_t* lit = out.lit.data();
  const std::uint32_t* uses = adj.edge_uses.data();
  const std::size_t ne = adj.edge_count();
  for (std::size_t e = 0; e < ne; ++e) {
    const std::uint32_t first = adj.edge_offsets[e], last = adj.edge_offsets[e + 1];
    int m = 0;  // net lit uses: +1 walking lo -> hi, −1 walking hi -> lo
    for (std::uint32_t k = first; k < last; ++k)
      if (lit[EdgeUse::triangle(uses[k])]) m += EdgeUse::reversed(uses[k]) ? -1 : 1;
    if (m == 0) continue;
    // A lit use walking in the net direction names the edge in its own (original) vertices.
    const bool want_reversed = m < 0;
    for (std::uint32_t k = first; k < last; ++k) {
      const std::uint32_t u = uses[k];
      if (!lit[EdgeUse::triangle(u)] || EdgeUse::reversed(u) != want_reversed) continue;
      const auto& tri = tris[EdgeUse::triangle(u)];
      const std::uint32_t s = EdgeUse::slot(u);
      const SilhouetteEdge edge{tri[(s + 1) % 3], tri[s]};  // opposite to the lit face's walk
      for (int c = std::abs(m); c > 0; --c) out.edges.push_back(edge);
      break;
    }
  }
  return out.edges.size();
}

}  // namespace shadowref
