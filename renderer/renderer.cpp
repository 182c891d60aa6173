// renderer.cpp — the Renderer: context, shader programs, the scene's meshes on the GPU, the
// W × H target, the passes techniques share, and the timed frame loop.
#include "shadowref/renderer/renderer.hpp"

#include "shadowref/outputs/interruption.hpp"
#include "shadowref/outputs/limits.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "frame.hpp"
#include "shaders.hpp"
#include "shadow_maps/light_map.hpp"
#include "shadowref/outputs/shading.hpp"
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/adjacency.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/scene/camera.hpp"

namespace shadowref::renderer {

double RenderResult::median_frame_ms() const {
  if (frame_ms.empty()) return 0.0;
  std::vector<double> t = frame_ms;
  std::sort(t.begin(), t.end());
  const std::size_t n = t.size();
  return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

// ---------------------------------------------------------------------------------------------
// GPU meshes

GpuMesh::GpuMesh(const GlFunctions& gl, std::span<const Vec4<float>> vertices,
                 std::span<const std::uint32_t> indices, std::span<const Vec3<float>> normals,
                 std::span<const Vec4<float>> alpha_test, const scene::AlphaTexture* mask)
    : gl_(&gl) {
  gl.GenVertexArrays(1, &vao_);
  gl.BindVertexArray(vao_);
  gl.GenBuffers(1, &vbo_);
  gl.BindBuffer(GL_ARRAY_BUFFER, vbo_);
  // Eigen's Vec4<float> is four packed floats (no padding), so the span is the vertex array.
  static_assert(sizeof(Vec4<float>) == 4 * sizeof(float));
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size_bytes()), vertices.data(), GL_STATIC_DRAW);
  gl.VertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
  gl.EnableVertexAttribArray(0);
  if (!normals.empty()) {
    static_assert(sizeof(Vec3<float>) == 3 * sizeof(float));
    gl.GenBuffers(1, &nbo_);
    gl.BindBuffer(GL_ARRAY_BUFFER, nbo_);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(normals.size_bytes()), normals.data(), GL_STATIC_DRAW);
    gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    gl.EnableVertexAttribArray(1);
  }
  if (!alpha_test.empty()) {
    gl.GenBuffers(1, &abo_);
    gl.BindBuffer(GL_ARRAY_BUFFER, abo_);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(alpha_test.size_bytes()), alpha_test.data(), GL_STATIC_DRAW);
    gl.VertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
    gl.EnableVertexAttribArray(2);
  }
  if (mask) {
    // The 8-bit alphas as they are (R8UI, read by texelFetch: no filtering, no conversion); row 0
    // of the PNG is the texture's row 0, which v = 0 addresses (scene/alpha_mask.hpp).
    gl.GenTextures(1, &mask_);
    gl.ActiveTexture(kAlphaMaskUnit);
    gl.BindTexture(GL_TEXTURE_2D, mask_);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R8UI, mask->width, mask->height, 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE,
                  mask->alpha.data());
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    gl.ActiveTexture(GL_TEXTURE0);
  }
  if (!indices.empty()) {
    gl.GenBuffers(1, &ebo_);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size_bytes()), indices.data(),
                  GL_STATIC_DRAW);
    indexed_ = true;
    count_ = static_cast<GLsizei>(indices.size());
  } else {
    count_ = static_cast<GLsizei>(vertices.size());
  }
  gl.BindVertexArray(0);
}

GpuMesh::GpuMesh(GpuMesh&& o) noexcept
    : gl_(o.gl_), vao_(o.vao_), vbo_(o.vbo_), ebo_(o.ebo_), nbo_(o.nbo_), abo_(o.abo_), mask_(o.mask_),
      posed_vao_(o.posed_vao_), posed_vbo_(o.posed_vbo_), skin_vbo_(o.skin_vbo_), pose_block_(o.pose_block_),
      bind_block_(o.bind_block_), rigid_block_(o.rigid_block_), count_(o.count_), indexed_(o.indexed_) {
  o.vao_ = o.vbo_ = o.ebo_ = o.nbo_ = o.abo_ = o.mask_ = 0;
  o.posed_vao_ = o.posed_vbo_ = o.skin_vbo_ = o.pose_block_ = o.bind_block_ = 0;
  o.count_ = 0;
}

std::vector<unsigned char> skin_block_bytes(std::span<const Mat4<float>> joints, bool skinned) {
  static_assert(scene::kMaxSkinJoints == shaders::kSceneVertexJoints, "the Skin block holds scene::kMaxSkinJoints joints");
  constexpr std::size_t kMatrixBytes = 16 * sizeof(float);
  std::vector<unsigned char> bytes(shaders::kSceneVertexJoints * kMatrixBytes + 4 * sizeof(std::int32_t), 0);
  for (std::size_t j = 0; j < joints.size() && j < scene::kMaxSkinJoints; ++j)
    std::memcpy(bytes.data() + j * kMatrixBytes, joints[j].data(), kMatrixBytes);  // column-major, as std140's mat4
  const std::int32_t flag = skinned ? 1 : 0;
  std::memcpy(bytes.data() + shaders::kSceneVertexJoints * kMatrixBytes, &flag, sizeof flag);
  return bytes;
}

