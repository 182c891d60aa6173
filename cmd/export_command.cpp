// export_command.cpp — `shadowref export`: the scene pack an engine team renders with its own
// engine and hands back to `shadowref conform --candidate-dir`.
//
// The pack (OUT/):
//   README.md                    what to render, how to name the files, how to get a verdict
//   manifest.json                scenes, resolutions, lights, techniques with the expectations
//   scenes/<scene>.json          the scene files as the catalogue has them (+ scenes/meshes/)
//   <scene>/meshes/<object>.obj  every object in world space (the transform applied), CCW outside
//   <scene>/meshes/<object>.gltf the same as glTF 2.0 (one embedded buffer)
//   <scene>/scene.gltf           the whole scene as glTF 2.0: every object, the camera, the lights
//                                (KHR_lights_punctual), for engines that load a scene in one call
//   <scene>/matrices.json        per run convention (gl, gl-zo, reversed-z, d3d): the camera's view,
//                                projection (infinite, and a finite one), view-projection, the world
//                                mirror, the bias matrix and every light's shadow-map views; per light
//                                its parameters, homogeneous point and planar shadow matrix — every
//                                matrix in canonical (column vectors) and D3DX (row vectors) layout
//   <scene>/reference/           mask(_<i>).png, decided(_<i>).png, covered.png, shaded.png, visibility(_<i>).exr
// Every matrix comes from mathlib (view.hpp, projection.hpp, shadow_matrix.hpp, shadow_map.hpp,
// d3dx.hpp) through scene/camera.hpp: the ones our renderer and the reference use.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <system_error>

#include "command.hpp"
#include "shadowref/compare/compare.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/staged_folder.hpp"
#include "shadowref/outputs/spare_cores.hpp"
#include "shadowref/conform/catalogue.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/d3dx.hpp"
#include "shadowref/projection.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/scene/prepared_scene.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/shadow_map.hpp"
#include "shadowref/shadow_matrix.hpp"
#include "shadowref/outputs/json_text.hpp"

namespace shadowref::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct ExportArgs {
  std::string out;
  std::string scenes;
  std::string catalogue;
  std::string cache;  // empty: a cache inside the staging folder, removed before the pack is committed
  int jobs = 0;
};

json rows(const Mat4<double>& m) {
  json a = json::array();
  for (int r = 0; r < 4; ++r) a.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  return a;
}

// {"canonical": rows of M (v' = M v), "d3dx": fields _11.._44 row by row (v' = v M)}
json both_layouts(const Mat4<double>& m) {
  const D3dxMatrix<double> d = to_d3dx(m);
  json a = json::array();
  for (int r = 0; r < 4; ++r) a.push_back({d.m[r][0], d.m[r][1], d.m[r][2], d.m[r][3]});
  return {{"canonical", rows(m)}, {"d3dx", a}};
}

void write_text(const fs::path& file, const std::string& text) { outputs::write_file_atomically(file, text); }

std::string safe_name(std::string s) {
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) c = '_';
  return s;
}

void write_obj(const scene::Object& o, const fs::path& file) {
  std::string t = "# shadowref export: " + o.name + " in world space, counter-clockwise = outside\no " + o.name + "\n";
  char buf[128];
  for (const auto& p : o.mesh.positions) {
    std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", static_cast<double>(p.x()), static_cast<double>(p.y()),
                  static_cast<double>(p.z()));
    t += buf;
  }
  for (const auto& tri : o.mesh.triangles) {
    std::snprintf(buf, sizeof buf, "f %u %u %u\n", tri[0] + 1, tri[1] + 1, tri[2] + 1);
    t += buf;
  }
  write_text(file, t);
}

