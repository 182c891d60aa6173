// shadow_map.cpp — shadow mapping: Williams 1978, "Casting curved shadows on curved surfaces".
//
// Per light, the scene's depth is rendered from the light into a texture; each camera fragment
// is then mapped through B · P_light · V_light (mathlib's shadow_bias_matrix, projections, look_at)
// and compared with the stored depth. Three variants:
//   shadowmap        a GL_DEPTH_COMPONENT24 texture, GL_COMPARE_REF_TO_TEXTURE with GL_LEQUAL
//                    through a sampler2DArrayShadow (one layer, or six for a cube), one nearest tap;
//   shadowmap-pcf    percentage-closer filtering (Reeves, Salesin & Cook 1987): a 3 × 3 box of
//                    nearest compares one texel apart, equal weights; the mask calls a pixel lit
//                    when at least half of the 9 taps are (shaded.png keeps the fraction);
//   shadowmap-rgba8  no depth texture: the light pass packs its depth into an RGBA8 colour target
//                    (mathlib/depth_packing.hpp, mirrored in GLSL) and the camera pass unpacks and
//                    compares 24-bit integers — the method of hardware without depth textures.
// Bias: the depth pass culls front faces of closed casters (the map then holds back faces, so a
// lit surface is never compared against itself) and uses glPolygonOffset(kOffsetFactor,
// kOffsetUnits); open meshes (a ground quad, a leaf) are drawn two-sided, since culling would
// drop whichever side faces the light. The RGBA8 pass applies the same offset in its shader.
// The light's views (fit_light), one map layer each:
//   * directional light: one orthographic view fitted to the scene's bounding sphere;
//   * point, spot and rect lights (a rect at its centre): one perspective view aimed at the
//     centre of the scene's bounding box, opened to hold all eight corners, when that takes at
//     most kMaxFovDeg; otherwise a CUBE of six 90-degree views (Gerasimov 2004, "Omnidirectional
//     shadow mapping", GPU Gems ch. 12), stored as six layers of a 2D array texture, the face
//     picked per fragment by the largest component of (p − light), like a cube-map lookup.
//   Why the cube: a single perspective map covers less than a half-space around the light. With
//   the light inside the scene's bounds (or beside them), the old code clamped the frustum to
//   kMaxFovDeg, so geometry outside it counted as lit (false light: 100 decided pixels of 128² in
//   a scene with a box beside the light; 10 in two_lights.json), and it put the near plane at
//   far · 1e-3 (the box reached behind the light), crushing 24-bit depth toward 1 where the
//   self-comparison of surfaces lives (issue 6: from the light's own position, random scenes
//   showed shadowed pixels). The cube covers every direction, and its near plane is the true
//   distance to the closest triangle divided by sqrt(1 + 2 tan²) (no point of a face's frustum
//   lies farther than that factor from the light for its depth), so depth keeps its precision.
//   Spot lights take the same path as point lights, not their cone: the mask is the visibility of
//   the light's position, with the cone only scaling the shaded picture (as in the reference).
//   Faces that no geometry reaches are cleared, not drawn, and each face draws only the objects
//   that reach it. Each face is opened kCubeMarginTexels wider than 90 degrees, so that PCF taps
//   next to a face's edge stay inside the face.
//   The single map is kept where it fits: it costs one pass instead of up to six, and the
//   catalogue's scenes with the light outside their bounds keep their results.
// A fragment outside the single map, or behind its light, counts as lit: the map knows of no
// occluder there (directional maps hold the whole bounding sphere; a point light's single map
// holds the whole box, so only geometry-free directions fall outside).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "frame.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/scene/scene.hpp"
#include "shadowref/shadow_map.hpp"
#include "shadowref/view.hpp"

