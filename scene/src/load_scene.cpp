// load_scene.cpp — scene files → Scene (load_scene.hpp). Parsing and validation in one pass:
// each part of the document is read through a JsonNode that knows its path, so every error
// names the file and the JSON path.
#include "shadowref/outputs/errors.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/limits.hpp"
#include "shadowref/scene/load_scene.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "json_node.hpp"
#include "receiver_check.hpp"
#include "shadowref/scene/gltf_scene.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/scene/identifier.hpp"
#include "shadowref/scene/path_within.hpp"
#include "shadowref/scene/mesh_file.hpp"
#include "shadowref/primitives.hpp"
#include "shadowref/scene/shapes.hpp"
#include "shadowref/outputs/techniques.hpp"

namespace shadowref::scene {
namespace {

using detail::JsonNode;

// Resolutions above outputs::kMaxResolution are refused before anything is allocated.
constexpr long long kMaxResolution = outputs::kMaxResolution;
// Tessellation limits: a sphere at 4096 × 4096 is 33 M triangles, beyond any sensible scene
// (and below primitives.hpp's own limit of 2^14, so its .value() never throws for a loaded value).
constexpr long long kMaxSegments = 4096;

void read_camera(const JsonNode& n, Scene& scene) {
  n.expect_object({"position", "target", "up", "fovy_deg", "near", "far"});
  Camera& c = scene.camera;
  c.position = n.required("position").vec3();
  c.target = n.required("target").vec3();
  if (auto up = n.optional("up")) c.up = up->vec3();
  if (auto f = n.optional("fovy_deg")) {
    c.fovy_deg = f->number();
    if (!(c.fovy_deg > 0 && c.fovy_deg < 180)) f->fail("must be in (0, 180) degrees");
  }
  if (n.has("near")) c.near = n.positive("near");
  if (auto f = n.optional("far")) {
    c.far = f->number();
    if (!(*c.far > c.near)) f->fail("must be > near (" + std::to_string(c.near) + ")");
  }
  // The matrices both renderers will build, checked here once, in both precisions they use.
  for (const auto& err : {view_matrix<double>(c).ok() ? std::optional<Error>() : view_matrix<double>(c).error(),
                          view_matrix<float>(c).ok() ? std::optional<Error>() : view_matrix<float>(c).error()}) {
    if (!err) continue;
    if (*err == Error::EyeAtTarget) n.fail_at("target", "must differ from position");
    if (*err == Error::UpParallelToView) n.fail_at("up", "must not be parallel to the viewing direction (target - position)");
    n.fail(describe(*err));
  }
  const auto pd = projection_matrix<double>(c, scene.width, scene.height);
  const auto pf = projection_matrix<float>(c, scene.width, scene.height);
  if (!pd.ok()) n.fail(pd.message());
  if (!pf.ok()) n.fail(std::string(pf.message()) + " (in float)");
}

Vec3<double> nonzero_direction(const JsonNode& n) {
  const Vec3<double> d = n.vec3();
  if (!(d.norm() > 0)) n.fail("must not be the zero vector");
  return d.normalized();
}

Light read_light(const JsonNode& n) {
  Light l;
  const std::string type = n.required("type").string();
  if (type == "point") {
    n.expect_object({"type", "position"});
    l.type = LightType::Point;
    l.position = n.required("position").vec3();
  } else if (type == "directional") {
    n.expect_object({"type", "direction"});
    l.type = LightType::Directional;
    l.direction = nonzero_direction(n.required("direction"));
  } else if (type == "spot") {
    n.expect_object({"type", "position", "direction", "cone_deg"});
    l.type = LightType::Spot;
    l.position = n.required("position").vec3();
    l.direction = nonzero_direction(n.required("direction"));
    const JsonNode cone = n.required("cone_deg");
    l.cone_deg = cone.number();
    if (!(l.cone_deg > 0 && l.cone_deg <= 90)) cone.fail("must be in (0, 90] degrees (the half-angle of the cone)");
  } else if (type == "rect") {
    n.expect_object({"type", "corner", "edge_u", "edge_v", "samples"});
    l.type = LightType::Rect;
    l.corner = n.required("corner").vec3();
    l.edge_u = n.required("edge_u").vec3();
    l.edge_v = n.required("edge_v").vec3();
    if (!(l.edge_u.cross(l.edge_v).norm() > 0)) n.fail_at("edge_v", "must not be zero or parallel to edge_u");
    l.samples = static_cast<int>(n.integer_in("samples", 1, 64, 4));
  } else {
    n.fail_at("type", "unknown light type '" + type + "' (expected point, directional, spot or rect)");
  }
  return l;
}

int segments_in(const JsonNode& n, const char* key, long long lo, long long fallback) {
  return static_cast<int>(n.integer_in(key, lo, kMaxSegments, fallback));
}

Vec3<double> positive_vec3(const JsonNode& n) {
  const Vec3<double> v = n.vec3();
  if (!(v.minCoeff() > 0)) n.fail("every component must be > 0");
  return v;
}

// The path a mesh file is read from: relative to the scene's folder and, unless the options allow
// otherwise, inside it once both are canonical (symlinks resolved, "." and ".." folded), compared
// component by component (so /a/bc is not inside /a/b). Messages show the path as the scene wrote it.
std::filesystem::path mesh_path(const JsonNode& f, const std::filesystem::path& rel, const std::filesystem::path& scene_dir,
                                const LoadOptions& options) {
  namespace fs = std::filesystem;
  const fs::path path = rel.is_absolute() ? rel : scene_dir / rel;
  if (options.allow_meshes_outside_scene_folder) return path;
  std::error_code ec;
  const fs::path dir = fs::weakly_canonical(scene_dir.empty() ? fs::path(".") : scene_dir, ec);
  if (ec) f.fail("cannot resolve the scene's folder " + scene_dir.string() + ": " + ec.message());
  if (rel.has_root_path()) f.fail("'" + rel.string() + "' is an absolute path, outside the scene's folder " + dir.string());
  const fs::path resolved = fs::weakly_canonical(path, ec);
  if (ec) f.fail("cannot resolve " + path.string() + ": " + ec.message());
  if (!is_within(dir, resolved))
    f.fail("'" + rel.string() + "' resolves to " + resolved.string() + ", outside the scene's folder " + dir.string());
  return path;
}

TriangleMesh<double> read_shape(const JsonNode& n, const std::filesystem::path& scene_dir, const LoadOptions& options,
                                std::string& type, std::optional<Skin>& skin) {
  type = n.required("type").string();
  if (type == "plane") {
    n.expect_object({"type", "size"});
    const JsonNode s = n.required("size");
    const Vec2<double> size = s.vec2();
    if (!(size.minCoeff() > 0)) s.fail("every component must be > 0");
    return make_plane<double>(size.x() / 2, size.y() / 2).value();
  }
  if (type == "box") {
    n.expect_object({"type", "size"});
    const Vec3<double> half = positive_vec3(n.required("size")) / 2;
    return make_box<double>(-half, half).value();
  }
  if (type == "sphere") {
    n.expect_object({"type", "radius", "segments", "rings"});
    const double r = n.positive("radius");
    const int segments = segments_in(n, "segments", 3, 32);
    const int rings = segments_in(n, "rings", 2, std::max(2, segments / 2));
    return make_uv_sphere<double>(r, static_cast<std::uint32_t>(segments), static_cast<std::uint32_t>(rings)).value();
  }
  if (type == "torus") {
    n.expect_object({"type", "major_radius", "minor_radius", "segments", "sides"});
    const double major = n.positive("major_radius");
    const double minor = n.positive("minor_radius");
    if (!(minor < major)) n.fail_at("minor_radius", "must be < major_radius (a self-intersecting torus is not a closed surface)");
    const auto segments = static_cast<std::uint32_t>(segments_in(n, "segments", 3, 48));
    const auto sides = static_cast<std::uint32_t>(segments_in(n, "sides", 3, 24));
    return make_torus<double>(major, minor, segments, sides).value();
  }
  if (type == "stairs") {
    n.expect_object({"type", "steps", "size"});
    const int steps = static_cast<int>(n.integer_in("steps", 1, 1000, 5));
    return make_stairs(steps, positive_vec3(n.required("size")));
  }
  if (type == "mesh") {
    n.expect_object({"type", "file", "pose_time"});
    const JsonNode f = n.required("file");
    const std::filesystem::path rel = f.string();
    if (rel.empty()) f.fail("must not be empty");
    std::optional<double> pose_time;
    if (auto t = n.optional("pose_time")) {
      pose_time = t->number();
      if (!(*pose_time >= 0)) t->fail("must be >= 0 (seconds)");
    }
    const std::filesystem::path path = mesh_path(f, rel, scene_dir, options);
    try {
      PosedMesh posed = load_posed_mesh_file(path, pose_time);
      skin = std::move(posed.skin);
      return std::move(posed.mesh);
    } catch (const MeshFileError& e) {
      f.fail(path.string() + ": " + e.what());
    }
  }
  n.fail_at("type", "unknown shape type '" + type + "' (expected plane, box, sphere, torus, stairs or mesh)");
}

// M = T R S from the transform object (absent: identity).
Eigen::Matrix4d read_transform(const JsonNode& n) {
  n.expect_object({"scale", "rotate", "translate"});
  Eigen::Affine3d m = Eigen::Affine3d::Identity();
  if (auto t = n.optional("translate")) m.translate(t->vec3());
  if (auto r = n.optional("rotate")) {
    r->expect_object({"axis", "degrees"});
    const JsonNode axis_node = r->required("axis");
    const Vec3<double> axis = nonzero_direction(axis_node);
    const double deg = r->required("degrees").number();
    m.rotate(Eigen::AngleAxisd(deg * std::numbers::pi / 180.0, axis));
  }
  if (auto s = n.optional("scale")) {
    Vec3<double> scale;
    if (s->value().is_array()) scale = s->vec3();
    else scale = Vec3<double>::Constant(s->number());
    if (!((scale.array() != 0).all())) s->fail("must be non-zero (a zero scale flattens the object)");
    m.scale(scale);
  }
  return m.matrix();
}

// The mask texture's alpha (alpha_mask.hpp): a PNG's alpha channel, or its grey when it has none,
// read by the project's one image reader (outputs/image_io.hpp).
std::shared_ptr<const AlphaTexture> read_alpha_texture(const JsonNode& f, const std::filesystem::path& scene_dir,
                                                       const LoadOptions& options) {
  const std::filesystem::path rel = f.string();
  if (rel.empty()) f.fail("must not be empty");
  std::string extension = rel.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension != ".png") f.fail("'" + rel.string() + "' is not a PNG (.png): a mask is a PNG's alpha, or its grey");
  const std::filesystem::path path = mesh_path(f, rel, scene_dir, options);
  outputs::Image8 image;
  try {
    image = outputs::read_image8(path, 0);
  } catch (const outputs::InputError& e) {
    f.fail(e.what());
  }
  try {
    return alpha_texture_of(image, path, WithoutAlpha::Grey);
  } catch (const std::invalid_argument& e) {
    f.fail(path.string() + ": " + e.what());
  }
}

// An object's mask (alpha_mask.hpp) from its uvs, alpha_texture, alpha_cutoff and vertex_alpha keys;
// nullopt when it has neither a texture nor vertex alpha.
std::optional<AlphaMask> read_alpha_mask(const JsonNode& n, std::size_t vertices, const std::filesystem::path& scene_dir,
                                         const LoadOptions& options) {
  const bool texture = n.has("alpha_texture"), vertex = n.has("vertex_alpha");
  if (!texture && !vertex) {
    if (n.has("alpha_cutoff")) n.fail_at("alpha_cutoff", "needs alpha_texture or vertex_alpha (nothing to compare it with)");
    return std::nullopt;
  }
  AlphaMask mask;
  const JsonNode cutoff = n.required("alpha_cutoff");
  mask.cutoff = cutoff.number();
  if (!(mask.cutoff >= 0 && mask.cutoff <= 1)) cutoff.fail("must be in [0, 1]");
  mask.texture = texture ? read_alpha_texture(n.child("alpha_texture"), scene_dir, options)
                         : std::make_shared<const AlphaTexture>();
  const auto per_vertex = [&](const JsonNode& a) {
    if (a.array_size() != vertices)
      a.fail("has " + std::to_string(a.array_size()) + " entries, the mesh has " + std::to_string(vertices) +
             " vertices (one per vertex, in the mesh's order)");
  };
  if (texture) {
    const JsonNode uvs = n.required("uvs");
    per_vertex(uvs);
    for (std::size_t i = 0; i < vertices; ++i) {
      const JsonNode e = uvs.element(i);
      const Vec2<double> uv = e.vec2();
      if (!(uv.cwiseAbs().maxCoeff() <= kMaxAlphaUv)) e.fail("must be within [-64, 64] (alpha_mask.hpp, kMaxAlphaUv)");
      mask.uvs.push_back(uv.cast<float>());
    }
  } else {
    if (n.has("uvs")) n.fail_at("uvs", "needs alpha_texture (texture coordinates with nothing to look up)");
    mask.uvs.assign(vertices, Vec2<float>::Zero());
  }
  if (vertex) {
    const JsonNode va = n.child("vertex_alpha");
    per_vertex(va);
    mask.has_vertex_alpha = true;
    for (std::size_t i = 0; i < vertices; ++i) {
      const JsonNode e = va.element(i);
      const double a = e.number();
      if (!(a >= 0 && a <= 1)) e.fail("must be in [0, 1]");
      mask.vertex_alpha.push_back(static_cast<float>(a));
    }
  } else {
    mask.vertex_alpha.assign(vertices, 1.0f);
  }
  return mask;
}

void read_object(const JsonNode& n, std::size_t index, const std::filesystem::path& scene_dir, const LoadOptions& options,
                 Scene& scene) {
  n.expect_object({"name", "shape", "transform", "receiver", "color", "uvs", "alpha_texture", "alpha_cutoff", "vertex_alpha"});
  Object obj;
  obj.name = "objects[" + std::to_string(index) + "]";
  if (n.has("name")) {  // a file name when exported (meshes/<name>.obj)
    const JsonNode name = n.child("name");
    obj.name = name.string();
    if (auto problem = identifier_problem(obj.name)) name.fail(*problem);
  }
  const JsonNode shape_node = n.required("shape");
  const TriangleMesh<double> local = read_shape(shape_node, scene_dir, options, obj.shape, obj.skin);
  const Eigen::Matrix4d xf = n.has("transform") ? read_transform(n.child("transform")) : Eigen::Matrix4d::Identity();
  if (obj.skin) {  // the object's transform in front of every joint (skin.hpp)
    for (Skin::Joint& j : obj.skin->joints) j.world = xf * j.world;
    obj.skin->bind_to_world = xf;
  }
  const bool mirror = xf.topLeftCorner<3, 3>().determinant() < 0;
  obj.mesh.positions.reserve(local.positions.size());
  for (std::size_t i = 0; i < local.positions.size(); ++i) {
    // A skinned vertex posed through its joints, the transform already in front of them: the very
    // sum a glTF reader of the pack's scene.gltf computes (skin.hpp).
    const Vec3<double> w = obj.skin ? pose_vertex(*obj.skin, i) : Vec3<double>((xf * local.positions[i].homogeneous()).head<3>());
    const Vec3<float> f = w.cast<float>();
    if (!f.allFinite()) n.fail_at("transform", "moves a vertex to a non-finite position (overflow in float)");
    obj.mesh.positions.push_back(f);
  }
  obj.mesh.triangles = local.triangles;
  if (mirror)
    for (auto& t : obj.mesh.triangles) std::swap(t[1], t[2]);
  if (obj.mesh.triangles.empty()) shape_node.fail("the mesh has no triangles");
  obj.alpha = read_alpha_mask(n, obj.mesh.positions.size(), scene_dir, options);
  if (!obj.alpha && n.has("uvs")) n.fail_at("uvs", "needs alpha_texture (texture coordinates with nothing to look up)");
  if (auto c = n.optional("color")) {
    const Vec3<double> color = c->vec3();
    if (!(color.minCoeff() >= 0 && color.maxCoeff() <= 1)) c->fail("every component must be in [0, 1]");
    obj.color = color.cast<float>();
  }
  if (auto r = n.optional("receiver")) {
    obj.receiver = r->boolean();
    if (obj.receiver) {
      if (auto prev = scene.receiver_index()) r->fail("only one object may be the receiver (objects[" + std::to_string(*prev) + "] already is)");
    }
  }
  scene.objects.push_back(std::move(obj));
  if (scene.objects.back().receiver && !detail::receiver_is_planar(scene))
    n.fail_at("receiver", "the receiver must be planar (all its vertices on one plane)");
}

void read_expect(const JsonNode& n, Scene& scene) {
  if (!n.value().is_object()) n.fail("must be an object");
  for (const auto& item : n.value().items()) {
    bool known = false;
    known = outputs::find_technique_name(item.key()) != nullptr;
    const JsonNode e = n.child(item.key().c_str());
    if (!known) {
      std::string list;
      for (const auto& t : outputs::kTechniques) list += (list.empty() ? "" : ", ") + std::string(t.name);
      e.fail("unknown technique (known: " + list + ")");
    }
    e.expect_object({"result", "why", "errors", "from_height"});
    Expectation x;
    const JsonNode result = e.required("result");
    const std::string r = result.string();
    if (r != "pass" && r != "warn" && r != "fail") result.fail("must be \"pass\", \"warn\" or \"fail\"");
    x.pass = r != "fail";
    x.warn = r == "warn";
    if (e.has("why")) x.why = e.child("why").string();
    if ((!x.pass || x.warn) && x.why.empty())
      e.fail_at("why", "is required (and non-empty) for an expected failure or warning");
    if (e.has("errors")) {
      const JsonNode k = e.child("errors");
      const std::string v = k.string();
      if (v == "too-light") x.errors = PredictedErrors::TooLight;
      else if (v == "too-dark") x.errors = PredictedErrors::TooDark;
      else k.fail("must be \"too-light\" or \"too-dark\"");
      if (x.pass) k.fail("predicts the errors of an expected failure: only with \"result\": \"fail\"");
    }
    if (e.has("from_height")) {
      const JsonNode h = e.child("from_height");
      const long long v = h.integer();
      if (v < 1 || v > outputs::kMaxResolution) h.fail("must be an image height in [1, " + std::to_string(outputs::kMaxResolution) + "]");
      if (x.pass) h.fail("is the image height an expected failure shows from: only with \"result\": \"fail\"");
      x.from_height = static_cast<int>(v);
    }
    scene.expect[item.key()] = x;
  }
}

}  // namespace

