// faults.cpp — the fault switches described for messages and render.json (faults.hpp).
#include "shadowref/renderer/faults.hpp"

#include <cstdio>

namespace shadowref::renderer {

std::string describe(const Faults& f) {
  std::string out;
  const auto on = [&](bool value, const char* name) {
    if (value) out += (out.empty() ? "" : ", ") + std::string(name);
  };
  on(f.camera.half_pixel_offset, "camera.half_pixel_offset");
  on(f.planar.matrix_transposed, "planar.matrix_transposed");
  on(f.planar.directional_as_point, "planar.directional_as_point");
  on(f.planar.darken_every_fragment, "planar.darken_every_fragment");
  on(f.volume.no_caps, "volume.no_caps");
  on(f.volume.robust_always_zpass, "volume.robust_always_zpass");
  on(f.volume.light_position_as_direction, "volume.light_position_as_direction");
  on(f.volume.saturating_stencil, "volume.saturating_stencil");
  on(f.volume.cull_casters_outside_view, "volume.cull_casters_outside_view");
  const ShadowMapFaults& s = f.shadow_map;
  on(s.compare == CompareFault::Reversed, "shadow_map.compare=reversed");
  on(s.compare == CompareFault::ConventionIgnored, "shadow_map.compare=convention_ignored");
  on(s.clear_to_one, "shadow_map.clear_to_one");
  on(s.offset_sign_ignored, "shadow_map.offset_sign_ignored");
  on(s.no_bias_matrix, "shadow_map.no_bias_matrix");
  on(s.neg_one_to_one_bias, "shadow_map.neg_one_to_one_bias");
  on(s.no_polygon_offset, "shadow_map.no_polygon_offset");
  on(s.large_constant_offset, "shadow_map.large_constant_offset");
  const std::string world = "shadow_map.constant_offset_world=" + std::to_string(s.constant_offset_world);
  on(s.constant_offset_world > 0, world.c_str());
  on(s.cull_casters_outside_view, "shadow_map.cull_casters_outside_view");
  on(s.skin_bind_pose, "shadow_map.skin=bind_pose");
  on(s.fit == FitFault::NearTooTight, "shadow_map.fit=near_too_tight");
  on(s.fit == FitFault::FarTooTight, "shadow_map.fit=far_too_tight");
  on(s.cube == CubeFault::ZFacesSwapped, "shadow_map.cube=z_faces_swapped");
  on(s.cube == CubeFault::YFacesUpsideDown, "shadow_map.cube=y_faces_upside_down");
  on(s.half_texel_offset, "shadow_map.half_texel_offset");
  on(s.lookup_y_flipped, "shadow_map.lookup_y_flipped");
  on(s.light_direction_mirrored_x, "shadow_map.light_direction_mirrored_x");
  on(s.alpha == AlphaFault::Ignored, "shadow_map.alpha=ignored");
  on(s.alpha == AlphaFault::CutoffHalf, "shadow_map.alpha=cutoff_half");
  on(s.alpha == AlphaFault::VertexAlphaIgnored, "shadow_map.alpha=vertex_alpha_ignored");
  on(s.cull_open_front_faces, "shadow_map.cull_open_front_faces");
  on(f.cascade.gap, "cascade.gap");
  on(f.cascade.slice_depth_range, "cascade.slice_depth_range");
  on(f.cascade.no_snapping, "cascade.no_snapping");
  on(f.cascade.frustum_behind_camera, "cascade.frustum_behind_camera");
  on(f.soft.blocker_depth_from_receiver, "soft.blocker_depth_from_receiver");
  on(f.soft.taps_stay_in_face, "soft.taps_stay_in_face");
  on(f.soft.search_whole_cone, "soft.search_whole_cone");
  if (f.soft.light_size_scale != 1.0) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "soft.light_size_scale=%g", f.soft.light_size_scale);
    on(true, buf);
  }
  return out;
}

}  // namespace shadowref::renderer
