// frame.hpp — what a technique gets to draw one frame: the GL table, the compiled programs, the
// scene's meshes on the GPU, the camera matrices, and the passes every technique shares (the
// ambient pre-pass, one light's additive pass, mask read-back). Private to the renderer library.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string_view>
#include <span>
#include <vector>

#include "gl_functions.hpp"
#include "shadowref/conventions.hpp"
#include "shadowref/renderer/renderer.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/scene/prepared_scene.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::renderer {

// What the surface program's pass writes (u_mode; shaders.cpp generates its GLSL constants from these).
enum class SurfaceMode { Ambient, Light, Mask };

// How a light's map is laid out in its layers (u_layout): one view, a cube's six faces, or cascades.
enum class MapLayout { Single, Cube, Cascades };

// The shadow-map lookups (shadow_maps/lookup.hpp), each with a surface program of its own; None:
// the surface program without a map.
struct MapLookup;  // shadow_maps/lookup.hpp: one per lookup, in the lookup's own file
class PassPrograms;

// A linked program and the locations of the uniforms every scene pass sets (-1 when a program lacks
// one); the others are looked up by name where they are set (at()).
struct Program {
  GLuint id = 0;
  GLint clip_from_world = -1, shadow_from_world = -1, colour = -1, mode = -1, albedo = -1, ambient = -1, light = -1,
        light_intensity = -1, spot = -1;
  GLint at(const GlFunctions& gl, const char* name) const { return gl.GetUniformLocation(id, name); }
};

// The depth passes' fragment shaders (shaders.hpp): a constant colour (depth pre-pass, stencil
// passes, planar black, a depth map), an RGBA8-packed depth, vsm's moments, a distance cube's
// distance, and a float depth map's offset depth by hand (alone, or with vsm's moments).
enum class DepthProgram { Flat, PackedDepth, Moments, Distance, OffsetDepth, MomentsOffsetDepth };

// The renderer's programs (programs.cpp), each in two builds: without the alpha test (no discard:
// the build every unmasked object draws with, keeping the rasteriser's early depth test) and with it
// (for masked objects, compiled the first time a scene has one; shaders::alpha_test). The surface
// program of each lookup is compiled the first time a render asks for it: a process that draws one
// technique pays for one.
class Programs {
 public:
  explicit Programs(const GlFunctions& gl);  // compiles the untested depth programs and plain surface program
  ~Programs();                                // the context must be current
  Programs(const Programs&) = delete;
  Programs& operator=(const Programs&) = delete;

  // kSceneVertex + the pass's fragment shader (DepthProgram).
  const Program& depth(DepthProgram pass, bool alpha_tested = false) const;
  const Program& flat(bool alpha_tested = false) const { return depth(DepthProgram::Flat, alpha_tested); }
  // kSceneVertex + shaders::surface_fragment(lookup): nullptr for the passes without a map.
  const Program& surface(const MapLookup* lookup = nullptr, bool alpha_tested = false) const;

 private:
  const GlFunctions& gl_;
  mutable std::map<std::pair<DepthProgram, bool>, Program> depth_;            // compiled when first asked
  mutable std::map<std::pair<const MapLookup*, bool>, Program> surface_;      // by lookup, compiled when first asked
};

// The texture unit of every program's alpha mask (u_alpha_mask, an R8UI texture); the light maps use 0 to 3.
inline constexpr GLenum kAlphaMaskUnit = GL_TEXTURE4;

// The uniform block binding of kSceneVertex's `Skin` block (programs.cpp binds every program's there).
inline constexpr GLuint kSkinBlockBinding = 0;

// How a draw poses a skinned object (scene/skin.hpp); a rigid object ignores it.
enum class SkinDraw {
  Gpu,       // the bind pose skinned in the vertex shader with the pose's joint matrices (every pass)
  CpuPosed,  // the scene's posed mesh, the very floats the CPU posed (stencil volumes: stencil_volumes.cpp)
  BindPose,  // the bind pose unposed (ShadowMapFaults::skin_bind_pose only)
};

// A skinned object's GPU data (GpuMesh::add_skin): per flat vertex, the CPU-posed position, the four
// joint indices (as floats) and weights; the joint matrices at the pose and in the bind pose; and the
// renderer's rigid block (u_skinned false), bound back after each skinned draw.
struct GpuSkinData {
  std::span<const Vec4<float>> posed_vertices;
  std::span<const Vec4<float>> joints;
  std::span<const Vec4<float>> weights;
  std::span<const Mat4<float>> pose_matrices;
  std::span<const Mat4<float>> bind_matrices;
  GLuint rigid_block = 0;
};

// The `Skin` block's contents (std140: kSceneVertexJoints mat4, then the bool u_skinned, 4 bytes: 0 or 1), as bytes.
std::vector<unsigned char> skin_block_bytes(std::span<const Mat4<float>> joints, bool skinned);

// Homogeneous vertices (vec4) and optional 32-bit triangle indices on the GPU.
class GpuMesh {
 public:
  // `normals`, when not empty, is one per vertex (attribute 1: the face normals of a flat mesh).
  // `alpha_test`, when not empty, is one per vertex (attribute 2: u, v, the threshold of
  // scene::alpha_threshold, the vertex alpha) and `mask` the object's texture, uploaded as R8UI and
  // bound to kAlphaMaskUnit by draw(). Without them attribute 2 keeps GL's default (0, 0, 0, 1): a
  // threshold of 0, which every fragment passes (shaders.cpp, kAlphaTest).
  GpuMesh(const GlFunctions& gl, std::span<const Vec4<float>> vertices, std::span<const std::uint32_t> indices,
          std::span<const Vec3<float>> normals = {}, std::span<const Vec4<float>> alpha_test = {},
          const scene::AlphaTexture* mask = nullptr);
  ~GpuMesh();
  GpuMesh(GpuMesh&& other) noexcept;
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
  GpuMesh& operator=(GpuMesh&&) = delete;
  // Makes the mesh skinned: its vertices (attribute 0) are then the bind pose; attributes 3 and 4
  // the joints and weights; a second vertex array draws the CPU-posed vertices (SkinDraw::CpuPosed).
  void add_skin(const GpuSkinData& skin);
  void draw(SkinDraw skin = SkinDraw::Gpu) const;  // GL_TRIANGLES, indexed when indices were given
  bool empty() const { return count_ == 0; }
  bool skinned() const { return posed_vao_ != 0; }

