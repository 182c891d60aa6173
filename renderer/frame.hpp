// frame.hpp — what a technique gets to draw one frame: the GL table, the compiled programs, the
// scene's meshes on the GPU, the camera matrices, and the passes every technique shares (the
// ambient pre-pass, one light's additive pass, mask read-back). Private to the renderer library.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "gl_functions.hpp"
#include "shadowref/conventions.hpp"
#include "shadowref/renderer/renderer.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/scene/prepared_scene.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::renderer {

// A linked program and the uniform locations the renderer sets (-1 when a program lacks one).
struct Program {
  GLuint id = 0;
  GLint clip_from_world = -1, shadow_from_world = -1, colour = -1, mode = -1, shadow = -1, albedo = -1,
        ambient = -1, light = -1, light_intensity = -1, spot = -1, shadow_map = -1, packed_map = -1,
        texel = -1, offset_factor = -1, offset_units = -1, layout = -1, layer_from_world = -1, cascade_depth = -1,
        cascade_begin = -1, cascade_end = -1, reversed = -1, lit_greater = -1, depth_map = -1, world_from_layer = -1,
        inv_view_depth = -1, rect_u = -1, rect_v = -1, blocker_at_receiver = -1, moment_map = -1,
        layer_inv_view_depth = -1, taps_in_own_face = -1, random_taps = -1, random_pcf_radius = -1,
        normal_offset_texels = -1, light_position = -1, distance_range = -1;
};

struct Programs {
  Program flat;           // kSceneVertex + kFlatFragment
  Program surface;        // kSceneVertex + kSurfaceFragment
  Program surface_soft;   // the same with PCSS compiled in (shaders::kPcssDefine): pcss and vsm only
  Program packed_depth;   // kSceneVertex + kPackedDepthFragment
  Program moments;        // kSceneVertex + kMomentsFragment: vsm's light pass
  Program distance;       // kSceneVertex + kDistanceFragment: a distance cube's light pass
};

// Homogeneous vertices (vec4) and optional 32-bit triangle indices on the GPU.
class GpuMesh {
 public:
  // `normals`, when not empty, is one per vertex (attribute 1: the face normals of a flat mesh).
  GpuMesh(const GlFunctions& gl, std::span<const Vec4<float>> vertices, std::span<const std::uint32_t> indices,
          std::span<const Vec3<float>> normals = {});
  ~GpuMesh();
  GpuMesh(GpuMesh&& other) noexcept;
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
  GpuMesh& operator=(GpuMesh&&) = delete;
  void draw() const;  // GL_TRIANGLES, indexed when indices were given
  bool empty() const { return count_ == 0; }

 private:
  const GlFunctions* gl_;
  GLuint vao_ = 0, vbo_ = 0, ebo_ = 0, nbo_ = 0;
  GLsizei count_ = 0;
  bool indexed_ = false;
};

// Helpers shared by technique files.
void set_matrix(const GlFunctions& gl, GLint location, const Mat4<float>& m);
Mat4<float> to_float(const Mat4<double>& m);

// Slope-scaled and constant offset of the shadow maps' depth pass, in glPolygonOffset's units (the
// constant in steps of the 24-bit depth): large enough for the two-sided ground's self-comparison at
// grazing light, small enough not to detach shadows visibly at the catalogue's scale. The factor is
// what candidate.json declares as slope_bias_texels.
inline constexpr float kShadowMapOffsetFactor = 2.0f;
// The 3 x 3 PCF kernel compares the fragment's depth with texels up to one texel away on both axes:
// its diagonal tap stands two texels' slope off the fragment's own (|dz/ds| + |dz/dt|), and a texel
// centre half a texel more. A factor of 2 left one-tap acne on lit ground (8/9 fractions on 5 % of
// directional_light's pixels, seen in shaded.png and visibility.png, not in the mask); 3 covers it.
inline constexpr float kPcfOffsetFactor = 3.0f;
inline constexpr float kShadowMapOffsetUnits = 8.0f;
// RenderOptions::random_taps's PCF disk: its radius in texels, the 3 x 3 box's corner taps' reach,
// which PCF's slope factor (kPcfOffsetFactor) covers; what candidate.json declares as
// filter_radius_texels.
inline constexpr double kRandomPcfRadiusTexels = 1.41421356237309515;
// ShadowMapFaults::large_constant_offset: a constant offset of 2^17 depth steps, about 0.8 % of the
// 24-bit range (the size of constant bias that hides acne everywhere, grazing light included),
// which detaches shadows from their contacts.
inline constexpr float kPeterPanUnits = 131072.0f;
// One glPolygonOffset unit as window depth (0..1): one step of the 24-bit depth; what candidate.json
// declares as depth_bias per unit.
inline constexpr double kWindowDepthPerUnit = 1.0 / 16777216.0;

