// shadowref/adjacency.hpp — edge adjacency of an indexed triangle mesh, its report (open,
// non-manifold, mis-wound edges, degenerate triangles) and the geometry-shader adjacency index
// buffer (GL_TRIANGLES_ADJACENCY, D3D11_PRIMITIVE_TOPOLOGY_TRIANGLELIST_ADJ).
//
// Edges are matched on WELDED vertices (mesh.hpp, weld_map): a mesh exported with split vertices
// (UV seams, flat normals) still gets its adjacency, while every index this header hands out is
// an index of the original mesh. Matching is a counting sort on the welded vertices, once per
// mesh (O(V + T), build_adjacency); the flat arrays it leaves (edge_offsets, edge_uses) are what
// the shadow caster's edge list is built from (silhouette.hpp), with no hashing and no allocation
// per light.
//
// Edge slot e of triangle (v0, v1, v2) is the directed edge v[e] -> v[(e + 1) % 3]:
// slot 0 = v0->v1, slot 1 = v1->v2, slot 2 = v2->v0 (the order of the adjacency index buffer).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Geometry>  // cross products

#include "shadowref/mesh.hpp"
#include "shadowref/result.hpp"

namespace shadowref {

// A triangle edge with no neighbour (open, non-manifold, or on a degenerate triangle).
inline constexpr std::uint32_t kNoNeighbor = 0xFFFFFFFFu;

// What build_adjacency found. Edges are counted once per undirected welded edge.
struct MeshReport {
  std::size_t vertices = 0;              // positions in the mesh (used or not)
  std::size_t welded_vertices = 0;       // distinct positions among the used vertices
  std::size_t triangles = 0;
  std::size_t edges = 0;                 // undirected welded edges of non-degenerate triangles
  std::size_t open_edges = 0;            // used by one triangle: a crack or a border
  std::size_t non_manifold_edges = 0;    // used by three or more triangles (fins, T-shapes)
  std::size_t miswound_edges = 0;        // two triangles that walk the edge in the same direction
  std::size_t degenerate_triangles = 0;  // a repeated welded vertex, or an exactly zero cross product

  // A closed, consistently wound, edge-manifold surface: every edge has exactly two triangles that
  // walk it in opposite directions. Why "edge-": two closed parts touching at one vertex (a bowtie
  // vertex) still pass, which is harmless for shadow volumes. Degenerate triangles do not break
  // closedness by themselves (those with a repeated vertex have no edges; zero-area ones keep theirs),
  // but a mesh with no edge at all (only repeated-vertex triangles) is not a surface.
  bool closed_manifold() const {
    return edges > 0 && open_edges == 0 && non_manifold_edges == 0 && miswound_edges == 0;
  }
};

// One triangle's use of an undirected edge, packed into 32 bits: triangle << 3 | reversed << 2 |
// slot. `reversed` is set when the triangle walks the edge from its larger welded vertex index to
// the smaller one, so two uses with different `reversed` bits are consistently wound.
struct EdgeUse {
  static constexpr std::uint32_t pack(std::uint32_t triangle, bool reversed, std::uint32_t slot) {
    return triangle << 3 | (reversed ? 4u : 0u) | slot;
  }
  static constexpr std::uint32_t triangle(std::uint32_t use) { return use >> 3; }
  static constexpr bool reversed(std::uint32_t use) { return (use & 4u) != 0; }
  static constexpr std::uint32_t slot(std::uint32_t use) { return use & 3u; }
};

struct MeshAdjacency {
  // weld[v]: the representative vertex of v's position (weld_map); edges are matched on these.
  std::vector<std::uint32_t> weld;
  // neighbors[t][e]: the triangle across edge slot e of t when that edge has exactly two triangles
  // (whatever their winding: mis-wound pairs are neighbours too, and reported), else kNoNeighbor.
  std::vector<std::array<std::uint32_t, 3>> neighbors;
  // neighbor_slots[t][e]: the slot of the same edge in neighbors[t][e] (undefined without one).
  std::vector<std::array<std::uint8_t, 3>> neighbor_slots;
  // Undirected edge i is used by edge_uses[edge_offsets[i] .. edge_offsets[i + 1]) (EdgeUse
  // values, in triangle order). Edges are sorted by their welded vertex pair.
  std::vector<std::uint32_t> edge_offsets;
  std::vector<std::uint32_t> edge_uses;
  // Triangles with a repeated welded vertex or a zero cross product (never lit, see silhouette.hpp).
  std::vector<std::uint32_t> degenerate_triangles;
  MeshReport report;