void GpuMesh::add_skin(const GpuSkinData& skin) {
  const GlFunctions& gl = *gl_;
  const auto block = [&](std::span<const Mat4<float>> m) {
    const std::vector<unsigned char> bytes = skin_block_bytes(m, true);
    GLuint b = 0;
    gl.GenBuffers(1, &b);
    gl.BindBuffer(GL_UNIFORM_BUFFER, b);
    gl.BufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(bytes.size()), bytes.data(), GL_STATIC_DRAW);
    gl.BindBuffer(GL_UNIFORM_BUFFER, 0);
    return b;
  };
  pose_block_ = block(skin.pose_matrices);
  bind_block_ = block(skin.bind_matrices);
  rigid_block_ = skin.rigid_block;
  // Joints then weights in one buffer, attributes 3 and 4 of the bind-pose vertex array.
  gl.BindVertexArray(vao_);
  gl.GenBuffers(1, &skin_vbo_);
  gl.BindBuffer(GL_ARRAY_BUFFER, skin_vbo_);
  const auto half = static_cast<GLsizeiptr>(skin.joints.size_bytes());
  std::vector<Vec4<float>> both(skin.joints.begin(), skin.joints.end());
  both.insert(both.end(), skin.weights.begin(), skin.weights.end());
  gl.BufferData(GL_ARRAY_BUFFER, 2 * half, both.data(), GL_STATIC_DRAW);
  gl.VertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
  gl.EnableVertexAttribArray(3);
  gl.VertexAttribPointer(4, 4, GL_FLOAT, GL_FALSE, 0, reinterpret_cast<const void*>(static_cast<std::uintptr_t>(half)));
  gl.EnableVertexAttribArray(4);
  // The CPU-posed vertices with the same normals and alpha attributes.
  gl.GenVertexArrays(1, &posed_vao_);
  gl.BindVertexArray(posed_vao_);
  gl.GenBuffers(1, &posed_vbo_);
  gl.BindBuffer(GL_ARRAY_BUFFER, posed_vbo_);
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(skin.posed_vertices.size_bytes()), skin.posed_vertices.data(), GL_STATIC_DRAW);
  gl.VertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
  gl.EnableVertexAttribArray(0);
  if (nbo_) {
    gl.BindBuffer(GL_ARRAY_BUFFER, nbo_);
    gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    gl.EnableVertexAttribArray(1);
  }
  if (abo_) {
    gl.BindBuffer(GL_ARRAY_BUFFER, abo_);
    gl.VertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
    gl.EnableVertexAttribArray(2);
  }
  if (ebo_) gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  gl.BindVertexArray(0);
}

GpuMesh::~GpuMesh() {
  for (GLuint* b : {&posed_vbo_, &skin_vbo_, &pose_block_, &bind_block_})
    if (*b) gl_->DeleteBuffers(1, b);
  if (posed_vao_) gl_->DeleteVertexArrays(1, &posed_vao_);
  if (ebo_) gl_->DeleteBuffers(1, &ebo_);
  if (nbo_) gl_->DeleteBuffers(1, &nbo_);
  if (abo_) gl_->DeleteBuffers(1, &abo_);
  if (mask_) gl_->DeleteTextures(1, &mask_);
  if (vbo_) gl_->DeleteBuffers(1, &vbo_);
  if (vao_) gl_->DeleteVertexArrays(1, &vao_);
}

void GpuMesh::draw(SkinDraw skin) const {
  if (count_ == 0) return;
  if (mask_) {
    gl_->ActiveTexture(kAlphaMaskUnit);
    gl_->BindTexture(GL_TEXTURE_2D, mask_);
    gl_->ActiveTexture(GL_TEXTURE0);
  }
  const bool gpu_skinned = skinned() && skin != SkinDraw::CpuPosed;
  if (gpu_skinned) gl_->BindBufferBase(GL_UNIFORM_BUFFER, kSkinBlockBinding, skin == SkinDraw::BindPose ? bind_block_ : pose_block_);
  gl_->BindVertexArray(skinned() && skin == SkinDraw::CpuPosed ? posed_vao_ : vao_);
  if (indexed_) gl_->DrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
  else gl_->DrawArrays(GL_TRIANGLES, 0, count_);
  gl_->BindVertexArray(0);
  if (gpu_skinned) gl_->BindBufferBase(GL_UNIFORM_BUFFER, kSkinBlockBinding, rigid_block_);
}

// ---------------------------------------------------------------------------------------------
// Shared helpers

