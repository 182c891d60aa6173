// shadow_map.cpp — shadow mapping: Williams 1978, "Casting curved shadows on curved surfaces".
//
// Per light, the scene's depth is rendered from the light into a texture; each camera fragment
// is then mapped through B · P_light · V_light (mathlib's shadow_bias_matrix, projections, look_at)
// and compared with the stored depth. Three variants:
//   shadowmap        a GL_DEPTH_COMPONENT24 texture, GL_COMPARE_REF_TO_TEXTURE with GL_LEQUAL
//                    through a sampler2DShadow, one nearest tap;
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
// The light frustum: perspective from point and spot lights (and rect lights, at their centre),
// aimed at the centre of the scene's bounding box and opened to hold all eight corners (up to
// kMaxFovDeg: a light inside the box sees only part of it); orthographic for directional lights,
// fitted to the bounding sphere. A fragment outside the map, or behind the light, counts as lit:
// the map knows of no occluder there (a documented limit of one map per light).
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

struct LightCamera {
  Mat4<double> view;
  Mat4<double> projection;
  int size = 2048;  // texels per side
};

constexpr int kAutoMinSize = 1024;
constexpr int kAutoMaxSize = 8192;
constexpr int kDirectionalAutoSize = 2048;
constexpr double kTexelsPerPixel = 3.0;  // texels per camera pixel, in angle at the view centres

Vec3<double> up_for(const Vec3<double>& forward) {
  // The world axis least aligned with the view direction: never parallel to it.
  const Vec3<double> a = forward.cwiseAbs();
  if (a.x() <= a.y() && a.x() <= a.z()) return Vec3<double>(1, 0, 0);
  if (a.y() <= a.z()) return Vec3<double>(0, 1, 0);
  return Vec3<double>(0, 0, 1);
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
  if (l.w() == 0.0) {
    const Vec3<double> toward = l.head<3>().normalized();
    const Vec3<double> eye = centre + toward * (2.0 * radius);
    lc.view = look_at<double>(eye, centre, up_for(toward)).value();
    lc.projection = ortho<double>(-radius, radius, -radius, radius, 0.5 * radius, 3.5 * radius, kOpenGL).value();
    lc.size = frame.options.shadow_map_size ? frame.options.shadow_map_size : kDirectionalAutoSize;
    return lc;
  }
  const Vec3<double> pos = l.head<3>() / l.w();
  Vec3<double> axis = centre - pos;
  if (axis.norm() < 1e-9 * radius) axis = Vec3<double>(0, -1, 0);  // light at the centre: look down
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
  const double fov = std::clamp(2.0 * max_angle * 1.02, 1e-3, kMaxFovDeg * std::numbers::pi / 180.0);
  const double far = std::max(max_depth, 1e-3 * radius) * 1.01;
  const double near = std::max(min_depth * 0.99, far * 1e-3);
  lc.view = look_at<double>(pos, pos + axis, up_for(axis)).value();
  lc.projection = perspective<double>(fov, 1.0, near, far, kOpenGL).value();
  if (frame.options.shadow_map_size) {
    lc.size = frame.options.shadow_map_size;
  } else {
    // Angle per texel at the map's centre: 2 tan(fov / 2) / size; per camera pixel:
    // 2 tan(fovy / 2) / height. Ask for kTexelsPerPixel texels per pixel.
    const double cam = std::tan(frame.scene.camera.fovy_deg * std::numbers::pi / 360.0) / frame.height();
    const double want = kTexelsPerPixel * std::tan(fov / 2.0) / cam;
    lc.size = static_cast<int>(std::clamp(std::ceil(want), double(kAutoMinSize), double(kAutoMaxSize)));
  }
  return lc;
}

// One light's map: the texture and the matrix that maps world points into it.
struct LightMap {
  const GlFunctions* gl = nullptr;
  GLuint texture = 0;
  int size = 0;
  Mat4<float> shadow_from_world;  // B · P_light · V_light
  LightMap() = default;
  LightMap(LightMap&& o) noexcept : gl(o.gl), texture(o.texture), size(o.size), shadow_from_world(o.shadow_from_world) {
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
  const Mat4<float> light_clip = to_float(Mat4<double>(lc.projection * lc.view));
  LightMap map;
  map.gl = &gl;
  map.size = size;
  map.shadow_from_world = to_float(Mat4<double>(shadow_bias_matrix<double>(DepthRange::NegOneToOne) *
                                                lc.projection * lc.view));

  gl.GenTextures(1, &map.texture);
  gl.BindTexture(GL_TEXTURE_2D, map.texture);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float far_border[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // depth 1 / packed 0xFFFFFF: nothing occludes
  gl.TexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, far_border);

  GLuint fbo = 0, depth_rb = 0;
  gl.GenFramebuffers(1, &fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  if (variant == Variant::Rgba8) {
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, size, size, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, map.texture, 0);
    // A plain depth buffer still picks the nearest surface; only the colour target is sampled.
    gl.GenRenderbuffers(1, &depth_rb);
    gl.BindRenderbuffer(GL_RENDERBUFFER, depth_rb);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, size, size);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
    gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
  } else {
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, map.texture, 0);
    gl.DrawBuffer(GL_NONE);
  }
  gl.ReadBuffer(GL_NONE);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("the shadow-map framebuffer is incomplete");

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
  set_matrix(gl, p.clip_from_world, light_clip);
  if (variant == Variant::Rgba8) {
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.Uniform1f(p.offset_factor, kOffsetFactor);
    gl.Uniform1f(p.offset_units, kOffsetUnits);
  } else {
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(kOffsetFactor, kOffsetUnits);
    gl.Uniform4f(p.colour, 0, 0, 0, 0);
  }
  gl.CullFace(GL_FRONT);
  for (std::size_t i = 0; i < frame.objects.size(); ++i) {
    if (frame.closed[i]) gl.Enable(GL_CULL_FACE);
    else gl.Disable(GL_CULL_FACE);
    frame.objects[i].draw();
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
  gl.BindTexture(GL_TEXTURE_2D, map.texture);
  gl.ActiveTexture(GL_TEXTURE0);
  const Program& p = frame.programs.surface;
  gl.UseProgram(p.id);
  const float texel = 1.0f / static_cast<float>(map.size);
  gl.Uniform2f(p.texel, texel, texel);
}

void unbind_maps(const GlFunctions& gl) {
  gl.ActiveTexture(GL_TEXTURE1);
  gl.BindTexture(GL_TEXTURE_2D, 0);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, 0);
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