namespace shadowref::renderer {
namespace {

// Slope-scaled and constant offset of the depth pass, in glPolygonOffset's units (the constant in
// steps of the 24-bit depth): large enough for the two-sided ground's self-comparison at grazing
// light, small enough not to detach shadows visibly at the catalogue's scale.
constexpr float kOffsetFactor = 2.0f;
constexpr float kOffsetUnits = 8.0f;
constexpr double kMaxFovDeg = 160.0;

enum class Variant { Depth, Pcf, Rgba8 };

// One view of a light: one layer of its map.
struct LightView {
  Mat4<double> view;
  Mat4<double> projection;
  bool empty = false;  // no geometry in this view (a cube face): cleared, not drawn
  std::vector<bool> draw;  // per object: may reach this view (empty: every object)
};

struct LightCamera {
  std::vector<LightView> views;  // 1, or 6 for a cube (+x, −x, +y, −y, +z, −z: the shader's order)
  bool cube = false;
  int size = 2048;  // texels per side of every layer
};

constexpr int kAutoMinSize = 1024;
constexpr int kAutoMaxSize = 8192;
constexpr int kCubeAutoMaxSize = 2048;  // per face: six of them
constexpr int kDirectionalAutoSize = 2048;
constexpr double kTexelsPerPixel = 3.0;  // texels per camera pixel, in angle at the view centres
constexpr double kCubeMarginTexels = 3.0;  // each face reaches this far beyond 90 degrees (PCF taps)

Vec3<double> up_for(const Vec3<double>& forward) {
  // The world axis least aligned with the view direction: never parallel to it.
  const Vec3<double> a = forward.cwiseAbs();
  if (a.x() <= a.y() && a.x() <= a.z()) return Vec3<double>(1, 0, 0);
  if (a.y() <= a.z()) return Vec3<double>(0, 1, 0);
  return Vec3<double>(0, 0, 1);
}

// The point of triangle abc closest to p (Ericson, "Real-Time Collision Detection", 5.1.5).
Vec3<double> closest_on_triangle(const Vec3<double>& p, const Vec3<double>& a, const Vec3<double>& b,
                                 const Vec3<double>& c) {
  const Vec3<double> ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3<double> bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3<double> cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = va + vb + vc;
  if (!(denom > 0)) return a;  // degenerate (zero-area) triangle: a vertex is close enough
  return a + ab * (vb / denom) + ac * (vc / denom);
}

// Automatic size: kTexelsPerPixel texels per camera pixel in angle, at the centres of both views
// (angle per texel at the map's centre: 2 tan(fov / 2) / size; per camera pixel: 2 tan(fovy / 2) / height).
int auto_size(const Frame& frame, double tan_half_fov, int max_size) {
  const double cam = std::tan(frame.scene.camera.fovy_deg * std::numbers::pi / 360.0) / frame.height();
  const double want = kTexelsPerPixel * tan_half_fov / cam;
  return static_cast<int>(std::clamp(std::ceil(want), double(kAutoMinSize), double(max_size)));
}

// Six 90-degree views (plus a margin of kCubeMarginTexels) around the light at `pos`.
LightCamera fit_cube(const Frame& frame, const Vec3<double>& pos) {
  LightCamera lc;
  lc.cube = true;
  // The size first: the margin is counted in texels.
  lc.size = frame.options.shadow_map_size ? frame.options.shadow_map_size : auto_size(frame, 1.0, kCubeAutoMaxSize);
  const double tan_half = 1.0 / (1.0 - 2.0 * kCubeMarginTexels / lc.size);
  // Near: no point of a face's frustum lies closer to the light than its depth times
  // sqrt(1 + 2 tan²), so the closest triangle's distance divided by that is in front of every
  // face's geometry. Far: the farthest vertex (the geometry lies in the vertices' convex hull).
  double closest = std::numeric_limits<double>::infinity(), farthest = 0;
  for (const scene::Object& o : frame.scene.objects) {
    for (const auto& t : o.mesh.triangles) {
      const Vec3<double> a = o.mesh.positions[t[0]].cast<double>(), b = o.mesh.positions[t[1]].cast<double>(),
                         c = o.mesh.positions[t[2]].cast<double>();
      closest = std::min(closest, (closest_on_triangle(pos, a, b, c) - pos).norm());
    }
    for (const Vec3<float>& v : o.mesh.positions) farthest = std::max(farthest, (v.cast<double>() - pos).norm());
  }
  const double far = std::max(farthest * 1.01, 1e-6);
  double near = 0.99 * closest / std::sqrt(1.0 + 2.0 * tan_half * tan_half);
  // The light touching a surface: geometry nearer than far · 1e-4 is clipped (a documented limit;
  // it would need more depth precision than 24 bits have).
  near = std::clamp(near, far * 1e-4, far * 0.5);
  const Vec3<double> axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3<double>& axis : axes) {
    LightView v;
    const Vec3<double> up = axis.y() != 0.0 ? Vec3<double>(0, 0, 1) : Vec3<double>(0, 1, 0);
    v.view = look_at<double>(pos, pos + axis, up).value();
    v.projection = perspective<double>(2.0 * std::atan(tan_half), 1.0, near, far, kOpenGL).value();
    // An object is left out of a face when all its vertices lie outside one plane of the face's
    // pyramid (then so does their convex hull); a face with no object left is empty.
    const Vec3<double> right = axis.cross(up);
    const Vec3<double> sides[4] = {right, -right, up, -up};
    v.empty = true;
    for (const scene::Object& o : frame.scene.objects) {
      bool out_behind = true, out_side[4] = {true, true, true, true};
      for (const Vec3<float>& pf : o.mesh.positions) {
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
    lc.views.push_back(v);
  }
  return lc;
}

LightCamera fit_light(const Frame& frame, std::size_t light_index) {
  const auto box = scene::bounds(frame.scene);
  const Vec3<double> centre = 0.5 * (box[0] + box[1]);
  const double radius = std::max(0.5 * (box[1] - box[0]).norm(), 1e-6);
  const Vec4<double> l = frame.light(light_index);
  std::vector<Vec3<double>> corners;
  for (int c = 0; c < 8; ++c)
    corners.emplace_back((c & 1) ? box[1].x() : box[0].x(), (c & 2) ? box[1].y() : box[0].y(),
                         (c & 4) ? box[1].z() : box[0].z());
  LightCamera lc;
  LightView v;
  if (l.w() == 0.0) {
    const Vec3<double> toward = l.head<3>().normalized();
    const Vec3<double> eye = centre + toward * (2.0 * radius);
    v.view = look_at<double>(eye, centre, up_for(toward)).value();
    v.projection = ortho<double>(-radius, radius, -radius, radius, 0.5 * radius, 3.5 * radius, kOpenGL).value();
    lc.views.push_back(v);
    lc.size = frame.options.shadow_map_size ? frame.options.shadow_map_size : kDirectionalAutoSize;
    return lc;
  }
  const Vec3<double> pos = l.head<3>() / l.w();
  Vec3<double> axis = centre - pos;
  if (axis.norm() < 1e-9 * radius) return fit_cube(frame, pos);  // the light at the box's centre
  axis.normalize();
  double max_angle = 0, min_depth = std::numeric_limits<double>::infinity(), max_depth = 0;
  for (const Vec3<double>& c : corners) {
    const Vec3<double> d = c - pos;
    const double along = d.dot(axis);
    const double across = (d - along * axis).norm();
    max_angle = std::max(max_angle, std::atan2(across, along));
    min_depth = std::min(min_depth, along);
    max_depth = std::max(max_depth, along);
  }
  // The box does not fit in one frustum of at most kMaxFovDeg (the light inside it or beside it):
  // a cube, which sees every direction.
  if (2.0 * max_angle * 1.02 > kMaxFovDeg * std::numbers::pi / 180.0 || !(min_depth > 0.0)) return fit_cube(frame, pos);
  const double fov = std::max(2.0 * max_angle * 1.02, 1e-3);
  const double far = std::max(max_depth, 1e-3 * radius) * 1.01;
  const double near = std::max(min_depth * 0.99, far * 1e-3);
  v.view = look_at<double>(pos, pos + axis, up_for(axis)).value();
  v.projection = perspective<double>(fov, 1.0, near, far, kOpenGL).value();
  lc.views.push_back(v);
  lc.size = frame.options.shadow_map_size ? frame.options.shadow_map_size : auto_size(frame, std::tan(fov / 2.0), kAutoMaxSize);
  return lc;
}

// One light's map: the texture (a 2D array, one layer per view) and the matrices that map world
// points into it.
struct LightMap {
  const GlFunctions* gl = nullptr;
  GLuint texture = 0;
  int size = 0;
  bool cube = false;
  Mat4<float> shadow_from_world;  // B · P_light · V_light (the single view)
  std::vector<Mat4<float>> face_from_world;  // the same per cube face
  LightMap() = default;
  LightMap(LightMap&& o) noexcept
      : gl(o.gl), texture(o.texture), size(o.size), cube(o.cube), shadow_from_world(o.shadow_from_world),
        face_from_world(std::move(o.face_from_world)) {
    o.texture = 0;
  }
  LightMap(const LightMap&) = delete;
  LightMap& operator=(const LightMap&) = delete;
  LightMap& operator=(LightMap&&) = delete;
  ~LightMap() {
    if (texture) gl->DeleteTextures(1, &texture);
  }
};

LightMap render_light_map(const Frame& frame, std::size_t light_index, Variant variant) {
  const GlFunctions& gl = frame.gl;
  const LightCamera lc = fit_light(frame, light_index);
  const int size = lc.size;
  const auto layers = static_cast<GLsizei>(lc.views.size());
  LightMap map;
  map.gl = &gl;
  map.size = size;
  map.cube = lc.cube;
  const Mat4<double> bias = shadow_bias_matrix<double>(DepthRange::NegOneToOne);
  for (const LightView& v : lc.views) map.face_from_world.push_back(to_float(Mat4<double>(bias * v.projection * v.view)));
  map.shadow_from_world = map.face_from_world[0];

  gl.GenTextures(1, &map.texture);
  gl.BindTexture(GL_TEXTURE_2D_ARRAY, map.texture);
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float far_border[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // depth 1 / packed 0xFFFFFF: nothing occludes
  gl.TexParameterfv(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BORDER_COLOR, far_border);

  GLuint fbo = 0, depth_rb = 0;
  gl.GenFramebuffers(1, &fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  if (variant == Variant::Rgba8) {
    gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, size, size, layers, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    // A plain depth buffer still picks the nearest surface; only the colour target is sampled.
    gl.GenRenderbuffers(1, &depth_rb);
    gl.BindRenderbuffer(GL_RENDERBUFFER, depth_rb);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, size, size);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
    gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
  } else {
    gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT24, size, size, layers, 0, GL_DEPTH_COMPONENT,
                  GL_UNSIGNED_INT, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl.DrawBuffer(GL_NONE);
  }
  gl.ReadBuffer(GL_NONE);

  gl.Viewport(0, 0, size, size);
  gl.DepthMask(GL_TRUE);
  gl.ClearDepth(1.0);
  gl.ClearColor(1.0f, 1.0f, 1.0f, 1.0f);  // = pack_depth_rgba8(1)
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.Disable(GL_STENCIL_TEST);
  gl.Disable(GL_BLEND);
  const Program& p = variant == Variant::Rgba8 ? frame.programs.packed_depth : frame.programs.flat;
  gl.UseProgram(p.id);
  if (variant == Variant::Rgba8) {
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.Uniform1f(p.offset_factor, kOffsetFactor);
    gl.Uniform1f(p.offset_units, kOffsetUnits);
  } else {
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(kOffsetFactor, kOffsetUnits);
    gl.Uniform4f(p.colour, 0, 0, 0, 0);
  }
  gl.CullFace(GL_FRONT);
  for (GLsizei layer = 0; layer < layers; ++layer) {
    const LightView& view = lc.views[static_cast<std::size_t>(layer)];
    gl.FramebufferTextureLayer(GL_FRAMEBUFFER, variant == Variant::Rgba8 ? GL_COLOR_ATTACHMENT0 : GL_DEPTH_ATTACHMENT,
                               map.texture, 0, layer);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("the shadow-map framebuffer is incomplete");
    gl.Clear(variant == Variant::Rgba8 ? GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT : GL_DEPTH_BUFFER_BIT);
    if (view.empty) continue;
    set_matrix(gl, p.clip_from_world, to_float(Mat4<double>(view.projection * view.view)));
    for (std::size_t i = 0; i < frame.objects.size(); ++i) {
      if (!view.draw.empty() && !view.draw[i]) continue;
      if (frame.closed[i]) gl.Enable(GL_CULL_FACE);
      else gl.Disable(GL_CULL_FACE);
      frame.objects[i].draw();
    }
  }
  gl.Disable(GL_CULL_FACE);
  gl.CullFace(GL_BACK);
  gl.Disable(GL_POLYGON_OFFSET_FILL);
  gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.DeleteFramebuffers(1, &fbo);
  if (depth_rb) gl.DeleteRenderbuffers(1, &depth_rb);
  return map;
}

void bind_map(const Frame& frame, const LightMap& map, Variant variant) {
  const GlFunctions& gl = frame.gl;
  gl.ActiveTexture(variant == Variant::Rgba8 ? GL_TEXTURE1 : GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D_ARRAY, map.texture);
  gl.ActiveTexture(GL_TEXTURE0);
  const Program& p = frame.programs.surface;
  gl.UseProgram(p.id);
  const float texel = 1.0f / static_cast<float>(map.size);
  gl.Uniform2f(p.texel, texel, texel);
  gl.Uniform1i(p.cube, map.cube ? 1 : 0);
  if (map.cube) {
    static_assert(!Mat4<float>::IsRowMajor);
    std::vector<float> m;
    for (const Mat4<float>& f : map.face_from_world) m.insert(m.end(), f.data(), f.data() + 16);
    gl.UniformMatrix4fv(p.cube_from_world, static_cast<GLsizei>(map.face_from_world.size()), GL_FALSE, m.data());
  }
}

void unbind_maps(const GlFunctions& gl) {
  gl.ActiveTexture(GL_TEXTURE1);
  gl.BindTexture(GL_TEXTURE_2D_ARRAY, 0);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

int shader_mode(Variant v) { return v == Variant::Depth ? 1 : v == Variant::Pcf ? 2 : 3; }

void render_variant(Frame& frame, Variant variant) {
  const GlFunctions& gl = frame.gl;
  const Mat4<float> clip = frame.camera_clip(CameraDepth::Scene);
  std::vector<LightMap> maps;
  for (std::size_t i = 0; i < frame.scene.lights.size(); ++i) maps.push_back(render_light_map(frame, i, variant));

  // Masks: one camera pass per light writing the 0/1 comparison; the clear colour is "no surface".
  const Program& p = frame.programs.surface;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    frame.bind_target(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, static_cast<float>(kMaskNoSurface) / 255.0f);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_BLEND);
    gl.Disable(GL_STENCIL_TEST);
    bind_map(frame, maps[i], variant);
    set_matrix(gl, p.clip_from_world, clip);
    set_matrix(gl, p.shadow_from_world, maps[i].shadow_from_world);
    gl.Uniform1i(p.mode, 2);
    gl.Uniform1i(p.shadow, shader_mode(variant));
    const Vec4<float> l = frame.light(i).cast<float>();
    gl.Uniform4f(p.light, l.x(), l.y(), l.z(), l.w());
    for (const GpuMesh& m : frame.objects) m.draw();
    frame.result.masks.push_back(frame.read_grey());
  }

  // The shaded picture: ambient once, then each light added where its map says lit.
  frame.ambient_pass(clip);
  for (std::size_t i = 0; i < maps.size(); ++i) {
    bind_map(frame, maps[i], variant);
    frame.light_pass(clip, i, shader_mode(variant), &maps[i].shadow_from_world);
  }
  unbind_maps(gl);
  frame.result.shaded = frame.read_rgb();
}

}  // namespace

void render_shadowmap(Frame& frame) { render_variant(frame, Variant::Depth); }
void render_shadowmap_pcf(Frame& frame) { render_variant(frame, Variant::Pcf); }
void render_shadowmap_rgba8(Frame& frame) { render_variant(frame, Variant::Rgba8); }

}  // namespace shadowref::renderer
