// Unit tests of shadowref/d3dx.hpp: the D3DX layout is the transpose, stored _11 … _44 row by row.
#include "shadowref/d3dx.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "scalar_types.hpp"

namespace shadowref {
namespace {

template <class T>
class D3dxTest : public ::testing::Test {};
TYPED_TEST_SUITE(D3dxTest, test::Scalars);

TYPED_TEST(D3dxTest, FieldsAreTheTransposeAndRoundTrip) {
  using T = TypeParam;
  Mat4<T> m;
  m << 11, 12, 13, 14, 21, 22, 23, 24, 31, 32, 33, 34, 41, 42, 43, 44;  // canonical M(r, c) = 10(r+1) + (c+1)
  const D3dxMatrix<T> d = to_d3dx(m);
  EXPECT_EQ(d.field(1, 2), T(21));  // _12 is the canonical (row 2, column 1)
  EXPECT_EQ(d.field(4, 1), T(14));  // _41 (the translation row in D3DX) is canonical column 4
  EXPECT_EQ(from_d3dx(d), m);
}

TYPED_TEST(D3dxTest, RowVectorTimesD3dxEqualsCanonicalTimesColumnVector) {
  using T = TypeParam;
  Mat4<T> m;
  m << 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16;
  const Vec4<T> v(1, -2, 3, 1);
  const D3dxMatrix<T> d = to_d3dx(m);
  Vec4<T> row_result = Vec4<T>::Zero();  // v' = v · M, written as D3DX's D3DXVec4Transform does
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) row_result[c] += v[r] * d.m[r][c];
  EXPECT_EQ(row_result, Vec4<T>(m * v));  // small integers: exact
}

TEST(D3dxLayout, MemoryOrderIsTheD3dxMatrixOrder) {
  // A D3DXMATRIX / XMFLOAT4X4 is 16 floats _11, _12, _13, _14, _21, … in memory.
  Mat4<float> m = Mat4<float>::Zero();
  m(0, 3) = 7.0f;  // canonical translation x is D3DX _41, the 13th float in memory
  const D3dxMatrix<float> d = to_d3dx(m);
  float raw[16];
  static_assert(sizeof(d.m) == sizeof(raw));
  std::memcpy(raw, &d.m, sizeof raw);
  EXPECT_EQ(raw[12], 7.0f);
}

}  // namespace
}  // namespace shadowref