// RenderOptions::cube_depth: whether light i's map under `technique` holds distances (a cube of a
// depth-texture map, when distances are asked for), and the range they are stored over: the largest
// distance from the light to a corner of the scene's box, with 1 % to spare, so that every caster's
// distance lies below 1 (the clear value: nothing there).
bool cube_holds_distance(const RenderOptions& options, std::string_view technique, const scene::Light& light, bool cube);
double cube_distance_range(const scene::PreparedScene& prepared, std::size_t light);

// How the camera's far plane is set up for a technique (x and y rows never change).
using scene::CameraDepth;

// The GL compare function of a convention's depth comparison (convention.hpp).
GLenum gl_compare(DepthCompare c);

// Shadow-map storage kept from one render to the next: 2D array textures and renderbuffers, each of
// one format and size. Why: llvmpipe zeroes a fresh texture's memory and the kernel faults in every
// page of it, at each allocation; for the 2048-texel maps of a conformance run that was about a
// third of the drawing's time (perf: clear_page_erms, memset under glTexImage3D). A map's every layer
// is cleared before it is drawn (shadow_map.cpp), so a reused one carries nothing over.
class MapStoragePool {
 public:
  explicit MapStoragePool(const GlFunctions& gl) : gl_(gl) {}
  ~MapStoragePool();  // deletes them all: the context must be current
  MapStoragePool(const MapStoragePool&) = delete;
  MapStoragePool& operator=(const MapStoragePool&) = delete;
  // A 2D array texture of `layers` layers of size × size texels of `internal_format` (contents
  // undefined), bound to GL_TEXTURE_2D_ARRAY on the active unit; `format` and `type` as glTexImage3D's.
  GLuint texture(GLenum internal_format, GLenum format, GLenum type, int size, int layers);
  // A size × size renderbuffer of `internal_format`, bound to GL_RENDERBUFFER.
  GLuint renderbuffer(GLenum internal_format, int size);
  // Gives back what texture() or renderbuffer() handed out, for a later map of the same kind.
  void give_back(GLuint id, bool is_texture);

 private:
  struct Entry {
    bool is_texture;
    GLenum internal_format;
    int size, layers;
    GLuint id;
    bool in_use;
  };
  // The unused entry of that kind, now in use; null when there is none.
  Entry* reuse(bool is_texture, GLenum internal_format, int size, int layers);
  const GlFunctions& gl_;
  std::vector<Entry> entries_;
};

struct Frame {
  const GlFunctions& gl;
  const Programs& programs;
  MapStoragePool& maps;                       // the renderer's, kept across renders
  const scene::PreparedScene& prepared;       // camera, lights, casters, light fits, convention
  const scene::Scene& scene;                  // = *prepared.scene
  const RenderOptions& options;
  RenderResult& result;
  const std::vector<GpuMesh>& objects;        // scene.objects, same order
  GLuint target_fbo = 0;                      // W × H: RGBA8 colour, the RG8 mask attachment, depth/stencil
                                              // (24-bit, or 32F for reversed-z)
  // The target's second colour attachment, RG8: light_pass's lit fraction and mask.
  static constexpr GLenum kMaskAttachment = GL_COLOR_ATTACHMENT1;
  // The surface program this technique draws with (pcss, vsm: programs.surface_soft); null: programs.surface.
  const Program* surface = nullptr;
  const Program& surface_program() const { return surface ? *surface : programs.surface; }

