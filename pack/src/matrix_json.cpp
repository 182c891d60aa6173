// matrix_json.cpp — a matrix in the pack's JSON layouts (matrix_json.hpp).
#include "shadowref/pack/matrix_json.hpp"

#include "shadowref/d3dx.hpp"

namespace shadowref::pack {

using nlohmann::json;

json rows(const Mat4<double>& m) {
  json a = json::array();
  for (int r = 0; r < 4; ++r) a.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  return a;
}

json both_layouts(const Mat4<double>& m) {
  const D3dxMatrix<double> d = to_d3dx(m);
  json a = json::array();
  for (int r = 0; r < 4; ++r) a.push_back({d.m[r][0], d.m[r][1], d.m[r][2], d.m[r][3]});
  return {{"canonical", rows(m)}, {"d3dx", a}};
}

json column_major(const Mat4<double>& m) {
  json a = json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a.push_back(m(r, c));
  return a;
}

json vec3(const Vec3<double>& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace shadowref::pack
