// shadowref/d3dx.hpp — interop with the D3DX / DirectXMath row-vector layout.
//
// A D3DX matrix is used as v' = v · M (row vectors) and stores fields _11, _12, …, _44 row by row
// (the D3DXMATRIX / XMFLOAT4X4 memory order). The same transform in canonical column-vector form is
// its transpose. `D3dxMatrix` is that memory image: 16 values, m[r][c] = _{r+1}{c+1}, so it can be
// memcpy'd into a D3DXMATRIX / XMFLOAT4X4 of the same scalar. No failure mode; cost: 16 copies.
#pragma once

#include <array>

#include "shadowref/conventions.hpp"

namespace shadowref {

template <class T>
struct D3dxMatrix {
  std::array<std::array<T, 4>, 4> m{};  // m[r][c] is field _{r+1}{c+1}

  // Field _rc with r, c in 1..4, as written in the D3DX documentation.
  T field(int r, int c) const { return m[r - 1][c - 1]; }
};

// Canonical (column vectors) → D3DX layout (row vectors): the transpose, written out as _11 … _44.
template <class T>
D3dxMatrix<T> to_d3dx(const Mat4<T>& canonical) {
  D3dxMatrix<T> out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.m[r][c] = canonical(c, r);
  return out;
}

// D3DX layout → canonical.
template <class T>
Mat4<T> from_d3dx(const D3dxMatrix<T>& d3dx) {
  Mat4<T> out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out(c, r) = d3dx.m[r][c];
  return out;
}

}  // namespace shadowref
