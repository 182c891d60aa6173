// planar.cpp — planar projected shadows: Blinn 1988, "Me and my (fake) shadow" (IEEE CG&A).
//
// Every caster (every object but the receiver) is drawn a second time through the shadow matrix
// S = (P·L) I − L Pᵀ (mathlib/shadow_matrix.hpp), which flattens it onto the receiver's plane
// (scene::receiver_plane), in black with alpha blending. The stencil buffer does two jobs:
// the receiver's visible pixels are marked 1 first (so the shadow lands only on the receiver and
// never hangs over its edges), and a pixel's first shadow fragment moves it to 2, so overlapping
// projected triangles darken each pixel once. The projected pass has no depth test: the marked
// pixels already are the visible receiver, and the flattened caster would z-fight with it.
// Left as a GPU shows them, the technique's limits: no shadow on any other object (the caster's
// self-shadowing included), false shadows from geometry below the plane (S flattens it too), and
// geometry beyond the light projects with w < 0 and is clipped, or appears as an anti-shadow.
// The mask of light i: stencil 2 (a shadow fragment landed on the receiver) → shadowed; a surface
// that faces away from the light (n · l ≤ 0: its attached shadow, which the lit picture shows dark
// and every other technique and the reference call shadowed) → shadowed; every other surface → lit.
// Several lights: each darkens the lit picture once more by kShadowAlpha.
// Fault switches (faults.hpp, PlanarFaults): the matrix transposed, a directional light taken as a
// point, and no once-per-pixel rule; each is one `if` below.
#include <string>
#include <utility>
#include <vector>

#include "frame.hpp"
#include "shadowref/shadow_matrix.hpp"

namespace shadowref::renderer {
namespace {

// How much a planar shadow darkens: the classic half-transparent black.
constexpr float kShadowAlpha = 0.5f;
constexpr std::uint8_t kReceiverMark = 1;
constexpr std::uint8_t kShadowMark = 2;

}  // namespace

void render_planar(Frame& frame) {
  const GlFunctions& gl = frame.gl;
  const Mat4<double> pv = frame.camera_clip_double(CameraDepth::Scene);
  const Mat4<float> clip = to_float(pv);
  const std::optional<std::size_t> receiver = frame.scene.receiver_index();
  const std::optional<Plane<double>> plane = scene::receiver_plane(frame.scene);
  if (!receiver || !plane) frame.result.notes.push_back("the scene has no receiver: planar shadows cast nothing");

  // Attached shadows, one facing mask per light (before the picture: these passes clear it).
  const std::vector<Image8> facing = frame.facing_masks(clip);

  // The picture without shadows: ambient, then every light.
  frame.ambient_pass(clip);
  for (std::size_t i = 0; i < frame.scene.lights.size(); ++i) frame.light_pass(clip, i);

  const float black[4] = {0.0f, 0.0f, 0.0f, kShadowAlpha};
  const PassPrograms programs(frame, [&](bool tested) -> const Program& { return frame.programs.flat(tested); });
  for (std::size_t i = 0; i < frame.scene.lights.size(); ++i) {
    frame.bind_target(GL_STENCIL_BUFFER_BIT);
    if (receiver && plane) {
      Vec4<double> light = frame.light(i);
      if (frame.faults().planar.directional_as_point) light.w() = 1.0;  // FAULT: w = 0 read as a point
      const Result<Mat4<double>> s = shadow_matrix(*plane, light);
      if (!s) {
        frame.result.notes.push_back("light " + std::to_string(i) + ": no planar shadow (" + s.message() + ")");
      } else {
        // 1. Mark the receiver's visible pixels (same vertex shader as the pre-pass: equal depth).
        gl.Enable(GL_DEPTH_TEST);
        gl.DepthFunc(gl_compare(nearer_or_equal(frame.convention())));
        gl.DepthMask(GL_FALSE);
        gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        gl.Enable(GL_STENCIL_TEST);
        gl.StencilFunc(GL_ALWAYS, kReceiverMark, 0xFF);
        gl.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        programs.set([&](const Program& p) {
          set_matrix(gl, p.clip_from_world, clip);
          gl.Uniform4f(p.colour, 0, 0, 0, 0);
        });
        programs.use(*receiver);
        frame.objects[*receiver].draw(frame.skins);

        // 2. The casters through P · V · S, black, blended, once per marked pixel.
        gl.Disable(GL_DEPTH_TEST);
        gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        gl.Enable(GL_BLEND);
        gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        gl.StencilFunc(GL_EQUAL, kReceiverMark, 0xFF);
        gl.StencilOp(GL_KEEP, GL_KEEP, GL_INCR);  // 1 → 2: the next fragment here fails EQUAL 1
        // FAULT: any marked pixel (1 <= stencil) takes every fragment: darkened once per fragment.
        if (frame.faults().planar.darken_every_fragment) gl.StencilFunc(GL_LEQUAL, kReceiverMark, 0xFF);
        // FAULT: D3DX's row-vector layout used as a column-vector matrix.
        const Mat4<double> shadow = frame.faults().planar.matrix_transposed ? Mat4<double>(s->transpose()) : *s;
        programs.set([&](const Program& p) {
          set_matrix(gl, p.clip_from_world, to_float(Mat4<double>(pv * shadow)));
          gl.Uniform4f(p.colour, black[0], black[1], black[2], black[3]);
        });
        for (std::size_t o = 0; o < frame.objects.size(); ++o) {
          if (o == *receiver) continue;
          programs.use(o);  // a masked caster's holes cast nothing
          frame.objects[o].draw(frame.skins);
        }
        gl.Disable(GL_BLEND);
        gl.Disable(GL_STENCIL_TEST);
        gl.Enable(GL_DEPTH_TEST);
        gl.DepthFunc(frame.depth_nearer());
        gl.DepthMask(GL_TRUE);
      }
    }
    Image8 mask = frame.read_stencil_mask(kShadowMark, /*value_is_lit=*/false);
    for (std::size_t p = 0; p < mask.pixels.size(); ++p)
      if (mask.pixels[p] == outputs::kMaskLit && facing[i].pixels[p] == outputs::kMaskShadowed) mask.pixels[p] = outputs::kMaskShadowed;
    frame.result.masks.push_back(std::move(mask));
  }
  frame.result.shaded = frame.read_rgb();
}

}  // namespace shadowref::renderer