  std::size_t edge_count() const { return edge_offsets.empty() ? 0 : edge_offsets.size() - 1; }
};

// Welds, matches edges and classifies them. Errors: those of validate_mesh (EmptyMesh,
// MeshTooLarge, IndexOutOfRange, NonFinite). Degenerate triangles: one with a repeated welded
// vertex takes part in no edge (it encloses nothing and would fake non-manifold edges) and has
// kNoNeighbor on all three slots; a zero-area one with three distinct vertices keeps its edges, so
// that its neighbours stay connected.
// Algorithm: the edge uses, keyed by their welded pair (lo, hi), are grouped by a counting sort on
// lo (distribution counting, Knuth, TAOCP vol. 3, §5.2, Algorithm D: one histogram pass over the
// triangles, a prefix sum over the vertices, one scatter pass), then each vertex's bucket, about
// six uses, is sorted by hi (insertion sort; std::sort on (hi, use) for a large bucket such as a
// pole). The counting sort is stable and the uses are emitted in increasing order, so the result
// is the one of sorting the (lo, hi, use) triples: edges by welded pair, uses in triangle order,
// deterministic. Cost: O(V + T) expected time (plus the sorts of buckets of more than 32 uses),
// about 8 bytes per triangle edge and 4 per vertex of scratch besides the result; done once per
// mesh.
template <class T>
Result<MeshAdjacency> build_adjacency(const TriangleMesh<T>& mesh) {
  if (const auto bad = validate_mesh(mesh)) return *bad;
  MeshAdjacency adj;
  adj.weld = weld_map(mesh.positions);
  const std::uint32_t* weld = adj.weld.data();
  const std::size_t nv = mesh.positions.size(), nt = mesh.triangles.size();
  adj.neighbors.assign(nt, {kNoNeighbor, kNoNeighbor, kNoNeighbor});
  adj.neighbor_slots.assign(nt, {0, 0, 0});
  MeshReport& rep = adj.report;
  rep.vertices = nv;
  rep.triangles = nt;

  // Pass 1, the histogram: next[v] counts the uses whose smaller welded vertex is v; its top bit
  // says that v is used at all (by any triangle, degenerate ones included).
  constexpr std::uint32_t kUsed = 0x80000000u;  // uses < 3 * kMaxMeshTriangles < kUsed
  std::vector<std::uint32_t> next(nv, 0);
  std::uint32_t* count = next.data();
  for (std::uint32_t t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    const std::uint32_t w0 = weld[tri[0]], w1 = weld[tri[1]], w2 = weld[tri[2]];
    count[w0] |= kUsed, count[w1] |= kUsed, count[w2] |= kUsed;
    const bool repeated = w0 == w1 || w1 == w2 || w2 == w0;
    const Vec3<T>& p0 = mesh.positions[tri[0]];
    const bool zero_area =
        !repeated && (mesh.positions[tri[1]] - p0).cross(mesh.positions[tri[2]] - p0).squaredNorm() == T(0);
    if (repeated || zero_area) [[unlikely]] adj.degenerate_triangles.push_back(t);
    if (repeated) continue;
    ++count[std::min(w0, w1)], ++count[std::min(w1, w2)], ++count[std::min(w2, w0)];
  }
  rep.degenerate_triangles = adj.degenerate_triangles.size();
  // Prefix sum: next[v] = where bucket v starts.
  std::uint32_t uses = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const std::uint32_t c = count[v];
    rep.welded_vertices += c >> 31;
    count[v] = uses;
    uses += c & ~kUsed;
  }

