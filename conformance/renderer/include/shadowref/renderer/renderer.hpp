// shadowref/renderer/renderer.hpp — the OpenGL renderer as a library: one context, every shadow
// technique, the masks and the shaded picture of DESIGN.md "Outputs", and render.json.
//
// Usage:
//   Renderer r(GlApi::OSMesa, Driver::Llvmpipe);       // one per process and driver
//   RenderResult res = r.render(scene, "volume-zfail");
//   write_outputs(res, r.info(), scene, "out/ground_sphere/volume-zfail");
// Every matrix comes from mathlib (and the camera's from scene/camera.hpp, the very function the
// reference uses); shadow volumes come from mathlib's volume construction.
//
// Masks: mask i answers "is the surface seen through this pixel centre lit by light i?": 255 lit,
// 0 shadowed, 128 no surface. The image is the scene's resolution, row 0 at the top; GL renders
// into a W × H viewport whose fragments sit at the pixel centres, with the scene's own view and
// projection (the depth rows of the projection may differ per technique: zfail's epsilon,
// zfail-clamp's finite far; x and y, hence the pixel → surface mapping, never do).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "shadowref/renderer/gl_context.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::renderer {

// 8-bit image, row 0 at the top, `channels` interleaved bytes per pixel.
struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<std::uint8_t> pixels;
  std::uint8_t at(int x, int y, int c = 0) const {
    return pixels[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
                      static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)];
  }
};

inline constexpr std::uint8_t kMaskLit = 255;
inline constexpr std::uint8_t kMaskShadowed = 0;
inline constexpr std::uint8_t kMaskNoSurface = 128;

struct RenderOptions {
  // Texels per side of each light's shadow map; 0 = automatic: for point and spot lights, as many
  // as make one texel at most a third of a camera pixel in angle at the centres of both views
  // (so that a pixel next to a silhouette seen from the light is not judged by a texel on the
  // wrong side), clamped to [1024, 8192] (a point light's cube: [1024, 2048] per face, six
  // faces); 2048 for directional lights.
  int shadow_map_size = 0;
  int frames = 1;              // frames rendered; frame_ms is their median (the first is output)
};

struct RenderResult {
  std::string technique;
  std::vector<Image8> masks;   // one per light (grey)
  Image8 shaded;               // RGB
  std::vector<double> frame_ms;  // the time of each frame, all passes to glFinish and read-back
  std::vector<std::string> notes;  // what the technique could not do on this scene, and why
  double median_frame_ms() const;
};

struct GlInfo {
  GlApi api = GlApi::OSMesa;
  Driver driver = Driver::Llvmpipe;
  std::string vendor, renderer, version;
};

class Renderer;
struct Frame;

// One technique: its command-line name, one sentence for --help, and its implementation.
struct Technique {
  std::string_view name;
  std::string_view description;
  void (*render)(Frame& frame);
};

// Every technique, in the order --help lists them.
std::span<const Technique> techniques();
// The technique called `name`, or nullptr.
const Technique* find_technique(std::string_view name);

class Renderer {
 public:
  // Creates the context (create_gl_context) and compiles the shaders. Throws GlError.
  Renderer(GlApi api, Driver driver);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const GlInfo& info() const;
  // Renders `scene` with the technique `name`. Throws std::invalid_argument for an unknown
  // technique, GlError for a GL failure.
  RenderResult render(const scene::Scene& scene, std::string_view technique, const RenderOptions& options = {});
  // [conformance hook, issue 7] The same with a technique that is not in the table: the
  // deliberately wrong variants of conformance/tests/wrong_variants/, which the suite must catch.
  RenderResult render(const scene::Scene& scene, const Technique& technique, const RenderOptions& options = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes mask.png (one light) or mask_<i>.png (several), shaded.png and render.json into `dir`:
// first into a temporary sibling folder, renamed to `dir` when complete, so that a reader never
// sees half a result. An existing `dir` is replaced. Throws std::runtime_error on file errors.
void write_outputs(const RenderResult& result, const GlInfo& info, const scene::Scene& scene,
                   const std::filesystem::path& dir);

}  // namespace shadowref::renderer