Scene parse_scene(std::string_view json_text, const std::filesystem::path& file, const LoadOptions& options) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json_text.begin(), json_text.end());
  } catch (const nlohmann::json::exception& e) {  // syntax errors, and numbers beyond double (1e999)
    throw SceneError(file.string() + ": invalid JSON: " + e.what());
  }
  const JsonNode root(doc, "", file);
  root.expect_object({"name", "description", "units", "resolution", "camera", "lights", "objects", "expect", "tags", "invariants"});
  Scene scene;
  scene.file = file;
  // The name becomes a folder name (renders/<name>/, the reference cache's <name>-<key>/).
  const JsonNode name = root.required("name");
  scene.name = name.string();
  if (auto problem = identifier_problem(scene.name)) name.fail(*problem);
  if (auto d = root.optional("description")) scene.description = d->string();
  if (auto u = root.optional("units")) {
    const std::string symbol = u->string();
    const LengthUnit* unit = find_length_unit(symbol);
    if (!unit) u->fail("unknown unit '" + symbol + "' (known: " + length_unit_symbols() + ")");
    scene.units = *unit;
  }
  if (auto r = root.optional("resolution")) {
    if (r->array_size() != 2) r->fail("must be [width, height]");
    for (std::size_t i = 0; i < 2; ++i) {
      const long long v = r->element(i).integer();
      if (v < 1 || v > kMaxResolution) r->element(i).fail("must be in [1, " + std::to_string(kMaxResolution) + "]");
      (i == 0 ? scene.width : scene.height) = static_cast<int>(v);
    }
  }
  if (auto t = root.optional("tags")) {
    for (std::size_t i = 0; i < t->array_size(); ++i) scene.tags.push_back(t->element(i).string());
  }
  if (auto inv = root.optional("invariants")) {
    for (std::size_t i = 0; i < inv->array_size(); ++i) {
      const JsonNode item = inv->element(i);
      const std::string invariant = item.string();
      if (invariant != "no-cast-shadow") item.fail("unknown invariant '" + invariant + "' (known: no-cast-shadow)");
      scene.invariant_no_cast_shadow = true;
    }
  }
  read_camera(root.required("camera"), scene);
  const JsonNode lights = root.required("lights");
  if (lights.array_size() == 0) lights.fail("must hold at least one light");
  for (std::size_t i = 0; i < lights.array_size(); ++i) scene.lights.push_back(read_light(lights.element(i)));
  const JsonNode objects = root.required("objects");
  if (objects.array_size() == 0) objects.fail("must hold at least one object");
  const std::filesystem::path dir = file.parent_path();
  for (std::size_t i = 0; i < objects.array_size(); ++i) read_object(objects.element(i), i, dir, options, scene);
  if (auto e = root.optional("expect")) read_expect(*e, scene);
  return scene;
}

Scene load_scene(const std::filesystem::path& file, const LoadOptions& options) {
  if (is_gltf_scene_file(file)) {
    // An engine team's own glTF scene (gltf_scene.hpp): what it holds and is not read, said once.
    GltfScene g = read_gltf_scene(file);
    for (const std::string& line : g.not_read) std::cerr << "shadowref: warning: " << file.string() << ": " << line << "\n";
    return std::move(g.scene);
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(file.string() + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(file.string() + ": cannot read the scene file");
  return parse_scene(text.str(), file, options);
}

}  // namespace shadowref::scene