void set_matrix(const GlFunctions& gl, GLint location, const Mat4<float>& m) {
  // Eigen's default storage is column-major, which is what GL expects with transpose = GL_FALSE.
  static_assert(!Mat4<float>::IsRowMajor);
  gl.UniformMatrix4fv(location, 1, GL_FALSE, m.data());
}

Mat4<float> to_float(const Mat4<double>& m) { return m.cast<float>(); }

namespace {

std::vector<std::uint8_t> flip_rows(const std::vector<std::uint8_t>& bottom_up, int w, int h, int channels) {
  std::vector<std::uint8_t> out(bottom_up.size());
  const std::size_t row = static_cast<std::size_t>(w) * static_cast<std::size_t>(channels);
  for (int y = 0; y < h; ++y)
    std::copy_n(bottom_up.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(h - 1 - y) * row),
                row, out.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * row));
  return out;
}

// The shared lighting model (outputs/shading.hpp): the ambient term is added once, the lights share
// the direct term so that a several-light scene is not washed out.
constexpr auto kAmbient = static_cast<float>(outputs::kAmbient);
constexpr auto kDirect = static_cast<float>(outputs::kDirect);


}  // namespace

// ---------------------------------------------------------------------------------------------
// Frame

GLenum gl_compare(DepthCompare c) {
  switch (c) {
    case DepthCompare::Less: return GL_LESS;
    case DepthCompare::LessEqual: return GL_LEQUAL;
    case DepthCompare::Greater: return GL_GREATER;
    case DepthCompare::GreaterEqual: return GL_GEQUAL;
    case DepthCompare::Equal: return GL_EQUAL;
    case DepthCompare::Always: return GL_ALWAYS;
  }
  return GL_LESS;
}

Mat4<double> Frame::camera_clip_double(CameraDepth depth) const {
  const Mat4<double>& pv = prepared.camera_for(depth).clip_from_scene;
  if (!faults().camera.half_pixel_offset) return pv;
  // One pixel is 2 / W in NDC: half a pixel right and half a pixel down (row 0 at the top).
  Mat4<double> shift = Mat4<double>::Identity();
  shift(0, 3) = 1.0 / width();
  shift(1, 3) = -1.0 / height();
  return shift * pv;
}

bool Frame::outside_camera_view(std::size_t i) const {
  // Gribb & Hartmann's planes from the rows of P · V: w ± x >= 0 and w ± y >= 0 inside. The x, y
  // and w rows are the same in every convention and every CameraDepth.
  const Mat4<double>& m = prepared.camera.clip_from_scene;
  const BoundingSphere<float>& s = prepared.casters[i].sphere;
  const Vec4<double> centre(s.center.x(), s.center.y(), s.center.z(), 1.0);
  for (int row = 0; row < 2; ++row)
    for (double sign : {1.0, -1.0}) {
      const Vec4<double> plane = m.row(3).transpose() + sign * m.row(row).transpose();
      const double n = plane.head<3>().norm();
      if (n > 0.0 && plane.dot(centre) / n < -static_cast<double>(s.radius)) return true;
    }
  return false;
}

float Frame::light_intensity() const {
  return kDirect / static_cast<float>(std::max<std::size_t>(1, scene.lights.size()));
}

bool Frame::any_masked() const {
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    if (masked(i)) return true;
  return false;
}

PassPrograms::PassPrograms(const Frame& frame, const std::function<const Program&(bool alpha_tested)>& build)
    : frame_(frame) {
  builds_[0] = &build(false);
  if (frame.any_masked()) builds_[1] = &build(true);
}

void PassPrograms::set(const std::function<void(const Program&)>& f) const {
  for (const Program* p : {builds_[1], builds_[0]}) {
    if (!p) continue;
    frame_.gl.UseProgram(p->id);
    f(*p);
    current_ = p;
  }
}

const Program& PassPrograms::use(std::size_t object) const {
  const Program* p = builds_[frame_.masked(object) ? 1 : 0];
  if (p != current_) {
    frame_.gl.UseProgram(p->id);
    current_ = p;
  }
  return *p;
}

void Frame::bind_target(GLbitfield clear_mask, float clear_grey) const {
  gl.BindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  gl.Viewport(0, 0, width(), height());
  gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl.DepthMask(GL_TRUE);
  gl.StencilMask(0xFF);
  gl.ClearColor(clear_grey, clear_grey, clear_grey, 1.0f);
  gl.ClearDepth(far_depth(convention()));
  gl.ClearStencil(0);
  if (clear_mask) gl.Clear(clear_mask);
}