 private:
  const GlFunctions* gl_;
  GLuint vao_ = 0, vbo_ = 0, ebo_ = 0, nbo_ = 0, abo_ = 0, mask_ = 0;
  GLuint posed_vao_ = 0, posed_vbo_ = 0, skin_vbo_ = 0, pose_block_ = 0, bind_block_ = 0, rigid_block_ = 0;
  GLsizei count_ = 0;
  bool indexed_ = false;
};

// Helpers shared by technique files.
void set_matrix(const GlFunctions& gl, GLint location, const Mat4<float>& m);
Mat4<float> to_float(const Mat4<double>& m);

// How the camera's far plane is set up for a technique (x and y rows never change).
using scene::CameraDepth;

// The GL compare function of a convention's depth comparison (convention.hpp).
GLenum gl_compare(DepthCompare c);

class MapStoragePool;  // shadow_maps/light_map.hpp: the maps' storage, kept across renders

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
  // How skinned objects are drawn in this frame's passes (stencil volumes: CpuPosed, see there).
  SkinDraw skins = SkinDraw::Gpu;
  // The target's second colour attachment, RG8: light_pass's lit fraction and mask.
  static constexpr GLenum kMaskAttachment = GL_COLOR_ATTACHMENT1;

  int width() const { return scene.width; }
  int height() const { return scene.height; }
  const RunConvention& convention() const { return *prepared.convention; }
  // Object i is a closed 2-manifold (mathlib adjacency, in the prepared scene).
  bool closed(std::size_t i) const { return prepared.casters[i].closed; }
  // Object i carries an alpha mask (drawn with the alpha-tested programs: PassPrograms).
  bool masked(std::size_t i) const { return scene.objects[i].alpha.has_value(); }
  bool any_masked() const;

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
  // Ambient pre-pass: clears the target, writes depth (depth_nearer) and ambient colour for every
  // object, with the plain surface program (its depths equal every surface program's: the vertex
  // shader's gl_Position is invariant).
  void ambient_pass(const Mat4<float>& clip) const;
  // Light i's additive Lambert pass over the surfaces already in the depth buffer (GL_EQUAL),
  // with the current stencil state left to the caller, drawn with `programs` (a lookup's surface
  // programs, its map bound and its uniforms set; null: the plain one) and `shadow_from_world`.
  // With `masks`, the same pass also writes the light's lit fraction (red) and 0/1 mask (green)
  // into kMaskAttachment, cleared first to no light and outputs::kMaskNoSurface: the shadow maps'
  // filters run once per visible pixel for the picture, the mask and the fraction together.
  void light_pass(const Mat4<float>& clip, std::size_t light, const PassPrograms* programs = nullptr,
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
  // Lets llvmpipe rasterise what is queued (glFinish), then throws outputs::Interrupted after SIGINT
  // or SIGTERM: the point between two long passes (lights' maps, casters' volumes) where a signalled
  // run stops, rather than after every pass of the frame is drawn.
  void finish_then_check_interrupted() const;
  // The light intensity each light contributes: lighting adds up, ambient once.
  float light_intensity() const;
};


// The programs one pass draws the scene's objects with: each object with the build its mask asks
// for (Programs), the alpha-tested one only for masked objects and compiled only when the scene has
// one. A pass sets its uniforms on every build with set() and draws object i after use(i).
class PassPrograms {
 public:
  // `build(alpha_tested)` gives the pass's program in that build (a Programs accessor).
  PassPrograms(const Frame& frame, const std::function<const Program&(bool alpha_tested)>& build);
  // Calls f(program) with each build current in turn (glUseProgram), the untested one last.
  void set(const std::function<void(const Program&)>& f) const;
  // Makes object i's build current when it is not already, and returns it.
  const Program& use(std::size_t object) const;

 private:
  const Frame& frame_;
  std::array<const Program*, 2> builds_{};  // [alpha_tested]; [true] null when no object is masked
  mutable const Program* current_ = nullptr;
};

// The technique entry points (planar.cpp, stencil_volumes.cpp, shadow_maps/).
void render_planar(Frame& frame);
void render_volume_zpass(Frame& frame);
void render_volume_zfail(Frame& frame);
void render_volume_zfail_clamp(Frame& frame);
void render_volume_robust(Frame& frame);
void render_volume_finite(Frame& frame);
void render_shadowmap(Frame& frame);        // shadow_maps/shadow_map_techniques.cpp
void render_shadowmap_pcf(Frame& frame);
void render_shadowmap_rgba8(Frame& frame);
void render_csm(Frame& frame);
void render_csm_pcf(Frame& frame);
void render_pcss(Frame& frame);
void render_vsm(Frame& frame);
// Completes `declaration` (producer, convention and map size set) with what the shadow-map
// technique `technique` draws for this prepared scene and these options, per light where lights
// differ (shadow_maps/declaration.cpp); false, and nothing changed, for the other techniques.
bool declare_shadow_map(std::string_view technique, const scene::PreparedScene& prepared, const RenderOptions& options,
                        outputs::CandidateDeclaration& declaration);

}  // namespace shadowref::renderer
