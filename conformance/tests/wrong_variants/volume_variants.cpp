// volume_variants.cpp — depth-fail stencil volumes done wrong, two ways (the right version is
// conformance/renderer/stencil_volumes.cpp, Everitt & Kilgard 2002):
//   zfail-without-caps    the side quads only: a z-fail count needs the light and dark caps to
//                         close the volume, so pixels seen through a missing cap count wrong;
//   zfail-half-pixel      the camera shifted by half a pixel (Direct3D 9's pixel-centre
//                         convention applied to a pixel-centre API): everything moves by (0.5, 0.5).
#include <string>

#include "frame.hpp"
#include "shadowref/silhouette.hpp"
#include "shadowref/volume.hpp"
#include "wrong_variants.hpp"

namespace shadowref::wrong {
namespace {

using namespace shadowref::renderer;

void zfail(Frame& frame, bool caps, bool half_pixel) {
  const GlFunctions& gl = frame.gl;
  Mat4<double> pv = frame.camera_clip_double(CameraDepth::InfiniteEpsilon);
  if (half_pixel) {
    // One pixel is 2 / W in NDC: half a pixel right and half a pixel down (row 0 at the top).
    Mat4<double> shift = Mat4<double>::Identity();
    shift(0, 3) = 1.0 / frame.width();
    shift(1, 3) = -1.0 / frame.height();
    pv = shift * pv;
  }
  const Mat4<float> clip = to_float(pv);
  frame.ambient_pass(clip);
  Silhouette<float> sil;
  ShadowVolume<float> volume;
  for (std::size_t i = 0; i < frame.scene.lights.size(); ++i) {
    const Vec4<float> light = frame.light(i).cast<float>();
    frame.bind_target(GL_STENCIL_BUFFER_BIT);
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.DepthMask(GL_FALSE);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_CULL_FACE);
    gl.Enable(GL_STENCIL_TEST);
    gl.StencilFunc(GL_ALWAYS, 0, 0xFF);
    gl.StencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
    gl.StencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
    gl.UseProgram(frame.programs.flat.id);
    set_matrix(gl, frame.programs.flat.clip_from_world, clip);
    for (const scene::Object& o : frame.scene.objects) {
      Result<ShadowCaster<float>> caster = make_shadow_caster(o.mesh);
      if (!caster) continue;
      if (!find_silhouette(*caster, light, sil) || sil.lit_count == 0) continue;
      VolumeOptions<float> options;
      options.light_cap = options.dark_cap = caps;  // THE BUG when false: z-fail with an open volume
      if (!build_shadow_volume(*caster, sil, options, volume) || volume.indices.empty()) continue;
      const GpuMesh mesh(gl, volume.vertices, volume.indices);
      mesh.draw();
    }
    frame.result.masks.push_back(frame.read_stencil_mask(0, /*value_is_lit=*/true));
    gl.StencilFunc(GL_EQUAL, 0, 0xFF);
    gl.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    frame.light_pass(clip, i);
    gl.Disable(GL_STENCIL_TEST);
  }
  frame.result.shaded = frame.read_rgb();
}

}  // namespace

void render_zfail_without_caps(Frame& frame) { zfail(frame, /*caps=*/false, /*half_pixel=*/false); }
void render_zfail_half_pixel_offset(Frame& frame) { zfail(frame, /*caps=*/true, /*half_pixel=*/true); }

}  // namespace shadowref::wrong
