// stencil_volumes.cpp — stencil shadow volumes, five ways.
//
//   volume-zpass        Heidmann 1991, "Real shadows, real time" (IRIS Universe 18): the
//                       silhouette's side quads extruded to infinity (w = 0), no caps; two-sided
//                       stencil, front faces GL_INCR_WRAP and back faces GL_DECR_WRAP where they
//                       pass the depth test. Wrong where the near plane cuts a volume.
//   volume-zfail        Everitt & Kilgard 2002, "Practical and Robust Stenciled Shadow Volumes
//                       for Hardware-Accelerated Rendering" (Carmack's reverse): sides, light cap
//                       and dark cap; back faces GL_INCR_WRAP, front faces GL_DECR_WRAP where they
//                       FAIL the depth test; the camera's far plane at infinity with
//                       kSafeInfiniteEpsilonFloat so that the dark cap (w = 0) is never clipped.
//   volume-zfail-clamp  the same counting with a finite far plane and GL_DEPTH_CLAMP (NV_depth_clamp
//                       in the paper): the dark cap beyond the far plane is clamped, not clipped.
//   volume-robust       per caster, mathlib's near-plane clip volume test (volume_strategy.hpp):
//                       z-pass where it is provably safe, z-fail with caps elsewhere.
//   volume-finite       the older extrusion by a finite distance (kFiniteExtrusionRadii caster
//                       radii, mathlib's extrude_finite), closed with caps and counted z-fail; it
//                       falls short of receivers when the light is close to the caster.
// Every volume comes from mathlib (silhouette.hpp, volume.hpp) with its open-edge rule: an open
// edge of a lit face is a silhouette edge, so an open or non-manifold caster still gets a closed
// volume and is not rejected. Every object casts (the receiver too: its volume lies behind it).
// Depth test "nearer" (GL_LESS; GL_GREATER under reversed-Z) during the stencil pass: a light cap lies
// exactly on its surface (the vertex shader is `invariant` and the vertices are the same floats), so
// it fails the strict test and the z-fail
// count of a lit surface is (−1 cap) + (+1 exit) = 0, while z-pass does not count it at all.
// Mask of light i: the stencil after its volumes, 0 → lit, anything else → shadowed; then light
// i's additive pass where the stencil is 0.
// Fault switches (faults.hpp, VolumeFaults): no caps, robust always z-pass, the light's position
// classifying faces as a direction, saturating stencil ops, casters out of view culled; each is one
// `if` below.
#include <algorithm>
#include <string>

#include "frame.hpp"
#include "shadowref/silhouette.hpp"
#include "shadowref/volume.hpp"
#include "shadowref/volume_strategy.hpp"

namespace shadowref::renderer {
namespace {

// The finite extrusion distance, in radii of the caster's bounding sphere: a distance tied to the
// caster's size (as engines tuned it per level) rather than to the light, which is the point.
constexpr float kFiniteExtrusionRadii = 4.0f;

enum class Mode { ZPass, ZFail, ZFailClamp, Robust, Finite };

void set_stencil_ops(const GlFunctions& gl, StencilMethod method, const VolumeFaults& faults) {
  GLenum incr = GL_INCR_WRAP, decr = GL_DECR_WRAP;
  if (faults.saturating_stencil) incr = GL_INCR, decr = GL_DECR;  // FAULT: 0 − 1 stays 0
  if (method == StencilMethod::ZPass) {
    gl.StencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, incr);
    gl.StencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, decr);
  } else {
    gl.StencilOpSeparate(GL_BACK, GL_KEEP, incr, GL_KEEP);
    gl.StencilOpSeparate(GL_FRONT, GL_KEEP, decr, GL_KEEP);
  }
}