void Frame::ambient_pass(const Mat4<float>& clip) const {
  bind_target(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  // The picture's background (linear, like everything drawn here; read_rgb encodes sRGB).
  gl.ClearColor(static_cast<float>(outputs::kBackground[0]), static_cast<float>(outputs::kBackground[1]),
                static_cast<float>(outputs::kBackground[2]), 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT);
  gl.Disable(GL_BLEND);
  gl.Disable(GL_STENCIL_TEST);
  gl.Disable(GL_CULL_FACE);
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(depth_nearer());
  const PassPrograms surface(*this, [&](bool tested) -> const Program& { return programs.surface(nullptr, tested); });
  surface.set([&](const Program& p) {
    set_matrix(gl, p.clip_from_world, clip);
    set_matrix(gl, p.shadow_from_world, Mat4<float>::Identity());
    gl.Uniform1i(p.mode, static_cast<int>(SurfaceMode::Ambient));
    gl.Uniform1f(p.ambient, kAmbient);
  });
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const auto& c = scene.objects[i].color;
    gl.Uniform3f(surface.use(i).albedo, c.x(), c.y(), c.z());
    objects[i].draw(skins);
  }
}

namespace {

// The bands of a light's camera pass (in_row_bands). The first holds kFirstBandPixels; each next one
// as many rows as take kBandSeconds at the last band's pace, at most four times its rows (a band of
// cheap sky says little of the walls below it) and kMaxBandPixels: the heaviest lookup we draw, PCSS
// on the large level, shades those in about 3 s on a busy 2-core machine's llvmpipe, a shadow map's
// plain lookup in tens of ms. Each band draws all the geometry again (about 20 ms for the level), so
// a 256 x 256 scene's pass is one band, the level's at its own 640 x 480 two.
constexpr long long kFirstBandPixels = 1 << 16;
constexpr long long kMaxBandPixels = 1 << 18;
constexpr double kBandSeconds = 0.5;

// Runs `draw` once per band of rows of the W x H target, scissored to it and finished before the
// next, and stops between bands on SIGINT / SIGTERM: one such pass may otherwise rasterise for a
// minute inside one read-back. The scissor keeps each pixel's fragments as they were, so the pass
// writes the same pixels as one draw would.
template <class Draw>
void in_row_bands(const GlFunctions& gl, int width, int height, const Draw& draw) {
  const long long w = std::max(1, width);
  int rows = static_cast<int>(std::max(1LL, kFirstBandPixels / w));
  if (rows >= height) {
    draw();
    return;
  }
  const int max_rows = static_cast<int>(std::max(1LL, kMaxBandPixels / w));
  gl.Enable(GL_SCISSOR_TEST);
  for (int y0 = 0; y0 < height && !outputs::interrupt_signal();) {
    const int n = std::min(rows, height - y0);
    const auto start = std::chrono::steady_clock::now();
    gl.Scissor(0, y0, width, n);
    draw();
    gl.Finish();
    y0 += n;
    const double seconds = std::max(1e-6, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    rows = static_cast<int>(std::clamp(n * kBandSeconds / seconds, 1.0, static_cast<double>(std::min(4 * n, max_rows))));
  }
  gl.Disable(GL_SCISSOR_TEST);
  outputs::throw_if_interrupted();
}

}  // namespace

void Frame::light_pass(const Mat4<float>& clip, std::size_t light_index, const PassPrograms* lookup_programs,
                       const Mat4<float>* shadow_from_world, bool masks) const {
  gl.BindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  gl.Viewport(0, 0, width(), height());
  gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl.DepthMask(GL_FALSE);
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_EQUAL);  // only the nearest surfaces, laid down by ambient_pass (same shader → same depth)
  gl.Enable(GL_BLEND);
  gl.BlendFunc(GL_ONE, GL_ONE);  // lights add up
  if (masks) {
    // The mask attachment too, cleared to "no surface" (green) and no light (red), and not blended:
    // each visible pixel is drawn once (GL_EQUAL) and keeps what the shader wrote.
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, kMaskAttachment};
    gl.DrawBuffers(2, buffers);
    const GLfloat clear[4] = {0.0f, static_cast<float>(outputs::kMaskNoSurface) / 255.0f, 0.0f, 1.0f};
    gl.ClearBufferfv(GL_COLOR, 1, clear);
    gl.Disablei(GL_BLEND, 1);
  }
  gl.Disable(GL_CULL_FACE);
  std::optional<PassPrograms> plain;
  if (!lookup_programs) plain.emplace(*this, [&](bool tested) -> const Program& { return programs.surface(nullptr, tested); });
  const PassPrograms& surface = lookup_programs ? *lookup_programs : *plain;
  const scene::Light& l = scene.lights[light_index];
  const Vec4<float> h = light(light_index).cast<float>();
  surface.set([&](const Program& p) {
    set_matrix(gl, p.clip_from_world, clip);
    set_matrix(gl, p.shadow_from_world, shadow_from_world ? *shadow_from_world : Mat4<float>::Identity());
    gl.Uniform1i(p.mode, static_cast<int>(SurfaceMode::Light));
    gl.Uniform4f(p.light, h.x(), h.y(), h.z(), h.w());
    gl.Uniform1f(p.light_intensity, light_intensity());
    if (l.type == scene::LightType::Spot) {
      const Vec3<float> axis = l.direction.normalized().cast<float>();
      gl.Uniform4f(p.spot, axis.x(), axis.y(), axis.z(), static_cast<float>(std::cos(l.cone_deg * std::numbers::pi / 180.0)));
    } else {
      gl.Uniform4f(p.spot, 0, 0, 0, -2.0f);
    }
  });
  in_row_bands(gl, width(), height(), [&] {
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const auto& c = scene.objects[i].color;
      gl.Uniform3f(surface.use(i).albedo, c.x(), c.y(), c.z());
      objects[i].draw(skins);
    }
  });
  if (masks) gl.DrawBuffer(GL_COLOR_ATTACHMENT0);
  gl.Disable(GL_BLEND);
  gl.DepthMask(GL_TRUE);
  gl.DepthFunc(depth_nearer());
}

