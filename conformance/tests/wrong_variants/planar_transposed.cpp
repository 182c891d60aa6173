// planar_transposed.cpp — planar projected shadows with the shadow matrix transposed: the D3DX
// layout (row vectors) fed to a column-vector pipeline, the classic copy-paste bug between
// D3DXMatrixShadow and OpenGL. The right version is conformance/renderer/planar.cpp.
#include <vector>
#include "frame.hpp"
#include "shadowref/shadow_matrix.hpp"
#include "wrong_variants.hpp"

namespace shadowref::wrong {

using namespace shadowref::renderer;

void render_planar_transposed(Frame& frame) {
  const GlFunctions& gl = frame.gl;
  const Mat4<double> pv = frame.camera_clip_double(CameraDepth::Scene);
  const Mat4<float> clip = to_float(pv);
  const std::optional<std::size_t> receiver = frame.scene.receiver_index();
  const std::optional<Plane<double>> plane = scene::receiver_plane(frame.scene);
  const std::vector<Image8> facing = frame.facing_masks(clip);  // before the picture: it clears
  frame.ambient_pass(clip);
  for (std::size_t i = 0; i < frame.scene.lights.size(); ++i) frame.light_pass(clip, i);
  for (std::size_t i = 0; i < frame.scene.lights.size(); ++i) {
    frame.bind_target(GL_STENCIL_BUFFER_BIT);
    const Result<Mat4<double>> s = receiver && plane ? shadow_matrix(*plane, frame.light(i)) : Result<Mat4<double>>(Error::NonFinite);
    if (s) {
      gl.Enable(GL_DEPTH_TEST);
      gl.DepthFunc(GL_LEQUAL);
      gl.DepthMask(GL_FALSE);
      gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      gl.Enable(GL_STENCIL_TEST);
      gl.StencilFunc(GL_ALWAYS, 1, 0xFF);
      gl.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
      gl.UseProgram(frame.programs.flat.id);
      set_matrix(gl, frame.programs.flat.clip_from_world, clip);
      gl.Uniform4f(frame.programs.flat.colour, 0, 0, 0, 0);
      frame.objects[*receiver].draw();
      gl.Disable(GL_DEPTH_TEST);
      gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      gl.Enable(GL_BLEND);
      gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
      gl.StencilFunc(GL_EQUAL, 1, 0xFF);
      gl.StencilOp(GL_KEEP, GL_KEEP, GL_INCR);
      const Mat4<double> wrong = s->transpose();  // THE BUG: D3DX layout in a column-vector pipeline
      set_matrix(gl, frame.programs.flat.clip_from_world, to_float(Mat4<double>(pv * wrong)));
      gl.Uniform4f(frame.programs.flat.colour, 0, 0, 0, 0.5f);
      for (std::size_t o = 0; o < frame.objects.size(); ++o)
        if (o != *receiver) frame.objects[o].draw();
      gl.Disable(GL_BLEND);
      gl.Disable(GL_STENCIL_TEST);
      gl.Enable(GL_DEPTH_TEST);
      gl.DepthFunc(GL_LESS);
      gl.DepthMask(GL_TRUE);
    }
    // The same attached-shadow rule as the right technique, so the transposition is the only bug.
    Image8 mask = frame.read_stencil_mask(2, /*value_is_lit=*/false);
    for (std::size_t px = 0; px < mask.pixels.size(); ++px)
      if (mask.pixels[px] == outputs::kMaskLit && facing[i].pixels[px] == outputs::kMaskShadowed) mask.pixels[px] = outputs::kMaskShadowed;
    frame.result.masks.push_back(std::move(mask));
  }
  frame.result.shaded = frame.read_rgb();
}

}  // namespace shadowref::wrong
