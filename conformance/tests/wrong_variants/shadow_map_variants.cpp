// shadow_map_variants.cpp — Williams shadow maps done wrong, two ways (the right version is
// conformance/renderer/shadow_map.cpp):
//   shadowmap-without-bias   the camera fragment mapped through P_light · V_light without the bias
//                            matrix B: clip-space −1..1 read as texture coordinates and depth 0..1;
//   shadowmap-compare-reversed  GL_GEQUAL instead of GL_LEQUAL: lit and shadowed swap.
// The light camera here is a plain fit (perspective from the light toward the scene's bounding box,
// orthographic for a directional light) at a fixed 2048² map: enough to tell the bugs apart.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "frame.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/shadow_map.hpp"
#include "shadowref/view.hpp"
#include "wrong_variants.hpp"

namespace shadowref::wrong {
namespace {

using namespace shadowref::renderer;

constexpr int kSize = 2048;

Vec3<double> up_for(const Vec3<double>& f) {
  const Vec3<double> a = f.cwiseAbs();
  if (a.x() <= a.y() && a.x() <= a.z()) return Vec3<double>(1, 0, 0);
  if (a.y() <= a.z()) return Vec3<double>(0, 1, 0);
  return Vec3<double>(0, 0, 1);
}

// P_light · V_light.
Mat4<double> light_clip(const Frame& frame, std::size_t i) {
  const auto box = scene::bounds(frame.scene);
  const Vec3<double> centre = 0.5 * (box[0] + box[1]);
  const double radius = std::max(0.5 * (box[1] - box[0]).norm(), 1e-6);
  const Vec4<double> l = frame.light(i);
  if (l.w() == 0.0) {
    const Vec3<double> toward = l.head<3>().normalized();
    const Mat4<double> v = look_at<double>(centre + toward * (2.0 * radius), centre, up_for(toward)).value();
    return ortho<double>(-radius, radius, -radius, radius, 0.5 * radius, 3.5 * radius, kOpenGL).value() * v;
  }
  const Vec3<double> pos = l.head<3>() / l.w();
  Vec3<double> axis = centre - pos;
  if (axis.norm() < 1e-9 * radius) axis = Vec3<double>(0, -1, 0);
  axis.normalize();
  double max_angle = 0, min_depth = std::numeric_limits<double>::infinity(), max_depth = 0;
  for (int c = 0; c < 8; ++c) {
    const Vec3<double> d = Vec3<double>((c & 1) ? box[1].x() : box[0].x(), (c & 2) ? box[1].y() : box[0].y(),
                                        (c & 4) ? box[1].z() : box[0].z()) - pos;
    const double along = d.dot(axis);
    max_angle = std::max(max_angle, std::atan2((d - along * axis).norm(), along));
    min_depth = std::min(min_depth, along);
    max_depth = std::max(max_depth, along);
  }
  const double fov = std::clamp(2.0 * max_angle * 1.02, 1e-3, 160.0 * std::numbers::pi / 180.0);
  const double far = std::max(max_depth, 1e-3 * radius) * 1.01;
  const double near = std::max(min_depth * 0.99, far * 1e-3);
  return perspective<double>(fov, 1.0, near, far, kOpenGL).value() * look_at<double>(pos, pos + axis, up_for(axis)).value();
}

void shadow_map(Frame& frame, bool bias_matrix, GLenum compare) {
  const GlFunctions& gl = frame.gl;
  const Mat4<float> clip = frame.camera_clip(CameraDepth::Scene);
  const Program& p = frame.programs.surface;
  for (std::size_t i = 0; i < frame.scene.lights.size(); ++i) {
    const Mat4<double> lc = light_clip(frame, i);
    GLuint tex = 0, fbo = 0;
    gl.GenTextures(1, &tex);
    gl.BindTexture(GL_TEXTURE_2D, tex);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, kSize, kSize, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, static_cast<GLint>(compare));  // GL_LEQUAL when right
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, tex, 0);
    gl.DrawBuffer(GL_NONE);
    gl.ReadBuffer(GL_NONE);
    gl.Viewport(0, 0, kSize, kSize);
    gl.DepthMask(GL_TRUE);
    gl.ClearDepth(1.0);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_STENCIL_TEST);
    gl.Disable(GL_BLEND);
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(2.0f, 8.0f);
    gl.UseProgram(frame.programs.flat.id);
    set_matrix(gl, frame.programs.flat.clip_from_world, to_float(lc));
    gl.Uniform4f(frame.programs.flat.colour, 0, 0, 0, 0);
    for (const GpuMesh& m : frame.objects) m.draw();
    gl.Disable(GL_POLYGON_OFFSET_FILL);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.DeleteFramebuffers(1, &fbo);

    // THE BUG when bias_matrix is false: no B, so NDC −1..1 is read as texture coordinates.
    const Mat4<double> shadow_from_world = bias_matrix ? Mat4<double>(shadow_bias_matrix<double>(DepthRange::NegOneToOne) * lc) : lc;
    frame.bind_target(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, static_cast<float>(outputs::kMaskNoSurface) / 255.0f);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, tex);
    gl.UseProgram(p.id);
    gl.Uniform2f(p.texel, 1.0f / kSize, 1.0f / kSize);
    set_matrix(gl, p.clip_from_world, clip);
    set_matrix(gl, p.shadow_from_world, to_float(shadow_from_world));
    gl.Uniform1i(p.mode, 2);
    gl.Uniform1i(p.shadow, 1);
    const Vec4<float> l = frame.light(i).cast<float>();
    gl.Uniform4f(p.light, l.x(), l.y(), l.z(), l.w());
    for (const GpuMesh& m : frame.objects) m.draw();
    frame.result.masks.push_back(frame.read_grey());
    gl.BindTexture(GL_TEXTURE_2D, 0);
    gl.DeleteTextures(1, &tex);
  }
  frame.ambient_pass(clip);
  frame.result.shaded = frame.read_rgb();
}

}  // namespace

void render_shadowmap_without_bias(Frame& frame) { shadow_map(frame, /*bias_matrix=*/false, GL_LEQUAL); }
void render_shadowmap_compare_reversed(Frame& frame) { shadow_map(frame, /*bias_matrix=*/true, GL_GEQUAL); }

}  // namespace shadowref::wrong
