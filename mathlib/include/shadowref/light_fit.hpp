// shadowref/light_fit.hpp — where a shadow map looks from: the light's views and projections fitted
// to the scene's geometry, for spot / point / rect (one perspective view, or a cube of six) and
// directional lights (one orthographic view), in any run convention (convention.hpp).
//
//   * directional light (w = 0): one orthographic view looking along −L at the centre of the
//     geometry's bounding box, holding the box's bounding sphere (radius r), near r/2 and far 3.5 r
//     from an eye 2 r toward the light;
//   * point light (w ≠ 0; spot and rect lights are fitted at their position / centre): one
//     perspective view aimed at the centre of the bounding box and opened to hold all eight
//     corners, when that takes at most kMaxSingleFovDeg and every corner is in front of the light;
//     otherwise a CUBE of six 90-degree views (Gerasimov 2004, "Omnidirectional shadow mapping",
//     GPU Gems ch. 12) in the order +x, −x, +y, −y, +z, −z of scene space, each opened
//     kCubeMarginTexels wider than 90 degrees so that filter taps next to a face's edge stay in
//     that face. A cube face's near plane is the distance to the closest triangle divided by
//     sqrt(1 + 2 tan²) (no point of the face's frustum lies farther from the light than that factor
//     times its depth), so depth keeps its precision; its far is the farthest vertex. A face that
//     no object reaches is marked empty, and each face lists the objects that may reach it.
//   Why the cube: one perspective map covers less than a half-space around the light; with the light
//   inside or beside the scene's bounds a clamped frustum would leave geometry outside (false light).
//
// Map size (texels per side): the caller's, or automatic: kTexelsPerCameraPixel texels per camera
// pixel in angle at the centres of both views, clamped to [kAutoMinSize, kAutoMaxSize]
// ([kAutoMinSize, kCubeAutoMaxSize] per cube face; kDirectionalAutoSize for directional lights).
// Cost: one pass over the vertices for the box and the single view; a cube adds one pass over the
// triangles (closest point) and one over the vertices per face.
// Errors: EmptyMesh when there is no vertex; NonFinite for non-finite input. Canonical matrices;
// `view` is view_from_scene of the convention (so it includes the d3d world mirror).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "shadowref/convention.hpp"
#include "shadowref/mesh.hpp"

