// shadowref/pack/matrix_json.hpp — a 4 × 4 matrix as the pack writes it in JSON (docs/output-contract.md,
// "The pack's whole-scene glTF"; the pack README's "The matrices").
//
// Every matrix of the pack (matrices.json, scene.gltf's extras) is written through these, so that
// one layout rule holds for all of them: canonical rows (column vectors, v' = M v, as mathlib and
// OpenGL), the D3DX fields _11 .. _44 row by row (row vectors, v' = v M: the transpose), or glTF's
// node.matrix (the 16 values column by column). Values are the doubles themselves, never rounded.
#pragma once

#include <nlohmann/json.hpp>

#include "shadowref/conventions.hpp"

namespace shadowref::pack {

// The rows of `m`: [[m00, m01, m02, m03], ...] (canonical layout). Cost: 16 values.
nlohmann::json rows(const Mat4<double>& m);

// {"canonical": rows(m), "d3dx": the D3DX fields _11 .. _44 row by row (mathlib/d3dx.hpp's to_d3dx)}.
nlohmann::json both_layouts(const Mat4<double>& m);

// glTF's node.matrix: the 16 values column by column.
nlohmann::json column_major(const Mat4<double>& m);

// [x, y, z].
nlohmann::json vec3(const Vec3<double>& v);

}  // namespace shadowref::pack