std::string base64(const std::string& bytes) {
  static constexpr char k[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8);
    out += {k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

// glTF 2.0 meshes appended into one embedded buffer: float positions and uint32 indices (both
// 4-byte elements, so every buffer view stays aligned without padding).
struct GltfMeshes {
  std::string buffer;
  json buffer_views = json::array();
  json accessors = json::array();
  json meshes = json::array();

  // Appends o's mesh with `material` (none when negative); returns the mesh index.
  int add(const scene::Object& o, int material = -1) {
    const std::size_t position_offset = buffer.size();
    Vec3<float> lo = o.mesh.positions.front(), hi = lo;
    for (const auto& p : o.mesh.positions) {
      buffer.append(reinterpret_cast<const char*>(p.data()), 3 * sizeof(float));
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const std::size_t index_offset = buffer.size();
    for (const auto& tri : o.mesh.triangles) buffer.append(reinterpret_cast<const char*>(tri.data()), 3 * sizeof(std::uint32_t));
    const std::size_t view = buffer_views.size();
    buffer_views.push_back({{"buffer", 0}, {"byteOffset", position_offset}, {"byteLength", index_offset - position_offset}, {"target", 34962}});
    buffer_views.push_back({{"buffer", 0}, {"byteOffset", index_offset}, {"byteLength", buffer.size() - index_offset}, {"target", 34963}});
    const std::size_t accessor = accessors.size();
    accessors.push_back({{"bufferView", view}, {"componentType", 5126}, {"count", o.mesh.positions.size()}, {"type", "VEC3"},
                         {"min", {lo.x(), lo.y(), lo.z()}}, {"max", {hi.x(), hi.y(), hi.z()}}});
    accessors.push_back({{"bufferView", view + 1}, {"componentType", 5125}, {"count", 3 * o.mesh.triangles.size()}, {"type", "SCALAR"}});
    json primitive = {{"attributes", {{"POSITION", accessor}}}, {"indices", accessor + 1}, {"mode", 4}};
    if (material >= 0) primitive["material"] = material;
    meshes.push_back({{"name", o.name}, {"primitives", {primitive}}});
    return static_cast<int>(meshes.size() - 1);
  }

  void into(json& g) const {
    g["buffers"] = {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}};
    g["bufferViews"] = buffer_views;
    g["accessors"] = accessors;
    g["meshes"] = meshes;
  }
};

// glTF 2.0: one object's mesh, in world space like the OBJ.
void write_gltf(const scene::Object& o, const fs::path& file) {
  GltfMeshes m;
  m.add(o);
  json g;
  g["asset"] = {{"version", "2.0"}, {"generator", "shadowref export"}};
  g["scene"] = 0;
  g["scenes"] = {{{"nodes", {0}}}};
  g["nodes"] = {{{"name", o.name}, {"mesh", 0}}};
  m.into(g);
  write_text(file, outputs::json_text(g) + "\n");
}

// glTF's node.matrix: the 16 values column by column.
json column_major(const Mat4<double>& m) {
  json a = json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a.push_back(m(r, c));
  return a;
}

// A rigid node transform at `position` whose local -z (where glTF cameras look and glTF lights
// shine) is `forward` (unit). Its up is scene +y unless `forward` is (nearly) vertical, then -z:
// the roll of a light does not matter, only where its -z points.
Mat4<double> node_facing(const Vec3<double>& position, const Vec3<double>& forward) {
  const Vec3<double> z = -forward.normalized();
  const Vec3<double> up = std::abs(z.y()) > 0.99 ? Vec3<double>(0, 0, -1) : Vec3<double>(0, 1, 0);
  const Vec3<double> x = up.cross(z).normalized();
  const Vec3<double> y = z.cross(x);
  Mat4<double> m = Mat4<double>::Identity();
  m.block<3, 1>(0, 0) = x;
  m.block<3, 1>(0, 1) = y;
  m.block<3, 1>(0, 2) = z;
  m.block<3, 1>(0, 3) = position;
  return m;
}

json vec3(const Vec3<double>& v) { return {v.x(), v.y(), v.z()}; }

// <scene>/scene.gltf: the whole scene in one glTF 2.0 file, for engines that load a scene in one
// call. Scene coordinates are glTF's own (right-handed, y up, metres), so nothing is converted:
//   every object: a node without transform (its mesh is in world space, as the OBJs), its colour as
//     an unlit-looking material (metallic 0, roughness 1); single-sided, counter-clockwise outside;
//   the camera: a perspective camera (yfov, aspectRatio = W / H, znear, zfar only when the scene's
//     camera has one: the pack's projection is infinite otherwise) on a node whose matrix is the
//     inverse of the gl convention's view; extras carry the gl view and projections exactly;
//   the lights: KHR_lights_punctual, in the order of matrices.json's lights (their mask order):
//     point, spot (outerConeAngle = the pack's cone half-angle) and directional; a rect light is a
//     point light at its centre (what hard techniques approximate it by) with its parallelogram in
//     extras.
void write_scene_gltf(const scene::Scene& s, const fs::path& file) {
  GltfMeshes m;
  json g;
  g["asset"] = {{"version", "2.0"}, {"generator", "shadowref export"}};
  json nodes = json::array();
  json materials = json::array();
  for (const scene::Object& o : s.objects) {
    materials.push_back({{"name", o.name},
                         {"pbrMetallicRoughness",
                          {{"baseColorFactor", {o.color.x(), o.color.y(), o.color.z(), 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}});
    const int mesh = m.add(o, static_cast<int>(materials.size() - 1));
    nodes.push_back({{"name", o.name}, {"mesh", mesh}, {"extras", {{"receiver", o.receiver}, {"shape", o.shape}}}});
  }
  // The camera, exactly as matrices.json's gl convention has it.
  const scene::PreparedScene gl = scene::prepare_scene(s, kDefaultConvention);
  json perspective = {{"yfov", s.camera.fovy_deg * std::numbers::pi / 180.0},
                      {"aspectRatio", static_cast<double>(s.width) / static_cast<double>(s.height)},
                      {"znear", s.camera.near}};
  if (s.camera.far) perspective["zfar"] = *s.camera.far;
  g["cameras"] = {{{"name", "camera"}, {"type", "perspective"}, {"perspective", perspective}}};
  nodes.push_back({{"name", "camera"},
                   {"camera", 0},
                   {"matrix", column_major(gl.camera.view.inverse())},
                   {"extras",
                    {{"convention", "gl"},
                     {"resolution", {s.width, s.height}},
                     {"view", rows(gl.camera.view)},
                     {"projection", rows(gl.camera.projection)},
                     {"projection_finite", rows(gl.camera_finite_for_clamp.projection)},
                     {"layout", "canonical rows (column vectors, v' = M v), as matrices.json's gl convention"}}}});
  json lights = json::array();
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const scene::Light& l = s.lights[i];
    json light = {{"name", "light_" + std::to_string(i)}, {"color", {1.0, 1.0, 1.0}}, {"intensity", 1.0}};
    json extras = {{"index", i}, {"shadowref_type", scene::to_string(l.type)}, {"mask_file", outputs::mask_name(i, s.lights.size())}};
    Mat4<double> at = Mat4<double>::Identity();
    switch (l.type) {
      case scene::LightType::Point:
        light["type"] = "point";
        at.block<3, 1>(0, 3) = l.position;
        break;
      case scene::LightType::Spot:
        light["type"] = "spot";
        light["spot"] = {{"innerConeAngle", 0.0}, {"outerConeAngle", l.cone_deg * std::numbers::pi / 180.0}};
        extras["note"] = "the cone shapes lighting only; the mask is the visibility of the position";
        at = node_facing(l.position, l.direction);
        break;
      case scene::LightType::Directional:
        light["type"] = "directional";
        at = node_facing(Vec3<double>::Zero(), -l.direction);
        extras["direction_toward_light"] = vec3(l.direction);
        break;
      case scene::LightType::Rect:
        light["type"] = "point";
        at.block<3, 1>(0, 3) = l.corner + 0.5 * (l.edge_u + l.edge_v);
        extras["corner"] = vec3(l.corner);
        extras["edge_u"] = vec3(l.edge_u);
        extras["edge_v"] = vec3(l.edge_v);
        extras["size"] = {{"edge_u_length", l.edge_u.norm()},
                          {"edge_v_length", l.edge_v.norm()},
                          {"equal_area_square_side", std::sqrt(l.edge_u.cross(l.edge_v).norm())}};
        extras["note"] = "a rect light: the point light at its centre is what hard techniques are judged with; soft ones use the "
                         "parallelogram (corner, edge_u, edge_v)";
        break;
    }
    light["extras"] = extras;
    lights.push_back(light);
    nodes.push_back({{"name", "light_" + std::to_string(i)},
                     {"matrix", column_major(at)},
                     {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}});
  }
  json scene_nodes = json::array();
  for (std::size_t n = 0; n < nodes.size(); ++n) scene_nodes.push_back(n);
  g["scene"] = 0;
  g["scenes"] = {{{"name", s.name}, {"nodes", scene_nodes}}};
  g["nodes"] = nodes;
  g["materials"] = materials;
  if (!lights.empty()) {
    g["extensionsUsed"] = {"KHR_lights_punctual"};
    g["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
  }
  m.into(g);
  write_text(file, outputs::json_text(g) + "\n");
}

// The matrices of one run convention (convention.hpp), from the prepared scene: the very ones our
// renderer and the reference use when run with --convention NAME.
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
  json lights = json::array();
  for (const LightFit& fit : p.light_fits) {
    json l;
    l["kind"] = fit.cube ? "cube (6 views: +x, -x, +y, -y, +z, -z of scene space)" : "single view";
    l["map_size"] = fit.size;
    json views = json::array();
    for (const LightView& v : fit.views) {
      views.push_back({{"view", both_layouts(v.view)},
                       {"projection", both_layouts(v.projection)},
                       {"shadow_from_scene", both_layouts(Mat4<double>(shadow_bias<double>(c) * v.projection * v.view))},
                       {"empty", v.empty}});
    }
    l["views"] = views;
    lights.push_back(l);
  }
  j["light_views"] = lights;
  // Views an engine can use as they are (its own shadow maps, declared "light_views": "own"): a point
  // or rect light as an OpenGL cube map, exactly 90 degrees per face, no guard band, in GL's face
  // order and orientation; a spot or directional light as its one view; every map a power of two.
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
    const auto add = [&](const LightView& v) {
      views.push_back({{"view", both_layouts(v.view)},
                       {"projection", both_layouts(v.projection)},
                       {"shadow_from_scene", both_layouts(Mat4<double>(shadow_bias<double>(c) * v.projection * v.view))}});
    };
    if (!cube) {
      l["kind"] = "single view (the pack's: a single view has no guard band)";
      for (const LightView& v : fit.views) add(v);
    } else if (c.clip.hand == Handedness::Right) {
      l["kind"] = "OpenGL cube map (GL_TEXTURE_CUBE_MAP_POSITIVE_X + i: +x, -x, +y, -y, +z, -z; 90 degrees, no guard band)";
      for (const LightView& v : gl_cube_map_views(c, p.lights[i].head<3>(), meshes)) add(v);
    } else {
      l["kind"] = "none: OpenGL's cube-map orientation is defined in a right-handed world; use gl, gl-zo or reversed-z";
    }
    l["views"] = views;
    engine.push_back(l);
  }
  j["engine_light_views"] = engine;
  // The cascaded techniques' views (csm, csm-pcf): a directional light's cascades, any other light's
  // views as above.
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
    for (const LightView& v : fit.views)
      views.push_back({{"view", both_layouts(v.view)},
                       {"projection", both_layouts(v.projection)},
                       {"shadow_from_scene", both_layouts(Mat4<double>(shadow_bias<double>(c) * v.projection * v.view))}});
    l["views"] = views;
    cascades.push_back(l);
  }
  j["cascade_views"] = cascades;
  return j;
}

json matrices(const scene::Scene& s) {
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
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
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
    lights.push_back(l);
  }
  j["lights"] = lights;
  return j;
}

// The error image's colours, from the one definition (compare.hpp's kErrorColours).
std::string error_image_legend() {
  const compare::ErrorColours& c = compare::kErrorColours;
  const auto rgb = [](const unsigned char (&v)[3]) {
    return "rgb(" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) + ")";
  };
  return "## Reading the error image\n\n"
         "Each case's `error.png` (`error_<i>.png` per light) paints the wrong pixels over your dimmed reference:\n\n"
         "| colour | meaning |\n| --- | --- |\n"
         "| " + rgb(c.false_shadow) + " red | false shadow, unexplained (reference lit) |\n"
         "| " + rgb(c.acne) + " yellow | false shadow, unexplained: self-shadowing (acne) |\n"
         "| " + rgb(c.false_light) + " blue | false light, unexplained (reference shadowed) |\n"
         "| " + rgb(c.coverage) + " magenta | coverage: a surface in one, none in the other |\n"
         "| " + rgb(c.texel) + " orange | explained: within the texel footprint of a real boundary |\n"
         "| " + rgb(c.bias) + " cyan | explained: within the bias a correct map needs at a contact |\n"
         "| " + rgb(c.undecided) + " dark green | undecided: not judged |\n\n";
}