Image8 Frame::read_stencil_mask(std::uint8_t value, bool value_is_lit) const {
  outputs::throw_if_interrupted();  // as read_grey
  gl.BindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  const std::size_t n = static_cast<std::size_t>(width()) * static_cast<std::size_t>(height());
  std::vector<std::uint8_t> stencil(n);
  std::vector<float> depth(n);
  gl.ReadPixels(0, 0, width(), height(), GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil.data());
  gl.ReadPixels(0, 0, width(), height(), GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  std::vector<std::uint8_t> mask(n);
  const auto no_surface = static_cast<float>(far_depth(convention()));
  for (std::size_t i = 0; i < n; ++i) {
    // The depth buffer still holds the clear value (the far plane's depth) where no surface was
    // drawn; a surface maps strictly inside (even with the infinite far plane, up to 0.1 · 2^24
    // units away in 24 bits, and always in 32-bit float, whose steps near 0 are far finer).
    if (depth[i] == no_surface) mask[i] = outputs::kMaskNoSurface;
    else mask[i] = (stencil[i] == value) == value_is_lit ? outputs::kMaskLit : outputs::kMaskShadowed;
  }
  return Image8{width(), height(), 1, flip_rows(mask, width(), height(), 1)};
}

std::vector<Image8> Frame::facing_masks(const Mat4<float>& clip) const {
  std::vector<Image8> masks;
  const PassPrograms surface(*this, [&](bool tested) -> const Program& { return programs.surface(nullptr, tested); });
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    bind_target(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, static_cast<float>(outputs::kMaskNoSurface) / 255.0f);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(depth_nearer());
    gl.Disable(GL_BLEND);
    gl.Disable(GL_STENCIL_TEST);
    const Vec4<float> l = light(i).cast<float>();
    surface.set([&](const Program& p) {
      set_matrix(gl, p.clip_from_world, clip);
      set_matrix(gl, p.shadow_from_world, Mat4<float>::Identity());
      gl.Uniform1i(p.mode, static_cast<int>(SurfaceMode::Mask));  // no map: the facing test alone
      gl.Uniform4f(p.light, l.x(), l.y(), l.z(), l.w());
    });
    for (std::size_t o = 0; o < objects.size(); ++o) {
      surface.use(o);
      objects[o].draw(skins);
    }
    masks.push_back(read_grey());
  }
  return masks;
}

Image8 Frame::read_grey(GLenum channel, GLenum attachment) const {
  // A read-back waits for llvmpipe to rasterise the pass queued before it (one light's): after
  // SIGINT or SIGTERM the run stops here, one pass at most after the signal, not at the case's end.
  outputs::throw_if_interrupted();
  gl.BindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<std::uint8_t> grey(static_cast<std::size_t>(width()) * static_cast<std::size_t>(height()));
  gl.ReadBuffer(attachment);
  gl.ReadPixels(0, 0, width(), height(), channel, GL_UNSIGNED_BYTE, grey.data());
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  return Image8{width(), height(), 1, flip_rows(grey, width(), height(), 1)};
}

void Frame::finish_then_check_interrupted() const {
  gl.Finish();
  outputs::throw_if_interrupted();
}

Image8 Frame::read_rgb() const {
  outputs::throw_if_interrupted();  // as read_grey
  gl.BindFramebuffer(GL_FRAMEBUFFER, target_fbo);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width()) * static_cast<std::size_t>(height()) * 3);
  gl.ReadPixels(0, 0, width(), height(), GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  // The target holds linear light; shaded.png is sRGB like every producer's (outputs/shading.hpp).
  const auto& srgb = outputs::srgb8_from_linear8();
  for (std::uint8_t& v : rgb) v = srgb[v];
  return Image8{width(), height(), 3, flip_rows(rgb, width(), height(), 3)};
}

// ---------------------------------------------------------------------------------------------
// Registry