void render_volumes(Frame& frame, Mode mode) {
  const GlFunctions& gl = frame.gl;
  // Skinned objects drawn as the CPU posed them: the volumes are extruded on the CPU from the posed
  // mesh (the silhouette needs posed positions), and their caps must land on the very depths the
  // camera's passes drew (kSceneVertex's invariance), which GPU skinning would round differently.
  // Doom 3 skinned on the CPU for its volumes for the same reason.
  frame.skins = SkinDraw::CpuPosed;
  const CameraDepth depth = mode == Mode::ZPass        ? CameraDepth::Scene
                            : mode == Mode::ZFailClamp ? CameraDepth::FiniteForClamp
                                                       : CameraDepth::InfiniteEpsilon;
  const Mat4<double> pv = frame.camera_clip_double(depth);
  const Mat4<float> clip = to_float(pv);
  const VolumeFaults& faults = frame.faults().volume;

  // Casters (mesh, adjacency, face planes, bounding sphere): built once, in the prepared scene.
  const std::vector<scene::PreparedCaster>& casters = frame.prepared.casters;
  for (std::size_t c = 0; c < casters.size(); ++c)
    if (!casters[c].caster)
      frame.result.notes.push_back(frame.scene.objects[c].name + ": casts no volume (" + casters[c].why_not + ")");
  std::optional<std::array<Vec3<double>, 4>> near;
  if (mode == Mode::Robust) {
    const auto r = near_rectangle(pv, frame.convention().clip);
    if (r) near = *r;
    else frame.result.notes.push_back(std::string("near rectangle: ") + r.message() + "; every caster z-fail");
  }

  frame.ambient_pass(clip);
  Silhouette<float> sil;
  ShadowVolume<float> volume;
  for (std::size_t i = 0; i < frame.scene.lights.size(); ++i) {
    const Vec4<float> light = frame.light(i).cast<float>();
    frame.bind_target(GL_STENCIL_BUFFER_BIT);
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.DepthMask(GL_FALSE);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(frame.depth_nearer());
    gl.Disable(GL_CULL_FACE);  // both faces in one pass: two-sided stencil
    gl.Enable(GL_STENCIL_TEST);
    gl.StencilFunc(GL_ALWAYS, 0, 0xFF);
    if (mode == Mode::ZFailClamp) gl.Enable(GL_DEPTH_CLAMP);
    // The volumes are no scene object and never masked: the flat program without the alpha test.
    gl.UseProgram(frame.programs.flat().id);
    set_matrix(gl, frame.programs.flat().clip_from_world, clip);
    std::string robust_choice;
    for (std::size_t c = 0; c < casters.size(); ++c) {
      if (!casters[c].caster) continue;
      frame.finish_then_check_interrupted();  // between casters: a light's volumes fill for seconds at 4 x
      const ShadowCaster<float>& caster = *casters[c].caster;
      const BoundingSphere<float>& bsphere = casters[c].sphere;
      const std::string& name = frame.scene.objects[c].name;
      // FAULT: a caster out of the camera's view culled as if it could cast nothing into it.
      if (faults.cull_casters_outside_view && frame.outside_camera_view(c)) continue;
      // FAULT: faces classified against the light's position read as a direction (w = 0).
      const Vec4<float> classify = faults.light_position_as_direction ? Vec4<float>(light.x(), light.y(), light.z(), 0.0f) : light;
      const Result<std::size_t> edges = find_silhouette(caster, classify, sil);
      if (!edges) {
        frame.result.notes.push_back("light " + std::to_string(i) + ", " + name + ": " + edges.message());
        continue;
      }
      sil.light = light;  // extruded from the light itself (the same light unless the fault is on)
      if (sil.lit_count == 0) continue;  // no lit face: no prism, nothing to draw
      StencilMethod method = mode == Mode::ZPass ? StencilMethod::ZPass : StencilMethod::ZFail;
      if (mode == Mode::Robust && faults.robust_always_zpass) {
        method = StencilMethod::ZPass;  // FAULT: the near-plane test skipped, depth-pass everywhere
      } else if (mode == Mode::Robust && near) {
        const BoundingSphere<double> sphere{bsphere.center.cast<double>(),
                                            // a float radius rounded down could miss a vertex: widen
                                            // it by a few float ulps of the sphere's scale
                                            static_cast<double>(bsphere.radius) * (1.0 + 1e-6) +
                                                1e-6 * bsphere.center.cast<double>().cwiseAbs().maxCoeff()};
        const Result<StencilMethod> m = choose_stencil_method(*near, frame.light(i), sphere);
        method = m ? *m : StencilMethod::ZFail;
        robust_choice += (robust_choice.empty() ? "" : ", ") + name + " " + to_string(method);
      }
      VolumeOptions<float> options;
      options.light_cap = options.dark_cap = method == StencilMethod::ZFail && !faults.no_caps;  // FAULT: open volumes
      if (mode == Mode::Finite) options.finite_distance = kFiniteExtrusionRadii * bsphere.radius;
      const Result<VolumeRanges> ranges = build_shadow_volume(caster, sil, options, volume);
      if (!ranges) {
        frame.result.notes.push_back("light " + std::to_string(i) + ", " + name + ": no volume (" +
                                     ranges.message() + ")");
        continue;
      }
      if (volume.indices.empty()) continue;
      const GpuMesh mesh(gl, volume.vertices, volume.indices);
      set_stencil_ops(gl, method, faults);
      mesh.draw();
    }
    if (!robust_choice.empty()) frame.result.notes.push_back("light " + std::to_string(i) + ": " + robust_choice);
    gl.Disable(GL_DEPTH_CLAMP);
    frame.result.masks.push_back(frame.read_stencil_mask(0, /*value_is_lit=*/true));

    // Light i where the count is zero.
    gl.StencilFunc(GL_EQUAL, 0, 0xFF);
    gl.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    frame.light_pass(clip, i);
    gl.Disable(GL_STENCIL_TEST);
  }
  frame.result.shaded = frame.read_rgb();
}

}  // namespace

void render_volume_zpass(Frame& frame) { render_volumes(frame, Mode::ZPass); }
void render_volume_zfail(Frame& frame) { render_volumes(frame, Mode::ZFail); }
void render_volume_zfail_clamp(Frame& frame) { render_volumes(frame, Mode::ZFailClamp); }
void render_volume_robust(Frame& frame) { render_volumes(frame, Mode::Robust); }
void render_volume_finite(Frame& frame) { render_volumes(frame, Mode::Finite); }

}  // namespace shadowref::renderer
