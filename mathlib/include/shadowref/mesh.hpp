// shadowref/mesh.hpp — the indexed triangle mesh every part of shadowref shares.
//
// Positions plus uint32 triangles; a triangle's vertices are counter-clockwise seen from its
// front (outside) side, so its face normal is (v1 − v0) × (v2 − v0). No invariants are enforced
// by the type itself: validation, welding and adjacency live in their own headers.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "shadowref/conventions.hpp"

namespace shadowref {

template <class T>
struct TriangleMesh {
  std::vector<Vec3<T>> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

}  // namespace shadowref