namespace {

constexpr Technique kTechniqueTable[] = {
    {"planar",
     "Blinn 1988: each caster drawn again through the shadow matrix onto the receiver plane, black and "
     "blended, the stencil buffer letting each receiver pixel darken once (no shadow on other objects, "
     "false shadows from geometry under the plane or beyond the light).",
     render_planar},
    {"volume-zpass",
     "Heidmann 1991: silhouette edges extruded to infinity (w = 0), no caps, counted by two-sided "
     "stencil with wrapping increment / decrement where the volume faces pass the depth test.",
     render_volume_zpass},
    {"volume-zfail",
     "Everitt & Kilgard 2002 (Carmack's reverse): closed volumes with light and dark caps, counted where "
     "they fail the depth test, far plane at infinity with mathlib's epsilon.",
     render_volume_zfail},
    {"volume-zfail-clamp",
     "The same depth-fail volumes with a finite projection and GL_DEPTH_CLAMP, so that the dark cap "
     "beyond the far plane is clamped rather than clipped.",
     render_volume_zfail_clamp},
    {"volume-robust",
     "Per caster, depth-pass where mathlib says the near-plane clip volume misses it and depth-fail "
     "with caps elsewhere (Everitt & Kilgard 2002).",
     render_volume_robust},
    {"volume-finite",
     "The older volumes extruded by a finite distance (mathlib's finite extrusion), closed and counted "
     "depth-fail; they fall short when the light is close to the caster.",
     render_volume_finite},
    {"shadowmap",
     "Williams 1978: depth rendered from the light into a depth texture (front faces culled, polygon "
     "offset), compared per pixel through B * P_light * V_light with a sampler2DShadow.",
     render_shadowmap},
    {"shadowmap-pcf",
     "The shadow map with percentage-closer filtering: a 3x3 box of nearest depth compares one texel "
     "apart, lit where at least half pass.",
     render_shadowmap_pcf},
    {"shadowmap-rgba8",
     "The shadow map of hardware without depth textures: depth packed into an RGBA8 colour target "
     "(24 bits, mathlib's depth_packing) and compared as integers in the shader.",
     render_shadowmap_rgba8},
    {"csm",
     "Cascaded shadow maps (Engel 2006; Zhang et al. 2006): a directional light's map split at the "
     "practical split of the camera's depth into 4 cascades, each fitted to its slice's bounding "
     "sphere and snapped to whole texels (stable), depth range holding the whole scene; one nearest "
     "compare in the cascade of the fragment's depth. Other lights as shadowmap.",
     render_csm},
    {"csm-pcf",
     "The cascaded shadow maps with the 3x3 percentage-closer filter of shadowmap-pcf in each cascade.",
     render_csm_pcf},
    {"pcss",
     "Percentage-closer soft shadows (Fernando 2005) for rect lights: a blocker search over the light's "
     "rect seen through the map's near plane, the penumbra estimated from the blockers' mean depth, and "
     "an 8x8 filter over the rect seen through that depth, every tap compared with the receiver's own "
     "plane (a tap beyond a cube face's edge read from the neighbouring face); writes the lit fraction as "
     "visibility.png. Other lights as shadowmap-pcf.",
     render_pcss},
    {"vsm",
     "Variance shadow maps (Donnelly & Lauritzen 2006) filtered over PCSS's penumbra (Lauritzen 2007, "
     "GPU Gems 3 ch. 8): the light pass also stores the depth and its square; PCSS's blocker search "
     "and penumbra estimate, then the two moments averaged over the same 8x8 taps (the box a "
     "summed-area table returns) and Chebyshev's upper bound against the receiver's mean depth there. "
     "Bleeds light where two occluders overlap in the filter. Other lights as shadowmap-pcf.",
     render_vsm},
};

// The renderer implements exactly the contract's technique list, in its order.
constexpr bool table_matches_contract() {
  if (std::size(kTechniqueTable) != outputs::kTechniques.size()) return false;
  for (std::size_t i = 0; i < outputs::kTechniques.size(); ++i)
    if (kTechniqueTable[i].name != outputs::kTechniques[i].name) return false;
  return true;
}
static_assert(table_matches_contract(), "renderer technique table and outputs::kTechniques differ");

}  // namespace

std::span<const Technique> techniques() { return kTechniqueTable; }

const Technique* find_technique(std::string_view name) {
  for (const Technique& t : kTechniqueTable)
    if (t.name == name) return &t;
  return nullptr;
}

// ---------------------------------------------------------------------------------------------
// Renderer

struct Renderer::Impl {
  std::unique_ptr<GlContext> context;
  GlFunctions gl;
  std::unique_ptr<Programs> programs;    // destroyed in ~Impl, while it has the context current
  GlInfo info;
  std::unique_ptr<MapStoragePool> maps;  // the same
  GLuint rigid_skin_block = 0;           // the Skin block of every rigid draw (u_skinned false)