std::string readme(const json& manifest) {
  std::string t =
      "# shadowref scene pack\n\n"
      "Render each scene below with your engine and let `shadowref conform` judge the shadows exactly as it judges\n"
      "ours: pixel by pixel against a ray-traced reference, on the pixels whose answer is certain. The pack stands\n"
      "alone: every command below runs in this folder, with no shadowref source tree.\n\n"
      "## The world\n\n"
      "Right-handed, y up: every position, direction and mesh in this pack is in that one world frame. The objects\n"
      "are in `<scene>/meshes/` (OBJ or glTF, world space, counter-clockwise = outside), seen through the camera of\n"
      "`<scene>/matrices.json` at the scene's resolution, lit by its lights: `homogeneous` (x, y, z, w) is w = 1 a\n"
      "point light at xyz, w = 0 a directional light with xyz pointing toward the light; spot and rect lights are\n"
      "listed with all their parameters, and the mask is the visibility of the light's homogeneous point: a spot\n"
      "light's position, and **a rect light's centre** (hard techniques are judged with that point; soft ones, below,\n"
      "with the whole rect).\n"
      "**Faces turned away from a light are shadowed** (their own, attached shadow: 0 in the mask), not lit.\n\n"
      "**A spot light's cone is lighting, not shadow**: its mask is the occlusion of the spot's position in every\n"
      "direction, outside the cone too. An engine whose spot shadow covers only the cone (its shadow frustum is the\n"
      "cone) gets that mask by rendering the spot's shadow as a point light's at the same position (a cube of views),\n"
      "or by widening the shadow frustum until it covers every surface the camera sees.\n\n"
      "**A filtered hard technique** (PCF, bilinear or Poisson compares) writes a pixel lit when at least half of its\n"
      "filter's weight is lit (a filtered value of 0.5 or more), as our `shadowmap-pcf` does; not the picture of a\n"
      "light that saturates, whose threshold depends on the light's intensity.\n\n"
      "## The whole scene in one glTF\n\n"
      "`<scene>/scene.gltf` opens in any glTF 2.0 loader in one call (three.js `GLTFLoader`, Babylon `SceneLoader`,\n"
      "Filament `gltfio`, Godot, Blender, tinygltf). glTF's frame is this pack's (right-handed, y up), so nothing is\n"
      "converted. It holds:\n\n"
      "- every object as a node without transform (its mesh in world space, as in `meshes/`), in the order of\n"
      "  `matrices.json`'s `objects`, with the object's colour as material (`doubleSided` false: counter-clockwise =\n"
      "  outside) and `extras.receiver`; no normals (glTF loaders then use flat ones);\n"
      "- the camera: a perspective camera with `yfov`, `aspectRatio` = W / H and `znear`, and no `zfar`: an infinite\n"
      "  far plane, as `conventions.gl.projection`; its node's matrix is the inverse of `conventions.gl.view`, and its\n"
      "  `extras` carry the exact `view`, `projection` and `projection_finite` (canonical rows) and the `resolution`;\n"
      "- the lights through `KHR_lights_punctual`, in the masks' order (`extras.index`, `extras.mask_file`): point,\n"
      "  spot (`outerConeAngle` = the cone half-angle, `innerConeAngle` 0) and directional (shining along its\n"
      "  node's -z); a **rect light is a point light at its centre** (the point hard techniques are judged with)\n"
      "  with `extras.shadowref_type` \"rect\", its `corner`, `edge_u`, `edge_v` and `size`. Intensities are 1: the\n"
      "  mask is shadow only.\n\n"
      "## The matrices\n\n"
      "`matrices.json` has, under `conventions`, the camera and every light's shadow-map views in each depth convention\n"
      "we render and judge in: `gl` (right-handed, -1..1), `gl-zo` (right-handed, 0..1), `reversed-z` (0..1 reversed,\n"
      "float depth, GREATER) and `d3d` (truly left-handed: the world mirrored in z by `world_from_scene`, then a\n"
      "left-handed look-at and projection, 0..1). Use the one your engine works in: `conventions.<name>.view`,\n"
      "`.projection` (an infinite far plane), `.projection_finite` (a far plane behind the whole scene),\n"
      "`.view_projection`, `.shadow_map_bias` and `.light_views[<light>].views[<view>]` (`view`, `projection`,\n"
      "`shadow_from_scene`; a cube has 6 views: +x, -x, +y, -y, +z, -z). Cascaded shadow maps (`csm`, `csm-pcf`) use\n"
      "`.cascade_views[<light>]`: for a directional light, `splits` (camera depths, from the near plane to the scene's\n"
      "far end), `camera_depth_from_scene` (the row that gives a scene point's camera depth) and one view per cascade;\n"
      "judged with those cascades (declare `\"cascades\"` in candidate.json if yours has another count, and\n"
      "`\"light_views\": \"own\"` if your splits or windows differ). Every matrix is given in canonical (column\n"
      "vectors, v' = M v) and D3DX (row vectors, v' = v M: the transpose) layout. The pack's light views are\n"
      "ours: a cube's faces reach 3 texels beyond 90 degrees (a guard band for filter taps) in our own face\n"
      "orientation, at sizes fitted to the scene (1331, 1855 ...). For an engine that renders its own maps,\n"
      "`.engine_light_views[<light>]` gives views it can use as they are: a point or rect light as an OpenGL cube\n"
      "map (six views, exactly 90 degrees, no guard band, in GL_TEXTURE_CUBE_MAP_POSITIVE_X + i order and\n"
      "orientation: render face i through view i into that face and sample it with a cube-map lookup), a spot or\n"
      "directional light as its one view, each with `map_size`, the pack's size rounded up to a power of two (gl,\n"
      "gl-zo and reversed-z; d3d has no cube there). Judge maps made with them as `\"light_views\": \"own\"` with\n"
      "that `shadow_map_size`: the judge takes the size you declare and, not knowing your texel grid, lets a lookup\n"
      "reach a whole texel instead of half of one. Pixel centres:\n"
      "`ndc.x = 2 (x + 0.5) / W - 1`, `ndc.y = 1 - 2 (y + 0.5) / H`, row 0 at the top (remove Direct3D 9's\n"
      "half-pixel offset).\n\n"
      "## What to write\n\n"
      "One folder per scene, named after it, holding the shadow mask your technique computes:\n\n"
      "```\n"
      "my-renders/<scene>/mask.png        one light: 8-bit grey PNG, W x H, row 0 at the top\n"
      "my-renders/<scene>/mask_<i>.png    several lights: one mask per light, in the order of matrices.json\n"
      "my-renders/<scene>/candidate.json  optional: who made the masks, and how (below)\n"
      "```\n\n"
      "Each pixel answers \"is the surface seen through this pixel centre lit by this light?\": **255 lit, 0 shadowed,\n"
      "128 no surface** (background). The encoding is strict: a mask holding any other value (a 10 or a 250 from\n"
      "filtering or gamma) is refused, with one line naming the file, how many pixels are off and the first one.\n"
      "Shadow only: no shading, no ambient, no spot-cone falloff (a spot light's cone is lighting, not shadow).\n"
      "`<scene>/reference/mask*.png` shows the expected answer; `decided*.png` marks (255) the pixels that are judged.\n"
      "Optionally add `shaded.png` (RGB) for the report. The mask set must be exactly the scene's lights: a missing\n"
      "mask, a `mask_<N>.png` beyond the last light, or `mask.png` beside `mask_0.png` is refused for that scene, as is\n"
      "a mask of another size (checked from its header). Files may be symbolic links; the report names those that\n"
      "lead out of your folder.\n\n"
      "`candidate.json`, beside each scene's masks, declares the producer and the settings the judge may explain\n"
      "wrong pixels by (every key is optional; the report lists the ones it assumed):\n\n"
      "```json\n"
      "{\n"
      "  \"producer\": \"my-engine\",       \"version\": \"4.2.1\",\n"
      "  \"technique\": \"shadowmap\",      \"convention\": \"gl\",\n"
      "  \"shadow_map_size\": 2048,       \"filter_radius_texels\": 1,\n"
      "  \"slope_bias_texels\": 2,        \"constant_bias\": 0.0,\n"
      "  \"light_views\": \"pack\",         \"cascades\": 4,\n"
      "  \"normal_offset\": 0.0,          \"normal_offset_texels\": 0.0,\n"
      "  \"depth_bias\": 0.0,             \"depth_faces\": \"back\",\n"
      "  \"settings\": { \"shadow_camera_far\": 50, \"anything\": \"recorded, never judged\" }\n"
      "}\n"
      "```\n\n"
      "`technique`: how it is judged; `convention`: gl, gl-zo, reversed-z or d3d; `shadow_map_size`: texels per side\n"
      "(16 .. 16384); `atlas_tile` instead, for a tile of a shadow atlas: `{\"size\": 683, \"guard_band\": 8}`, the tile's\n"
      "texels per side and the guard band along each side beyond the light's view (the view then spans size - 2 x\n"
      "guard_band texels, its map size); `filter_radius_texels`: how far the filter reaches beyond the centre texel (0 one tap, 1 a 3x3\n"
      "PCF box); `slope_bias_texels`: the slope-scaled bias as the depth change across this many texels\n"
      "(glPolygonOffset's factor); `constant_bias`: world units along the light ray; `normal_offset`: a normal-offset\n"
      "bias in world units (three.js and Babylon `normalBias`), `normal_offset_texels` the same in texels; `depth_bias`:\n"
      "a constant bias in the light projection's window depth, 0..1 over its near..far (three.js and Babylon `bias`, as\n"
      "a magnitude); `depth_faces`: the faces your depth pass draws (`front`, `back`, `both`); `depth`: `window` (a\n"
      "depth texture) or `distance` (a cube storing the distance from the light over a range, three.js and Babylon\n"
      "point lights: then `depth_bias` is in units of that range and `depth_range` gives it, far - near in world units;\n"
      "a polygon offset does not apply there, so declare `slope_bias_texels` 0, unless your shader adds a slope term\n"
      "of its own: then its factor); `light_views`: `pack`\n"
      "when your shadow maps use the light views of matrices.json (their texel grid is known: with a `shadow_map_size`\n"
      "and no filter, the judge checks that size against your masks' own staircases and judges a size they contradict\n"
      "as the automatic one), `own` when your engine fits its own (any turn or phase: the judge then reaches a whole\n"
      "texel of the declared size each way, enough for texels up to 1.41 times the pack's at that size); `cascades`:\n"
      "cascaded techniques only, cascades per directional light (0: the pack's 4);\n"
      "`light_taps`: soft techniques only, the filter's taps per axis over the light's area (8 for an 8x8 filter);\n"
      "`sampling`: `grid` (the default: a fixed kernel) or `random` (taps placed anew per pixel, e.g. a Poisson or\n"
      "Vogel disk rotated by noise; declare `light_taps` as the root of the tap count: 4 for 16 taps);\n"
      "`lights`: an array, one object per light in the pack's order, each overriding the keys above for that light\n"
      "(all but producer, version, technique, convention and settings), e.g. `[{}, {\"shadow_map_size\": 512}]`;\n"
      "`settings`: any object, your engine's own settings, recorded in the report and never judged. Any other key is\n"
      "refused with one line naming it.\n\n"
      "Declare what your engine does: a declaration can only narrow what the judge explains, never buy a verdict.\n"
      "A false shadow is never explained by the receiver's own surface (acne: yellow in the error image, counted as\n"
      "`unexplained_acne`), whatever bias you declare; a leak at a contact is explained only up to the bias a correct\n"
      "map needs there at your texel size (twice the slope bias that removes acne across your lookup's reach), so a\n"
      "larger bias shows as unexplained peter-panning; declaring less never improves a verdict. Unexplained pixels\n"
      "that come right when your shadows are moved back by a pixel or two (or shrunk or grown back) are counted as\n"
      "`displaced` (a half-pixel offset, a viewport off by one): above 1 % of the edge pixels they FAIL.\n\n"
      "## Soft shadows\n\n"
      "A soft technique (`--technique pcss`, percentage-closer soft shadows, or `vsm`, variance shadow maps filtered\n"
      "over PCSS's penumbra) is judged twice. Its `mask.png` as above\n"
      "(lit where at least half the light is), and, for every light with an area (`rect` in matrices.json, with its\n"
      "`size`), its lit fraction:\n\n"
      "```\n"
      "my-renders/<scene>/visibility.png      8-bit grey, round(255 x lit fraction); the background is mask.png's 128\n"
      "my-renders/<scene>/visibility_<i>.png  several lights: one per light, like the masks\n"
      "```\n\n"
      "The fraction is compared with the reference's (`reference/visibility.exr`: the fraction over the light's\n"
      "`reference_samples_per_axis`^2 points, averaged over the pixel) on the pixels one smooth surface covers\n"
      "(`reference/covered.png`). A pixel within the sampling tolerance 1/n + 1/light_taps + half an 8-bit step passes;\n"
      "beyond it, a pixel is explained when your fraction lies in the range the true fraction takes over your filter's\n"
      "footprint (`filter_radius_texels`); the rest is unexplained. FAIL: any 5x5 block unexplained, more than 3 % of\n"
      "the penumbra unexplained, or a mean error over the penumbra above what sampling alone leaves\n"
      "(1/(4n) + 1/(4 light_taps)): a penumbra of the wrong width. The report shows your fraction and its error image.\n"
      "With `\"sampling\": \"random\"` a pixel may err by three times the binomial spread of your light_taps^2 taps\n"
      "(1/n + 1.5/light_taps), the width is judged on 3x3 local means (FAIL above 1/(4n) + 1/(6 light_taps)), and\n"
      "noise that the local means remove is a WARN beyond 1/(4n) + 1/(2 light_taps), never a wrong width.\n\n"
      "Some expected failures predict the kind of their errors (`errors` in the scene file, e.g. `vsm` on\n"
      "light_bleeding: too light, light bleeding into a full shadow). Such a case is XFAIL only when the errors of the\n"
      "other kind, judged alone by the same bounds, pass; otherwise it is a FAIL that names them.\n\n"
      "## How to get the verdict\n\n"
      "In this folder:\n\n"
      "```sh\n"
      "shadowref conform --catalogue scenes --candidate-dir my-renders --technique shadowmap --out my-verdict\n"
      "shadowref conform --catalogue scenes --scenes ground_sphere --candidate-dir my-renders --technique shadowmap --out my-verdict\n"
      "```\n\n"
      "`--catalogue scenes` is this pack's copy of the scene files (the references are recomputed from them into\n"
      "`my-verdict/reference-cache`); `--scenes` picks some (comma-separated globs over the names below, e.g.\n"
      "`--scenes 'ground_sphere,soft_*'`). `--technique` picks the\n"
      "threshold (our technique names: planar, volume-*, shadowmap, shadowmap-pcf, shadowmap-rgba8, csm, csm-pcf, pcss, vsm;\n"
      "any other name\n"
      "gets the strictest) and the catalogue's expectations (a scene where the technique is known to fail expects a\n"
      "FAIL: see `manifest.json`). The table, `my-verdict/report.json` and `my-verdict/report/index.html` (reference,\n"
      "your mask and the error image side by side) follow. Exit code: 0 every case PASS or XFAIL, 1 quality warnings,\n"
      "2 failures.\n\n"
      "In CI (known failures in an expectations file, shards, one merged report): shadowref's docs/ci.md.\n\n";
  t += "## Which technique name is my engine?\n\n"
       "`--technique` and `candidate.json`'s `technique` pick the thresholds and the catalogue's expectations:\n\n"
       "| your engine's shadows | technique |\n| --- | --- |\n"
       "| casters flattened onto the receiver plane by a shadow matrix | `planar` |\n"
       "| stencil shadow volumes counted where they pass the depth test (no caps) | `volume-zpass` |\n"
       "| stencil volumes counted where they fail it, capped, far plane at infinity (Carmack's reverse) | `volume-zfail` |\n"
       "| the same with a finite far plane and depth clamp | `volume-zfail-clamp` |\n"
       "| z-pass where the near plane misses the volume, z-fail elsewhere | `volume-robust` |\n"
       "| volumes extruded by a finite distance | `volume-finite` |\n"
       "| a shadow map, one depth compare per pixel | `shadowmap` |\n"
       "| a shadow map with a filtered compare (PCF, bilinear, Poisson; declare `filter_radius_texels`) | `shadowmap-pcf` |\n"
       "| a shadow map of depth packed into an RGBA8 colour target | `shadowmap-rgba8` |\n"
       "| cascaded shadow maps, one compare / filtered | `csm` / `csm-pcf` |\n"
       "| percentage-closer soft shadows, contact hardening | `pcss` |\n"
       "| variance shadow maps | `vsm` |\n\n"
       "An engine's \"stencil shadows\" are usually z-fail volumes with caps (`volume-zfail`); judge them as\n"
       "`volume-robust` only when they switch to z-pass where the camera is outside every volume.\n\n";
  t += error_image_legend();
  t += "## Scenes\n\n| scene | resolution | lights | description |\n| --- | --- | --- | --- |\n";
  for (const json& s : manifest["scenes"])
    t += "| " + s["name"].get<std::string>() + " | " + std::to_string(s["resolution"][0].get<int>()) + "x" +
         std::to_string(s["resolution"][1].get<int>()) + " | " + std::to_string(s["lights"].get<int>()) + " | " +
         s["description"].get<std::string>() + " |\n";
  return t;
}

