// matrices.cpp — a scene's matrices.json (matrices.hpp).
#include "shadowref/pack/matrices.hpp"

#include <bit>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "shadowref/cascades.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/light_fit.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/pack/matrix_json.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/shadow_matrix.hpp"

namespace shadowref::pack {
namespace {

using nlohmann::json;

// One light view: its view and projection, and the scene-to-map-texture matrix (bias · P · V).
json view_json(const RunConvention& c, const LightView& v) {
  return {{"view", both_layouts(v.view)},
          {"projection", both_layouts(v.projection)},
          {"shadow_from_scene", both_layouts(Mat4<double>(shadow_bias<double>(c) * v.projection * v.view))}};
}

// The pack's own light views (those the reference's cause model and our renderer use): a cube's
// faces reach beyond 90 degrees (a guard band), at sizes fitted to the scene.
json pack_light_views(const scene::PreparedScene& p) {
  json lights = json::array();
  for (const LightFit& fit : p.light_fits) {
    json l;
    l["kind"] = fit.cube ? "cube (6 views: +x, -x, +y, -y, +z, -z of scene space)" : "single view";
    l["map_size"] = fit.size;
    json views = json::array();
    for (const LightView& v : fit.views) {
      views.push_back(view_json(*p.convention, v));
      views.back()["empty"] = v.empty;
    }
    l["views"] = views;
    lights.push_back(l);
  }
  return lights;
}

// The cascaded techniques' views (csm, csm-pcf): a directional light's cascades, any other light's
// views as the pack's.
json cascade_views(const scene::PreparedScene& p) {
  json cascades = json::array();
  for (const LightFit& fit : p.cascade_fits) {
    json l;
    l["map_size"] = fit.size;
    if (!fit.cascade_splits.empty()) {
      l["kind"] = "cascades (cascade i decides the points whose camera depth lies in [splits[i], splits[i+1]))";
      l["splits"] = fit.cascade_splits;
      // How they were made (mathlib/cascades.hpp): the practical split scheme (Zhang et al. 2006)
      // with this weight; each window the slice's bounding sphere widened by the margin, snapped to
      // whole texels.
      l["split_weight"] = kDefaultSplitWeight;
      l["window_margin_texels"] = kCascadeMarginTexels;
      const Vec4<double>& d = fit.cascade_depth_from_scene;
      l["camera_depth_from_scene"] = {d.x(), d.y(), d.z(), d.w()};
    } else {
      l["kind"] = fit.cube ? "cube (6 views: +x, -x, +y, -y, +z, -z of scene space)" : "single view";
    }
    json views = json::array();
    for (const LightView& v : fit.views) views.push_back(view_json(*p.convention, v));
    l["views"] = views;
    cascades.push_back(l);
  }
  return cascades;
}

// One light's parameters, its homogeneous point and mask file, and its planar shadow matrix onto
// the receiver plane (when the scene has one).
json light_json(const scene::Scene& s, std::size_t i, const std::optional<Plane<double>>& plane) {
  const scene::Light& sl = s.lights[i];
  const Vec4<double> L = scene::homogeneous(sl);
  json l;
  l["type"] = scene::to_string(sl.type);
  l["homogeneous"] = {L.x(), L.y(), L.z(), L.w()};
  switch (sl.type) {
    case scene::LightType::Point: l["position"] = {sl.position.x(), sl.position.y(), sl.position.z()}; break;
    case scene::LightType::Directional: l["direction_toward_light"] = {sl.direction.x(), sl.direction.y(), sl.direction.z()}; break;
    case scene::LightType::Spot:
      l["position"] = {sl.position.x(), sl.position.y(), sl.position.z()};
      l["direction"] = {sl.direction.x(), sl.direction.y(), sl.direction.z()};
      l["cone_half_angle_deg"] = sl.cone_deg;
      l["note"] = "the cone shapes lighting only; the mask is the visibility of the position";
      break;
    case scene::LightType::Rect:
      l["corner"] = {sl.corner.x(), sl.corner.y(), sl.corner.z()};
      l["edge_u"] = {sl.edge_u.x(), sl.edge_u.y(), sl.edge_u.z()};
      l["edge_v"] = {sl.edge_v.x(), sl.edge_v.y(), sl.edge_v.z()};
      // The light's size for soft techniques: its edges' lengths and the side of the square of equal area.
      l["size"] = {{"edge_u_length", sl.edge_u.norm()},
                   {"edge_v_length", sl.edge_v.norm()},
                   {"equal_area_square_side", std::sqrt(sl.edge_u.cross(sl.edge_v).norm())},
                   {"reference_samples_per_axis", sl.samples}};
      l["visibility_file"] = outputs::visibility_name(i, s.lights.size());
      l["note"] = "the mask is the visibility of the parallelogram's centre (homogeneous); the reference's visibility.exr is the "
                  "area light's lit fraction over samples_per_axis^2 stratified points, what a soft technique's visibility.png "
                  "is judged against";
      break;
  }
  l["mask_file"] = outputs::mask_name(i, s.lights.size());
  if (plane) {
    const Result<Mat4<double>> sm = shadow_matrix(*plane, L);
    if (sm) l["planar_shadow_matrix"] = both_layouts(*sm);
    else l["planar_shadow_matrix"] = sm.message();
  }
  return l;
}

}  // namespace

json convention_matrices(const scene::PreparedScene& p) {
  const RunConvention& c = *p.convention;
  json j;
  j["summary"] = c.summary;
  j["handedness"] = to_string(c.clip.hand);
  j["clip_depth"] = c.clip.order == DepthOrder::Reversed ? "one-to-zero (reversed)" : to_string(c.clip.depth);
  j["depth_buffer"] = c.float_depth ? "32-bit float" : "24-bit fixed point";
  j["depth_test"] = c.clip.order == DepthOrder::Reversed ? "GREATER" : "LESS";
  j["depth_clear"] = far_depth(c);
  j["shadow_compare_lit_when"] = c.clip.order == DepthOrder::Reversed ? "GEQUAL" : "LEQUAL";
  j["polygon_offset_sign"] = polygon_offset_sign(c);
  j["world_from_scene"] = both_layouts(world_from_scene<double>(c));
  j["view"] = both_layouts(p.camera.view);
  j["projection"] = both_layouts(p.camera.projection);
  j["view_projection"] = both_layouts(p.camera.clip_from_scene);
  j["projection_finite"] = both_layouts(p.camera_finite_for_clamp.projection);
  j["shadow_map_bias"] = both_layouts(shadow_bias<double>(c));
  j["light_views"] = pack_light_views(p);
  j["engine_light_views"] = engine_light_views(p);
  j["cascade_views"] = cascade_views(p);
  return j;
}

json engine_light_views(const scene::PreparedScene& p) {
  const RunConvention& c = *p.convention;
  json engine = json::array();
  std::vector<const TriangleMesh<float>*> meshes;
  for (const scene::Object& o : p.scene->objects) meshes.push_back(&o.mesh);
  for (std::size_t i = 0; i < p.light_fits.size(); ++i) {
    const LightFit& fit = p.light_fits[i];
    const scene::LightType type = p.scene->lights[i].type;
    const bool cube = type == scene::LightType::Point || type == scene::LightType::Rect;
    json l;
    l["map_size"] = std::bit_ceil(static_cast<unsigned>(fit.size));
    json views = json::array();
    if (!cube) {
      l["kind"] = "single view (the pack's: a single view has no guard band)";
      for (const LightView& v : fit.views) views.push_back(view_json(c, v));
    } else if (c.clip.hand == Handedness::Right) {
      l["kind"] = "OpenGL cube map (GL_TEXTURE_CUBE_MAP_POSITIVE_X + i: +x, -x, +y, -y, +z, -z; 90 degrees, no guard band)";
      for (const LightView& v : gl_cube_map_views(c, p.lights[i].head<3>(), meshes)) views.push_back(view_json(c, v));
    } else {
      l["kind"] = "none: OpenGL's cube-map orientation is defined in a right-handed world; use gl, gl-zo or reversed-z";
    }
    l["views"] = views;
    engine.push_back(l);
  }
  return engine;
}

json matrices_json(const scene::Scene& s) {
  json j;
  j["resolution"] = {s.width, s.height};
  j["pixel_convention"] =
      "row 0 is the top row; pixel (x, y) has its centre at ndc.x = 2 (x + 0.5) / W - 1, ndc.y = 1 - 2 (y + 0.5) / H "
      "(Direct3D 10+ and OpenGL both sample at pixel centres; Direct3D 9 needs its half-pixel offset removed)";
  j["world"] = "right-handed, y up (scene coordinates; the d3d convention mirrors z into a left-handed world: world_from_scene)";
  j["layouts"] = "canonical: column vectors, v' = M v, rows listed; d3dx: row vectors, v' = v M, fields _11.._44 row "
                 "by row (the transpose)";
  json cam;
  cam["position"] = {s.camera.position.x(), s.camera.position.y(), s.camera.position.z()};
  cam["target"] = {s.camera.target.x(), s.camera.target.y(), s.camera.target.z()};
  cam["up"] = {s.camera.up.x(), s.camera.up.y(), s.camera.up.z()};
  cam["fovy_deg"] = s.camera.fovy_deg;
  cam["near"] = s.camera.near;
  cam["far"] = s.camera.far ? json(*s.camera.far) : json("infinite");
  j["camera"] = cam;
  json conventions = json::object();
  for (const RunConvention& c : kRunConventions) conventions[std::string(c.name)] = convention_matrices(scene::prepare_scene(s, c));
  j["conventions"] = conventions;
  const std::optional<Plane<double>> plane = scene::receiver_plane(s);
  if (plane) j["receiver_plane"] = {plane->a(), plane->b(), plane->c(), plane->d()};
  json lights = json::array();
  for (std::size_t i = 0; i < s.lights.size(); ++i) lights.push_back(light_json(s, i, plane));
  j["lights"] = lights;
  return j;
}

}  // namespace shadowref::pack