  Impl(GlApi api, Driver driver) : context(create_gl_context(api, driver)), gl(*context) {
    maps = std::make_unique<MapStoragePool>(gl);
    info.api = api;
    info.driver = driver;
    const auto str = [&](GLenum e) {
      const auto* s = reinterpret_cast<const char*>(gl.GetString(e));
      return std::string(s ? s : "");
    };
    info.vendor = str(GL_VENDOR);
    info.renderer = str(GL_RENDERER);
    info.version = str(GL_VERSION);
    programs = std::make_unique<Programs>(gl);
    const std::vector<unsigned char> rigid = skin_block_bytes({}, false);
    gl.GenBuffers(1, &rigid_skin_block);
    gl.BindBuffer(GL_UNIFORM_BUFFER, rigid_skin_block);
    gl.BufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(rigid.size()), rigid.data(), GL_STATIC_DRAW);
    gl.BindBuffer(GL_UNIFORM_BUFFER, 0);
  }
  ~Impl() {
    context->make_current();
    if (rigid_skin_block) gl.DeleteBuffers(1, &rigid_skin_block);
    maps.reset();
    programs.reset();
  }
};

Renderer::Renderer(GlApi api, Driver driver) : impl_(std::make_unique<Impl>(api, driver)) {}
Renderer::~Renderer() = default;
const GlInfo& Renderer::info() const { return impl_->info; }

namespace {

// The W × H render target: RGBA8 colour, an RG8 mask attachment (Frame::kMaskAttachment) and a
// packed depth + 8-bit stencil renderbuffer, the depth 24-bit fixed point or, where the convention
// asks (reversed-z), 32-bit float.
struct Target {
  const GlFunctions& gl;
  GLuint fbo = 0, colour = 0, mask = 0, depth_stencil = 0;
  Target(const GlFunctions& g, int w, int h, bool float_depth) : gl(g) {
    gl.GenRenderbuffers(1, &colour);
    gl.BindRenderbuffer(GL_RENDERBUFFER, colour);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    gl.GenRenderbuffers(1, &mask);
    gl.BindRenderbuffer(GL_RENDERBUFFER, mask);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RG8, w, h);
    gl.GenRenderbuffers(1, &depth_stencil);
    gl.BindRenderbuffer(GL_RENDERBUFFER, depth_stencil);
    gl.RenderbufferStorage(GL_RENDERBUFFER, float_depth ? GL_DEPTH32F_STENCIL8 : GL_DEPTH24_STENCIL8, w, h);
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, Frame::kMaskAttachment, GL_RENDERBUFFER, mask);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_stencil);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError(std::string("the RGBA8 + RG8 + ") + (float_depth ? "DEPTH32F_STENCIL8" : "DEPTH24_STENCIL8") +
                    " framebuffer is incomplete");
  }
  ~Target() {
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.DeleteFramebuffers(1, &fbo);
    gl.DeleteRenderbuffers(1, &colour);
    gl.DeleteRenderbuffers(1, &mask);
    gl.DeleteRenderbuffers(1, &depth_stencil);
  }
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;
};

}  // namespace

RenderResult Renderer::render(const scene::Scene& scene, std::string_view technique, const RenderOptions& options) {
  if (const std::string p = outputs::shadow_map_size_problem(options.shadow_map_size); !p.empty())
    throw std::invalid_argument("shadow map size " + std::to_string(options.shadow_map_size) + ": " + p);
  scene::PrepareOptions prepare;
  prepare.shadow_map_size = options.shadow_map_size;
  return render(scene::prepare_scene(scene, options.convention ? *options.convention : kDefaultConvention, prepare),
                technique, options);
}