namespace shadowref {

inline constexpr double kMaxSingleFovDeg = 160.0;
inline constexpr int kAutoMinSize = 1024;
inline constexpr int kAutoMaxSize = 8192;
inline constexpr int kCubeAutoMaxSize = 2048;      // per face: six of them
inline constexpr int kDirectionalAutoSize = 2048;
// Texels per camera pixel, in angle at the view centres: a pixel next to a silhouette seen from the
// light is then not judged by a texel on the wrong side of it.
inline constexpr double kTexelsPerCameraPixel = 3.0;
inline constexpr double kCubeMarginTexels = 3.0;

struct LightView {
  Mat4<double> view;                // scene → light view space (view_from_scene)
  Mat4<double> projection;          // light view → clip, in the run convention
  bool empty = false;               // no geometry reaches this view (a cube face): clear it, draw nothing
  std::vector<bool> draw;           // per mesh: may reach this view (empty vector: every mesh)
};

struct LightFit {
  std::vector<LightView> views;     // 1, 6 for a cube (+x, −x, +y, −y, +z, −z), or one per cascade
  bool cube = false;
  int size = kDirectionalAutoSize;  // texels per side of every view's map
  // Cascaded (cascades.hpp, fit_cascades): views[i] decides the scene points whose camera depth
  // cascade_depth_from_scene · (p, 1) lies in [cascade_splits[i], cascade_splits[i + 1]) (the last
  // closed). Empty: not cascaded.
  std::vector<double> cascade_splits;
  Vec4<double> cascade_depth_from_scene = Vec4<double>::Zero();
};


struct LightFitOptions {
  int map_size = 0;                 // texels per side; 0: automatic (see above)
  // tan(fovy / 2) / image height of the camera: the angle of one camera pixel at the view centre,
  // the unit of the automatic size. 0: the automatic size is kAutoMinSize.
  double camera_tan_per_pixel = 0;
};

// The world axis least aligned with `forward`: an up vector never parallel to it.
template <class T>
Vec3<T> least_aligned_axis(const Vec3<T>& forward) {
  const Vec3<T> a = forward.cwiseAbs();
  if (a.x() <= a.y() && a.x() <= a.z()) return Vec3<T>(1, 0, 0);
  if (a.y() <= a.z()) return Vec3<T>(0, 1, 0);
  return Vec3<T>(0, 0, 1);
}

// The point of triangle abc closest to p (Ericson, "Real-Time Collision Detection", 5.1.5). A
// degenerate (zero-area) triangle gives one of its vertices.
template <class T>
Vec3<T> closest_point_on_triangle(const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) {
  const Vec3<T> ab = b - a, ac = c - a, ap = p - a;
  const T d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3<T> bp = p - b;
  const T d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const T vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3<T> cp = p - c;
  const T d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const T vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const T va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const T denom = va + vb + vc;
  if (!(denom > 0)) return a;
  return a + ab * (vb / denom) + ac * (vc / denom);
}

namespace detail {

inline int auto_map_size(const LightFitOptions& o, double tan_half_fov, int max_size) {
  if (!(o.camera_tan_per_pixel > 0)) return kAutoMinSize;
  const double want = kTexelsPerCameraPixel * tan_half_fov / o.camera_tan_per_pixel;
  return static_cast<int>(std::clamp(std::ceil(want), double(kAutoMinSize), double(max_size)));
}

}  // namespace detail

// The distance from `pos` to the nearest triangle of `meshes` (infinity when they have none): how
// close a light sits to a surface, which a shadow camera's near plane must not clip. Brute force
// over every triangle, in double.
inline double nearest_triangle_distance(const Vec3<double>& pos, std::span<const TriangleMesh<float>* const> meshes) {
  double closest = std::numeric_limits<double>::infinity();
  for (const TriangleMesh<float>* m : meshes)
    for (const auto& t : m->triangles) {
      const Vec3<double> a = m->positions[t[0]].cast<double>(), b = m->positions[t[1]].cast<double>(),
                         c = m->positions[t[2]].cast<double>();
      closest = std::min(closest, (closest_point_on_triangle(pos, a, b, c) - pos).norm());
    }
  return closest;
}

namespace detail {

// A cube's near and far planes around `pos` for faces opened to tan_half (see the top of the file).
inline std::pair<double, double> cube_depth_range(const Vec3<double>& pos,
                                                  std::span<const TriangleMesh<float>* const> meshes, double tan_half) {
  const double closest = nearest_triangle_distance(pos, meshes);
  double farthest = 0;
  for (const TriangleMesh<float>* m : meshes)
    for (const Vec3<float>& v : m->positions) farthest = std::max(farthest, (v.cast<double>() - pos).norm());
  const double far = std::max(farthest * 1.01, 1e-6);
  double near = 0.99 * closest / std::sqrt(1.0 + 2.0 * tan_half * tan_half);
  // The light touching a surface: geometry nearer than far · 1e-4 is clipped (a documented limit;
  // it would need more depth precision than 24 bits have).
  near = std::clamp(near, far * 1e-4, far * 0.5);
  return {near, far};
}

inline LightFit fit_cube(const RunConvention& conv, const Vec3<double>& pos,
                         std::span<const TriangleMesh<float>* const> meshes, const LightFitOptions& o) {
  LightFit fit;
  fit.cube = true;
  // The size first: the margin is counted in texels.
  fit.size = o.map_size ? o.map_size : auto_map_size(o, 1.0, kCubeAutoMaxSize);
  const double tan_half = 1.0 / (1.0 - 2.0 * kCubeMarginTexels / fit.size);
  const auto [near, far] = cube_depth_range(pos, meshes, tan_half);
  const Vec3<double> axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3<double>& axis : axes) {
    LightView v;
    const Vec3<double> up = axis.y() != 0.0 ? Vec3<double>(0, 0, 1) : Vec3<double>(0, 1, 0);
    v.view = view_from_scene<double>(conv, pos, pos + axis, up).value();
    v.projection = perspective<double>(2.0 * std::atan(tan_half), 1.0, near, far, conv.clip).value();
    // A mesh is left out of a face when all its vertices lie outside one plane of the face's
    // pyramid (then so does their convex hull); a face with no mesh left is empty.
    const Vec3<double> right = axis.cross(up);
    const Vec3<double> sides[4] = {right, -right, up, -up};
    v.empty = true;
    for (const TriangleMesh<float>* m : meshes) {
      bool out_behind = true, out_side[4] = {true, true, true, true};
      for (const Vec3<float>& pf : m->positions) {
        const Vec3<double> d = pf.cast<double>() - pos;
        const double depth = d.dot(axis);
        if (depth > 0) out_behind = false;
        for (int k = 0; k < 4; ++k)
          if (d.dot(sides[k]) <= tan_half * depth) out_side[k] = false;
      }
      const bool outside = out_behind || out_side[0] || out_side[1] || out_side[2] || out_side[3];
      v.draw.push_back(!outside);
      if (!outside) v.empty = false;
    }
    fit.views.push_back(std::move(v));
  }
  return fit;
}

}  // namespace detail