void run_export(const ExportArgs& a) {
  std::vector<fs::path> files;
  try {
    files = conform::select_scenes(a.catalogue.empty() ? conform::default_catalogue() : fs::path(a.catalogue),
                                   conform::split_list(a.scenes));
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
  // Every scene is loaded and validated before anything is written: a bad scene leaves no pack.
  std::vector<scene::Scene> scenes;
  for (const fs::path& f : files) {
    try {
      scenes.push_back(scene::load_scene(f));
    } catch (const scene::SceneError& e) {
      throw BadInput(e.what());
    }
  }
  // The pack is written into a staging folder beside --out and renamed into place when complete,
  // so an interrupted or failed export never leaves a folder that looks like a pack.
  const fs::path final_out = fs::absolute(fs::path(a.out)).lexically_normal();
  std::error_code ec;
  if (fs::exists(final_out, ec)) {
    const bool is_pack = fs::exists(final_out / "manifest.json", ec);
    const bool is_empty = fs::is_directory(final_out, ec) && fs::is_empty(final_out, ec);
    if (!is_pack && !is_empty)
      throw BadInput("--out " + a.out + ": exists and is not a shadowref pack (no manifest.json): choose another folder");
  }
  outputs::StagedFolder staging(final_out);
  const fs::path& out = staging.path();
  fs::create_directories(out / "scenes", ec);
  if (ec) throw BadInput("--out " + a.out + ": " + ec.message());
  conform::ReferenceSettings settings;
  settings.threads = a.jobs > 0 ? a.jobs : outputs::spare_cores();
  // Export writes only under --out: without --cache, the references are computed into the staging
  // folder and the cache is dropped before the commit (the pack keeps copies in <scene>/reference/).
  const fs::path private_cache = out / ".reference-cache";
  const fs::path cache = a.cache.empty() ? private_cache : fs::path(a.cache);
  json manifest;
  manifest["tool"] = "shadowref export";
  manifest["mask_values"] = {{"lit", outputs::kMaskLit}, {"shadowed", outputs::kMaskShadowed}, {"no_surface", outputs::kMaskNoSurface}};
  manifest["scenes"] = json::array();
  for (std::size_t k = 0; k < files.size(); ++k) {
    const fs::path& f = files[k];
    const scene::Scene& s = scenes[k];
    const fs::path dir = out / s.name;
    fs::create_directories(dir / "meshes");
    // The scene file, and the mesh files it names next to it (the same relative paths).
    fs::copy_file(f, out / "scenes" / f.filename(), fs::copy_options::overwrite_existing);
    {
      std::ifstream in(f);
      const json sj = json::parse(in, nullptr, false);
      if (sj.is_object() && sj.contains("objects"))
        for (const auto& o : sj["objects"])
          if (o.contains("shape") && o["shape"].contains("file")) {
            const fs::path rel = o["shape"]["file"].get<std::string>();
            fs::create_directories((out / "scenes" / rel).parent_path());
            fs::copy_file(f.parent_path() / rel, out / "scenes" / rel, fs::copy_options::overwrite_existing);
          }
    }
    json objects = json::array();
    for (const scene::Object& o : s.objects) {
      const std::string n = safe_name(o.name);
      write_obj(o, dir / "meshes" / (n + ".obj"));
      write_gltf(o, dir / "meshes" / (n + ".gltf"));
      objects.push_back({{"name", o.name}, {"obj", "meshes/" + n + ".obj"}, {"gltf", "meshes/" + n + ".gltf"},
                         {"receiver", o.receiver}, {"color", {o.color.x(), o.color.y(), o.color.z()}}});
    }
    write_scene_gltf(s, dir / "scene.gltf");
    json m = matrices(s);
    m["objects"] = objects;
    m["scene_gltf"] = "scene.gltf";
    write_text(dir / "matrices.json", outputs::json_text(m, 2) + "\n");
    const conform::CachedReference ref = conform::ensure_reference(scene::prepare_scene(s), cache, settings);
    fs::remove_all(dir / "reference", ec);
    fs::create_directories(dir / "reference");
    for (const auto& e : fs::directory_iterator(ref.dir))
      if (e.path().filename() != "key.json") fs::copy_file(e.path(), dir / "reference" / e.path().filename());
    json expect = json::object();
    for (const auto& [t, e] : s.expect)
      expect[t] = !e.pass ? json{{"result", "fail"}, {"why", e.why}}
                  : e.warn ? json{{"result", "warn"}, {"why", e.why}}
                           : json{{"result", "pass"}};
    manifest["scenes"].push_back({{"name", s.name},
                                  {"description", s.description},
                                  {"resolution", {s.width, s.height}},
                                  {"lights", s.lights.size()},
                                  {"scene_file", "scenes/" + f.filename().string()},
                                  {"expect", expect}});
    std::printf("exported %s (%zu objects, %zu light(s), reference %s)\n", s.name.c_str(), s.objects.size(),
                s.lights.size(), ref.computed ? "computed" : "cached");
  }
  if (a.cache.empty()) fs::remove_all(private_cache);
  write_text(out / "README.md", readme(manifest));
  write_text(out / "manifest.json", outputs::json_text(manifest, 2) + "\n");  // last: its presence marks a complete pack
  staging.commit();
  std::printf("pack: %s (README.md says what to render and how to name the files)\n", final_out.string().c_str());
}

}  // namespace

void register_export_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Write a scene pack for engine teams: scenes, meshes (OBJ, glTF), camera and light matrices in canonical and "
      "D3DX layout, reference masks, and a README saying what to render and how to name the files.");
  cmd->add_option("--out", args->out, "the pack folder")->required();
  cmd->add_option("--scenes", args->scenes, conform::kScenesHelp);
  cmd->add_option("--catalogue", args->catalogue, "scene folder (default: the installed catalogue; from the build tree, the source tree's)");
  cmd->add_option("--cache", args->cache, "reference cache folder, kept between runs (default: none; the references are computed inside the "
                  "pack's staging folder, and nothing is written outside --out). `shadowref conform --out O` keeps "
                  "its cache in O/reference-cache: name it to reuse conform's references");
  cmd->add_option("--jobs", args->jobs, "reference threads (0: the cores the machine can spare, all less the one-minute load average, at least 1)")->check(CLI::Range(0, 256));
  cmd->callback([args, &exit_code] {
    run_export(*args);
    exit_code = kExitPass;
  });
}

}  // namespace shadowref::cli