RenderResult Renderer::render(const scene::PreparedScene& prepared, std::string_view technique, const RenderOptions& options) {
  const Technique* t = find_technique(technique);
  if (!t) throw std::invalid_argument("unknown technique '" + std::string(technique) + "'");
  impl_->context->make_current();
  const scene::Scene& scene = *prepared.scene;
  const RunConvention& convention = *prepared.convention;
  const GlFunctions& gl = impl_->gl;

  std::vector<GpuMesh> objects;
  objects.reserve(scene.objects.size());
  for (const scene::Object& o : scene.objects) {
    outputs::throw_if_interrupted();  // a large mesh's vertices take a while
    // Flat triangles: three vertices each (the very floats of the mesh, so that shadow-volume
    // caps built from the indexed mesh get identical depths) and the face normal
    // (v1 − v0) × (v2 − v0), computed in double as the reference does: a normal from screen-space
    // derivatives flips sign on nearly edge-on triangles.
    std::vector<Vec4<float>> v;
    std::vector<Vec3<float>> n;
    std::vector<Vec4<float>> alpha;  // a masked object's u, v, threshold, vertex alpha (GpuMesh)
    std::vector<Vec4<float>> bind, joints, weights;  // a skinned object's (GpuMesh::add_skin): v is then its posed vertices
    v.reserve(3 * o.mesh.triangles.size());
    n.reserve(3 * o.mesh.triangles.size());
    const float threshold = o.alpha ? scene::alpha_threshold(o.alpha->cutoff) : 0.0f;
    for (const auto& tri : o.mesh.triangles) {
      const Vec3<double> a = o.mesh.positions[tri[0]].cast<double>(), b = o.mesh.positions[tri[1]].cast<double>(),
                         c = o.mesh.positions[tri[2]].cast<double>();
      const Vec3<double> cr = (b - a).cross(c - a);
      const Vec3<float> normal = cr.squaredNorm() > 0.0 ? Vec3<float>(cr.normalized().cast<float>()) : Vec3<float>::Zero();
      for (std::uint32_t k : tri) {
        const Vec3<float>& p = o.mesh.positions[k];
        v.emplace_back(p.x(), p.y(), p.z(), 1.0f);
        n.push_back(normal);
        if (o.alpha) alpha.emplace_back(o.alpha->uvs[k].x(), o.alpha->uvs[k].y(), threshold, o.alpha->vertex_alpha[k]);
        if (o.skin) {
          const Vec3<float>& bp = o.skin->bind_positions[k];
          bind.emplace_back(bp.x(), bp.y(), bp.z(), 1.0f);
          const auto& id = o.skin->joint_indices[k];
          joints.emplace_back(static_cast<float>(id[0]), static_cast<float>(id[1]), static_cast<float>(id[2]), static_cast<float>(id[3]));
          const auto& w = o.skin->weights[k];
          weights.emplace_back(w[0], w[1], w[2], w[3]);
        }
      }
    }
    if (!o.skin) {
      objects.emplace_back(gl, v, std::span<const std::uint32_t>{}, n, alpha, o.alpha ? o.alpha->texture.get() : nullptr);
      continue;
    }
    // Skinned: the bind pose drawn through the joints (every pass), the CPU-posed floats beside it.
    std::vector<Mat4<float>> pose, bind_pose;
    for (const scene::Skin::Joint& j : o.skin->joints) {
      pose.push_back(to_float(j.world_from_bind()));
      bind_pose.push_back(to_float(o.skin->bind_to_world));
    }
    objects.emplace_back(gl, bind, std::span<const std::uint32_t>{}, n, alpha, o.alpha ? o.alpha->texture.get() : nullptr);
    objects.back().add_skin({v, joints, weights, pose, bind_pose, impl_->rigid_skin_block});
  }
  gl.BindBufferBase(GL_UNIFORM_BUFFER, kSkinBlockBinding, impl_->rigid_skin_block);
  const Target target(gl, scene.width, scene.height, convention.float_depth);
  // Clip-space depth 0..1 for the 0..1 conventions (ARB_clip_control, core in 4.5); GL's default
  // −1..1 is left alone otherwise, so that a 3.3 context without the extension still renders `gl`.
  const bool zero_to_one = convention.clip.depth == DepthRange::ZeroToOne;
  if (zero_to_one) {
    while (gl.GetError() != GL_NO_ERROR) {
    }
    gl.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    if (gl.GetError() != GL_NO_ERROR)
      throw GlError("the convention '" + std::string(convention.name) + "' needs glClipControl (ARB_clip_control), which " +
                    impl_->info.renderer + " (OpenGL " + impl_->info.version + ") lacks");
  }

  RenderResult result;
  for (int f = 0; f < std::max(1, options.frames); ++f) {
    RenderResult frame_result;
    frame_result.technique = std::string(t->name);
    frame_result.faults = describe(options.faults);
    if (!frame_result.faults.empty())
      frame_result.notes.push_back("deliberately wrong: fault switches " + frame_result.faults + " (renderer/faults.hpp)");
    Frame frame{gl, *impl_->programs, *impl_->maps, prepared, scene, options, frame_result, objects, target.fbo};
    const auto start = std::chrono::steady_clock::now();
    t->render(frame);
    gl.Finish();
    const auto stop = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(stop - start).count();
    if (f == 0) {
      result = std::move(frame_result);
      // What the judge needs to know of this render (outputs/candidate.hpp).
      result.declaration = outputs::default_declaration(std::string(t->name));
      result.declaration.producer = "shadowref renderer (OpenGL)";
      result.declaration.version = SHADOWREF_VERSION;
      result.declaration.convention = std::string(convention.name);
      result.declaration.shadow_map_size = prepared.options.shadow_map_size;
      // The prepared scene's light fits are the pack's, unless turned or moved (RenderOptions); the
      // shadow-map techniques add what each light's map draws with.
      result.declaration.light_views = options.view_turn_degrees == 0 && options.view_phase_texels == 0 ? outputs::LightViews::Pack
                                                                                                          : outputs::LightViews::Own;
      declare_shadow_map(t->name, prepared, options, result.declaration);
      result.declaration.defaulted.clear();
    }
    result.frame_ms.push_back(ms);
  }
  if (const GLenum err = gl.GetError(); err != GL_NO_ERROR) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%04X", err);
    throw GlError(std::string("OpenGL error ") + buf + " while rendering " + std::string(t->name));
  }
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (zero_to_one) gl.ClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);  // GL's default, for whoever renders next
  return result;
}

}  // namespace shadowref::renderer