// The six views of an OpenGL cube map around a light at `pos`, for engines that render their own
// cube: exactly 90 degrees (no guard band), in GL_TEXTURE_CUBE_MAP_POSITIVE_X + i order (+x, −x,
// +y, −y, +z, −z of scene space), each oriented as the OpenGL specification's cube-map face
// selection table has it (OpenGL 4.6, section 8.13, table 8.19): a direction r from the light in
// face i lands at NDC (sc / |ma|, tc / |ma|) of that table, so a face drawn through view i is read
// back by a cube-map lookup at the same texel. Right-handed conventions only (gl, gl-zo,
// reversed-z: a look-at's right is forward × up); near and far fitted to `meshes` as the pack's
// cubes are (the top of the file). Cost: a pass over the triangles and the vertices.
inline std::array<LightView, 6> gl_cube_map_views(const RunConvention& conv, const Vec3<double>& pos,
                                                  std::span<const TriangleMesh<float>* const> meshes) {
  const auto [near, far] = detail::cube_depth_range(pos, meshes, 1.0);
  // (forward, up) per face: right = forward × up is the table's sc axis, up its tc axis.
  static const Vec3<double> kFaces[6][2] = {{{1, 0, 0}, {0, -1, 0}}, {{-1, 0, 0}, {0, -1, 0}},
                                            {{0, 1, 0}, {0, 0, 1}},  {{0, -1, 0}, {0, 0, -1}},
                                            {{0, 0, 1}, {0, -1, 0}}, {{0, 0, -1}, {0, -1, 0}}};
  std::array<LightView, 6> views;
  for (int i = 0; i < 6; ++i) {
    views[i].view = view_from_scene<double>(conv, pos, pos + kFaces[i][0], kFaces[i][1]).value();
    views[i].projection = perspective<double>(std::numbers::pi / 2.0, 1.0, near, far, conv.clip).value();
  }
  return views;
}

// The shadow-map views of the light L (homogeneous) over `meshes` (world space), in `conv`.
inline Result<LightFit> fit_light(const RunConvention& conv, const Vec4<double>& L,
                                  std::span<const TriangleMesh<float>* const> meshes, const LightFitOptions& o = {}) {
  if (!L.allFinite()) return Error::NonFinite;
  Vec3<double> lo = Vec3<double>::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const TriangleMesh<float>* m : meshes)
    for (const Vec3<float>& v : m->positions) {
      lo = lo.cwiseMin(v.cast<double>());
      hi = hi.cwiseMax(v.cast<double>());
    }
  if (!(lo.x() <= hi.x())) return Error::EmptyMesh;
  if (!lo.allFinite() || !hi.allFinite()) return Error::NonFinite;
  const Vec3<double> centre = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * (hi - lo).norm(), 1e-6);
  LightFit fit;
  LightView v;
  if (L.w() == 0.0) {
    if (!(L.head<3>().norm() > 0)) return Error::NonFinite;
    const Vec3<double> toward = L.head<3>().normalized();
    const Vec3<double> eye = centre + toward * (2.0 * radius);
    v.view = view_from_scene<double>(conv, eye, centre, least_aligned_axis(toward)).value();
    v.projection = ortho_for<double>(conv, -radius, radius, -radius, radius, 0.5 * radius, 3.5 * radius).value();
    fit.views.push_back(std::move(v));
    fit.size = o.map_size ? o.map_size : kDirectionalAutoSize;
    return fit;
  }
  const Vec3<double> pos = L.head<3>() / L.w();
  Vec3<double> axis = centre - pos;
  if (axis.norm() < 1e-9 * radius) return detail::fit_cube(conv, pos, meshes, o);  // the light at the box's centre
  axis.normalize();
  double max_angle = 0, min_depth = std::numeric_limits<double>::infinity(), max_depth = 0;
  for (int c = 0; c < 8; ++c) {
    const Vec3<double> corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
    const Vec3<double> d = corner - pos;
    const double along = d.dot(axis);
    const double across = (d - along * axis).norm();
    max_angle = std::max(max_angle, std::atan2(across, along));
    min_depth = std::min(min_depth, along);
    max_depth = std::max(max_depth, along);
  }
  // The box does not fit in one frustum of at most kMaxSingleFovDeg (the light inside it or
  // beside it): a cube, which sees every direction.
  if (2.0 * max_angle * 1.02 > kMaxSingleFovDeg * std::numbers::pi / 180.0 || !(min_depth > 0.0))
    return detail::fit_cube(conv, pos, meshes, o);
  const double fov = std::max(2.0 * max_angle * 1.02, 1e-3);
  const double far = std::max(max_depth, 1e-3 * radius) * 1.01;
  const double near = std::max(min_depth * 0.99, far * 1e-3);
  v.view = view_from_scene<double>(conv, pos, pos + axis, least_aligned_axis(axis)).value();
  v.projection = perspective<double>(fov, 1.0, near, far, conv.clip).value();
  fit.views.push_back(std::move(v));
  fit.size = o.map_size ? o.map_size : detail::auto_map_size(o, std::tan(fov / 2.0), kAutoMaxSize);
  return fit;
}

}  // namespace shadowref