  // Pass 2, the scatter: the uses in increasing order, each to the end of its bucket. After it
  // next[v] is where bucket v ends (and v + 1's begins).
  adj.edge_uses.resize(uses);
  std::vector<std::uint32_t> his(uses);
  std::uint32_t* use_of = adj.edge_uses.data();
  std::uint32_t* hi_of = his.data();
  const std::uint32_t* degenerate = adj.degenerate_triangles.data();
  const std::uint32_t* degenerate_end = degenerate + adj.degenerate_triangles.size();
  for (std::uint32_t t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    const std::array<std::uint32_t, 3> w{weld[tri[0]], weld[tri[1]], weld[tri[2]]};
    if (degenerate != degenerate_end && *degenerate == t) [[unlikely]] {
      ++degenerate;
      if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) continue;
    }
    for (std::uint32_t s = 0; s < 3; ++s) {
      const std::uint32_t a = w[s], b = w[s == 2 ? 0 : s + 1];
      const std::uint32_t i = count[std::min(a, b)]++;
      hi_of[i] = std::max(a, b);
      use_of[i] = EdgeUse::pack(t, a > b, s);
    }
  }

  // Each bucket sorted by hi, then its runs of equal hi are the edges.
  adj.edge_offsets.reserve(uses / 2 + 1);
  std::vector<std::uint64_t> big;  // a large bucket as (hi, use) pairs for std::sort
  std::uint32_t first = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const std::uint32_t last = count[v];
    if (last - first > 32) [[unlikely]] {
      big.resize(last - first);
      for (std::uint32_t k = first; k < last; ++k) big[k - first] = std::uint64_t{hi_of[k]} << 32 | use_of[k];
      std::sort(big.begin(), big.end());
      for (std::uint32_t k = first; k < last; ++k) {
        hi_of[k] = static_cast<std::uint32_t>(big[k - first] >> 32);
        use_of[k] = static_cast<std::uint32_t>(big[k - first]);
      }
    } else {
      for (std::uint32_t k = first + 1; k < last; ++k) {  // stable: equal his keep their use order
        const std::uint32_t h = hi_of[k], u = use_of[k];
        std::uint32_t j = k;
        for (; j > first && hi_of[j - 1] > h; --j) hi_of[j] = hi_of[j - 1], use_of[j] = use_of[j - 1];
        hi_of[j] = h, use_of[j] = u;
      }
    }
    for (std::uint32_t i = first; i < last;) {
      std::uint32_t j = i + 1;
      while (j < last && hi_of[j] == hi_of[i]) ++j;
      adj.edge_offsets.push_back(i);
      const std::uint32_t n = j - i;
      if (n == 1) ++rep.open_edges;
      else if (n > 2) ++rep.non_manifold_edges;
      else {
        const std::uint32_t u = use_of[i], w = use_of[i + 1];
        if (EdgeUse::reversed(u) == EdgeUse::reversed(w)) ++rep.miswound_edges;
        const std::uint32_t tu = EdgeUse::triangle(u), tw = EdgeUse::triangle(w);
        const std::uint32_t su = EdgeUse::slot(u), sw = EdgeUse::slot(w);
        adj.neighbors[tu][su] = tw;
        adj.neighbor_slots[tu][su] = static_cast<std::uint8_t>(sw);
        adj.neighbors[tw][sw] = tu;
        adj.neighbor_slots[tw][sw] = static_cast<std::uint8_t>(su);
      }
      i = j;
    }
    first = last;
  }
  adj.edge_offsets.push_back(uses);
  rep.edges = adj.edge_count();
  return adj;
}

// The geometry-shader adjacency index buffer: 6 indices per triangle t = (v0, v1, v2),
//   out[6t + 0, 2, 4] = v0, v1, v2 (drawing only the even entries gives back the mesh);
//   out[6t + 1, 3, 5] = the far vertex of the neighbour across v0->v1, v1->v2, v2->v0
// (the neighbour's vertex that is not on the shared edge, as an index of the original mesh).
// Convention for an edge without a consistently wound neighbour (open, non-manifold, mis-wound,
// or on a degenerate triangle): the triangle's OWN opposite vertex (v2 for edge v0->v1), as
// D3DX10 does. Why: the "neighbour" a geometry shader then sees is the triangle itself walked
// backwards, whose normal is the opposite of the face's, so a lit face's open edge is a
// silhouette edge there too (the rule of silhouette.hpp) and the volume stays closed.
// Matches meshopt_generateAdjacencyIndexBuffer on closed, consistently wound meshes.
// `out` is resized to 6T (no allocation when its capacity suffices). Cost: O(T).
template <class T>
void adjacency_index_buffer(const TriangleMesh<T>& mesh, const MeshAdjacency& adj, std::vector<std::uint32_t>& out) {
  const std::size_t nt = mesh.triangles.size();
  out.resize(6 * nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    for (std::uint32_t s = 0; s < 3; ++s) {
      std::uint32_t far = tri[(s + 2) % 3];
      const std::uint32_t n = adj.neighbors[t][s];
      if (n != kNoNeighbor) {
        const std::uint32_t ns = adj.neighbor_slots[t][s];
        const auto& ntri = mesh.triangles[n];
        // Consistently wound: the neighbour walks our edge backwards, starting at our end vertex.
        if (adj.weld[ntri[ns]] == adj.weld[tri[(s + 1) % 3]]) far = ntri[(ns + 2) % 3];
      }
      out[6 * t + 2 * s] = tri[s];
      out[6 * t + 2 * s + 1] = far;
    }
  }
}

}  // namespace shadowref