  int width() const { return scene.width; }
  int height() const { return scene.height; }
  const RunConvention& convention() const { return *prepared.convention; }
  // Object i is a closed 2-manifold (mathlib adjacency, in the prepared scene).
  bool closed(std::size_t i) const { return prepared.casters[i].closed; }

  // P · V of the camera (the prepared scene's matrices, multiplied in double), with the chosen far
  // plane; camera_clip rounds it to float once for GL. (CameraFaults::half_pixel_offset shifts it.)
  Mat4<double> camera_clip_double(CameraDepth depth) const;
  Mat4<float> camera_clip(CameraDepth depth) const { return to_float(camera_clip_double(depth)); }
  // The fault switches of this render (faults.hpp); all off in production.
  const Faults& faults() const { return options.faults; }
  // Object i's bounding sphere lies wholly outside one of the four side planes of the camera's
  // frustum (what view-frustum culling tests; only the *_cull_casters_outside_view faults ask).
  bool outside_camera_view(std::size_t i) const;
  // The scene's lights as mathlib homogeneous points.
  Vec4<double> light(std::size_t i) const { return prepared.lights[i]; }
  // The depth test that keeps the nearer fragment in this convention (GL_LESS or GL_GREATER).
  GLenum depth_nearer() const { return gl_compare(nearer(convention())); }

  // Binds the W × H target and its viewport; clears what `mask` says (GL_*_BUFFER_BIT).
  void bind_target(GLbitfield clear_mask, float clear_grey = 0.0f) const;
  // Ambient pre-pass: clears the target, writes depth (depth_nearer) and ambient colour for every object.
  void ambient_pass(const Mat4<float>& clip) const;
  // Light i's additive Lambert pass over the surfaces already in the depth buffer (GL_EQUAL),
  // with the current stencil state left to the caller; `shadow` selects the surface shader's map.
  // With `masks`, the same pass also writes the light's lit fraction (red) and 0/1 mask (green)
  // into kMaskAttachment, cleared first to no light and outputs::kMaskNoSurface: the shadow maps'
  // filters run once per visible pixel for the picture, the mask and the fraction together.
  void light_pass(const Mat4<float>& clip, std::size_t light, int shadow = 0,
                  const Mat4<float>* shadow_from_world = nullptr, bool masks = false) const;

  // The stencil-derived mask: read stencil and depth; depth at the clear value (far_depth) → no surface;
  // otherwise, with `value_is_lit`, stencil == value → lit and anything else shadowed, and without
  // it stencil == value → shadowed and anything else lit. Rows flipped to top-down.
  Image8 read_stencil_mask(std::uint8_t value, bool value_is_lit) const;
  // Any mask already drawn into a colour attachment as grey (one channel: GL_RED, GL_GREEN, ...),
  // rows flipped.
  Image8 read_grey(GLenum channel = GL_RED, GLenum attachment = GL_COLOR_ATTACHMENT0) const;
  // Attached shadows: per light, a mask that is shadowed where the visible surface faces away from
  // the light (n · l <= 0), lit elsewhere, outputs::kMaskNoSurface where there is none. Clears the target:
  // call before drawing the picture.
  std::vector<Image8> facing_masks(const Mat4<float>& clip) const;
  // The colour buffer as RGB, rows flipped, sRGB-encoded (the target holds linear light).
  Image8 read_rgb() const;
  // The light intensity each light contributes: lighting adds up, ambient once.
  float light_intensity() const;
};


// The technique entry points (planar.cpp, stencil_volumes.cpp, shadow_map.cpp).
void render_planar(Frame& frame);
void render_volume_zpass(Frame& frame);
void render_volume_zfail(Frame& frame);
void render_volume_zfail_clamp(Frame& frame);
void render_volume_robust(Frame& frame);
void render_volume_finite(Frame& frame);
void render_shadowmap(Frame& frame);
void render_shadowmap_pcf(Frame& frame);
void render_shadowmap_rgba8(Frame& frame);
void render_csm(Frame& frame);
void render_csm_pcf(Frame& frame);
void render_pcss(Frame& frame);
void render_vsm(Frame& frame);

}  // namespace shadowref::renderer
