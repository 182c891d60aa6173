// load_errors_test.cpp — every refusal of the scene loader, table-driven: one change to a valid
// scene, and the exact "<file>: <json path>: <what>" line it must produce.
#include <gtest/gtest.h>

#include <string>

#include "shadowref/scene/load_scene.hpp"
#include "test_scene_json.hpp"

namespace shadowref::scene {
namespace {

using nlohmann::json;

// The rule every name refusal ends with (identifier.hpp).
#define SHADOWREF_NAME_RULE \
  " (a name becomes a file or folder name: 1 to 64 of A-Z a-z 0-9 _ . -, starting with a letter or a digit, no '..')"

struct ErrorCase {
  const char* name;
  const char* pointer;   // JSON pointer of the value to set ("" = nothing), or to remove
  const char* value;     // JSON text to put there; nullptr = remove the key
  const char* expected;  // the message after "test.json: "
};

// Each case: what it proves is in its name; the expected text pins both the path and the reason.
const ErrorCase kCases[] = {
    {"UnknownTopLevelKey", "/colour", "1", "colour: unknown key (allowed here: name, description, units, resolution, camera, lights, objects, expect, tags, invariants)"},
    {"UnknownUnit", "/units", "\"inch\"", "units: unknown unit 'inch' (known: m, cm, mm)"},
    {"UnitNotString", "/units", "0.001", "units: must be a string, not number"},
    {"UnknownInvariant", "/invariants", "[\"no-shadow-at-all\"]", "invariants[0]: unknown invariant 'no-shadow-at-all' (known: no-cast-shadow)"},
    {"MissingName", "/name", nullptr, "name: is required"},
    {"NameNotString", "/name", "3", "name: must be a string, not number"},
    {"NameClimbsOut", "/name", "\"../../escaped_scene\"", "name: must not contain '..'" SHADOWREF_NAME_RULE},
    {"NameWithSlash", "/name", "\"a/b\"", "name: must not contain '/'" SHADOWREF_NAME_RULE},
    {"NameWithBackslash", "/name", R"("a\\b")", "name: must not contain '\\'" SHADOWREF_NAME_RULE},
    {"NameWithDrive", "/name", "\"C:evil\"", "name: must not contain ':'" SHADOWREF_NAME_RULE},
    {"NameHidden", "/name", "\".hidden\"", "name: must start with a letter or a digit, not '.'" SHADOWREF_NAME_RULE},
    {"NameEmpty", "/name", "\"\"", "name: must not be empty" SHADOWREF_NAME_RULE},
    {"NameTooLong", "/name", "\"aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa\"", "name: must be at most 64 characters, not 65" SHADOWREF_NAME_RULE},
    {"NameWithSpace", "/name", "\"ground sphere\"", "name: must not contain ' '" SHADOWREF_NAME_RULE},
    {"NameNotAscii", "/name", "\"caf\u00e9\"", "name: must not contain byte 0xC3" SHADOWREF_NAME_RULE},
    {"ObjectNameClimbsOut", "/objects/1/name", "\"../ball\"", "objects[1].name: must not contain '..'" SHADOWREF_NAME_RULE},
    {"ObjectNameWithSlash", "/objects/1/name", "\"a/b\"", "objects[1].name: must not contain '/'" SHADOWREF_NAME_RULE},
    {"ResolutionZero", "/resolution", "[0, 48]", "resolution[0]: must be in [1, 16384]"},
    {"ResolutionAbsurd", "/resolution", "[64, 100000]", "resolution[1]: must be in [1, 16384]"},
    {"ResolutionFraction", "/resolution", "[64.5, 48]", "resolution[0]: must be a whole number"},
    {"ResolutionOneNumber", "/resolution", "[64]", "resolution: must be [width, height]"},
    {"CameraMissing", "/camera", nullptr, "camera: is required"},
    {"CameraEyeAtTarget", "/camera/target", "[0, 4, 8]", "camera.target: must differ from position"},
    {"CameraUpParallel", "/camera/up", "[0, -4, -8]", "camera.up: must not be parallel to the viewing direction (target - position)"},
    {"CameraFov", "/camera/fovy_deg", "180", "camera.fovy_deg: must be in (0, 180) degrees"},
    {"CameraNear", "/camera/near", "0", "camera.near: must be > 0"},
    {"CameraFar", "/camera/far", "0.05", "camera.far: must be > near (0.100000)"},
    {"CameraUnknownKey", "/camera/fov", "45", "camera.fov: unknown key (allowed here: position, target, up, fovy_deg, near, far)"},
    {"NoLights", "/lights", "[]", "lights: must hold at least one light"},
    {"LightsNotArray", "/lights", "{}", "lights: must be an array, not object"},
    {"LightUnknownType", "/lights/0/type", "\"laser\"", "lights[0].type: unknown light type 'laser' (expected point, directional, spot or rect)"},
    {"LightPositionShort", "/lights/0/position", "[1, 2]", "lights[0].position: must be an array of 3 numbers"},
    {"LightKeyOfOtherType", "/lights/0/direction", "[0, 1, 0]", "lights[0].direction: unknown key (allowed here: type, position)"},
    {"DirectionalZero", "/lights/0", R"({"type": "directional", "direction": [0, 0, 0]})", "lights[0].direction: must not be the zero vector"},
    {"SpotCone", "/lights/0", R"({"type": "spot", "position": [0, 5, 0], "direction": [0, -1, 0], "cone_deg": 120})", "lights[0].cone_deg: must be in (0, 90] degrees (the half-angle of the cone)"},
    {"RectParallelEdges", "/lights/0", R"({"type": "rect", "corner": [0, 5, 0], "edge_u": [1, 0, 0], "edge_v": [2, 0, 0]})", "lights[0].edge_v: must not be zero or parallel to edge_u"},
    {"RectSamples", "/lights/0", R"({"type": "rect", "corner": [0, 5, 0], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "samples": 0})", "lights[0].samples: must be in [1, 64]"},
    {"NoObjects", "/objects", "[]", "objects: must hold at least one object"},
    {"ObjectUnknownKey", "/objects/1/material", "1", "objects[1].material: unknown key (allowed here: name, shape, transform, receiver, color, uvs, alpha_texture, alpha_cutoff, vertex_alpha)"},
    // Alpha masks (alpha_mask.hpp): a card of four vertices, each key wrong in turn.
    {"AlphaCutoffAbove", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "alpha_texture": "mask_ga.png", "alpha_cutoff": 1.5})", "objects[1].alpha_cutoff: must be in [0, 1]"},
    {"AlphaCutoffNegative", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "vertex_alpha": [1, 1, 1, 1], "alpha_cutoff": -0.1})", "objects[1].alpha_cutoff: must be in [0, 1]"},
    {"AlphaCutoffMissing", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "alpha_texture": "mask_ga.png"})", "objects[1].alpha_cutoff: is required"},
    {"AlphaCutoffAlone", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "alpha_cutoff": 0.5})", "objects[1].alpha_cutoff: needs alpha_texture or vertex_alpha (nothing to compare it with)"},
    {"AlphaTextureMissing", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "alpha_texture": "no_such.png", "alpha_cutoff": 0.5})", "objects[1].alpha_texture: " SHADOWREF_SCENE_TEST_DATA "/no_such.png: no such file"},
    {"AlphaTextureNotPng", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "alpha_texture": "tri.obj", "alpha_cutoff": 0.5})", "objects[1].alpha_texture: 'tri.obj' is not a PNG (.png): a mask is a PNG's alpha, or its grey"},
    {"AlphaTextureRgb", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "alpha_texture": "mask_rgb.png", "alpha_cutoff": 0.5})", "objects[1].alpha_texture: " SHADOWREF_SCENE_TEST_DATA "/mask_rgb.png: an RGB image without alpha (expected grey, grey + alpha or RGBA)"},
    {"AlphaUvsMissing", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "alpha_texture": "mask_ga.png", "alpha_cutoff": 0.5})", "objects[1].uvs: is required"},
    {"AlphaUvCountMismatch", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "uvs": [[0, 0], [1, 0], [1, 1]], "alpha_texture": "mask_ga.png", "alpha_cutoff": 0.5})", "objects[1].uvs: has 3 entries, the mesh has 4 vertices (one per vertex, in the mesh's order)"},
    {"AlphaUvTooFar", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "uvs": [[0, 0], [100, 0], [1, 1], [0, 1]], "alpha_texture": "mask_ga.png", "alpha_cutoff": 0.5})", "objects[1].uvs[1]: must be within [-64, 64] (alpha_mask.hpp, kMaxAlphaUv)"},
    {"AlphaUvsWithoutTexture", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "vertex_alpha": [1, 1, 1, 1], "alpha_cutoff": 0.5})", "objects[1].uvs: needs alpha_texture (texture coordinates with nothing to look up)"},
    {"AlphaUvsAlone", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]]})", "objects[1].uvs: needs alpha_texture (texture coordinates with nothing to look up)"},
    {"VertexAlphaCountMismatch", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "vertex_alpha": [1, 1, 1, 1, 1], "alpha_cutoff": 0.5})", "objects[1].vertex_alpha: has 5 entries, the mesh has 4 vertices (one per vertex, in the mesh's order)"},
    {"VertexAlphaAbove", "/objects/1", R"({"shape": {"type": "plane", "size": [1, 1]}, "vertex_alpha": [1, 1, 2, 1], "alpha_cutoff": 0.5})", "objects[1].vertex_alpha[2]: must be in [0, 1]"},
    {"ShapeMissing", "/objects/1/shape", nullptr, "objects[1].shape: is required"},
    {"ShapeUnknownType", "/objects/1/shape/type", "\"cone\"", "objects[1].shape.type: unknown shape type 'cone' (expected plane, box, sphere, torus, stairs or mesh)"},
    {"SphereRadiusZero", "/objects/1/shape/radius", "0", "objects[1].shape.radius: must be > 0"},
    {"SphereRadiusNegative", "/objects/1/shape/radius", "-1", "objects[1].shape.radius: must be > 0"},
    {"SphereRadiusString", "/objects/1/shape/radius", "\"1\"", "objects[1].shape.radius: must be a number, not string"},
    {"SphereSegments", "/objects/1/shape/segments", "2", "objects[1].shape.segments: must be in [3, 4096]"},
    {"SphereSegmentsHuge", "/objects/1/shape/segments", "100000", "objects[1].shape.segments: must be in [3, 4096]"},
    {"SphereUnknownKey", "/objects/1/shape/size", "[1, 1, 1]", "objects[1].shape.size: unknown key (allowed here: type, radius, segments, rings)"},
    {"PlaneSizeNegative", "/objects/0/shape/size", "[20, -1]", "objects[0].shape.size: every component must be > 0"},
    {"BoxSizeZero", "/objects/1/shape", R"({"type": "box", "size": [1, 0, 1]})", "objects[1].shape.size: every component must be > 0"},
    {"TorusInverted", "/objects/1/shape", R"({"type": "torus", "major_radius": 1, "minor_radius": 2})", "objects[1].shape.minor_radius: must be < major_radius (a self-intersecting torus is not a closed surface)"},
    {"StairsSteps", "/objects/1/shape", R"({"type": "stairs", "steps": 0, "size": [1, 1, 1]})", "objects[1].shape.steps: must be in [1, 1000]"},
    {"MeshFileMissing", "/objects/1/shape", R"({"type": "mesh", "file": "no_such.obj"})", "objects[1].shape.file: " SHADOWREF_SCENE_TEST_DATA "/no_such.obj: no such file"},
    {"MeshFileBadIndex", "/objects/1/shape", R"({"type": "mesh", "file": "bad_index.obj"})", "objects[1].shape.file: " SHADOWREF_SCENE_TEST_DATA "/bad_index.obj: face 1 of shape '' uses vertex 7 but the file has 3 vertices"},
    {"MeshFileEmpty", "/objects/1/shape", R"({"type": "mesh", "file": "empty.obj"})", "objects[1].shape.file: " SHADOWREF_SCENE_TEST_DATA "/empty.obj: the mesh has no triangles"},
    {"MeshFileFormat", "/objects/1/shape", R"({"type": "mesh", "file": "not_a_mesh.ply"})", "objects[1].shape.file: " SHADOWREF_SCENE_TEST_DATA "/not_a_mesh.ply: unknown mesh format '.ply' (expected .obj, .gltf or .glb)"},
    {"MeshGltfLines", "/objects/1/shape", R"({"type": "mesh", "file": "lines.gltf"})", "objects[1].shape.file: " SHADOWREF_SCENE_TEST_DATA "/lines.gltf: a primitive has mode 1, only TRIANGLES (4) is supported"},
    {"TransformScaleZero", "/objects/1/transform/scale", "0", "objects[1].transform.scale: must be non-zero (a zero scale flattens the object)"},
    {"TransformRotateAxisZero", "/objects/1/transform/rotate", R"({"axis": [0, 0, 0], "degrees": 30})", "objects[1].transform.rotate.axis: must not be the zero vector"},
    {"TransformRotateNoDegrees", "/objects/1/transform/rotate", R"({"axis": [0, 1, 0]})", "objects[1].transform.rotate.degrees: is required"},
    {"TransformUnknownKey", "/objects/1/transform/shear", "1", "objects[1].transform.shear: unknown key (allowed here: scale, rotate, translate)"},
    {"TransformOverflow", "/objects/1/transform/scale", "1e39", "objects[1].transform: moves a vertex to a non-finite position (overflow in float)"},
    {"ColorOutOfRange", "/objects/1/color", "[1, 0.5, 2]", "objects[1].color: every component must be in [0, 1]"},
    {"ReceiverNotBool", "/objects/0/receiver", "1", "objects[0].receiver: must be true or false, not number"},
    {"TwoReceivers", "/objects/1/receiver", "true", "objects[1].receiver: only one object may be the receiver (objects[0] already is)"},
    {"ReceiverNotPlanar", "/objects/0/shape", R"({"type": "box", "size": [1, 1, 1]})", "objects[0].receiver: the receiver must be planar (all its vertices on one plane)"},
    {"ExpectUnknownTechnique", "/expect/planer", R"({"result": "pass"})", "expect.planer: unknown technique (known: planar, volume-zpass, volume-zfail, volume-zfail-clamp, volume-robust, volume-finite, shadowmap, shadowmap-pcf, shadowmap-rgba8, csm, csm-pcf, pcss, vsm)"},
    {"ExpectBadResult", "/expect/planar/result", "\"xfail\"", "expect.planar.result: must be \"pass\", \"warn\" or \"fail\""},
    {"ExpectFailWithoutWhy", "/expect/planar/result", "\"fail\"", "expect.planar.why: is required (and non-empty) for an expected failure or warning"},
    {"ExpectWarnWithoutWhy", "/expect/planar/result", "\"warn\"", "expect.planar.why: is required (and non-empty) for an expected failure or warning"},
    {"ExpectErrorsUnknown", "/expect/planar", R"({"result": "fail", "why": "w", "errors": "dark"})", "expect.planar.errors: must be \"too-light\" or \"too-dark\""},
    {"ExpectErrorsOnPass", "/expect/planar", R"({"result": "pass", "errors": "too-light"})", "expect.planar.errors: predicts the errors of an expected failure: only with \"result\": \"fail\""},
    {"ExpectFromHeightZero", "/expect/planar", R"({"result": "fail", "why": "w", "from_height": 0})", "expect.planar.from_height: must be an image height in [1, 16384]"},
    {"ExpectFromHeightNotInteger", "/expect/planar", R"({"result": "fail", "why": "w", "from_height": 720.5})", "expect.planar.from_height: must be a whole number"},
    {"ExpectFromHeightOnPass", "/expect/planar", R"({"result": "pass", "from_height": 720})", "expect.planar.from_height: is the image height an expected failure shows from: only with \"result\": \"fail\""},
    {"TagsNotStrings", "/tags", "[1]", "tags[0]: must be a string, not number"},
};

class LoadErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(LoadErrors, NamesFileAndJsonPath) {
  const ErrorCase& c = GetParam();
  json doc = test::minimal_scene();
  const json::json_pointer ptr(c.pointer);
  if (c.value) doc[ptr] = json::parse(c.value);
  else doc[ptr.parent_pointer()].erase(ptr.back());
  const std::filesystem::path file = std::filesystem::path(SHADOWREF_SCENE_TEST_DATA) / "test.json";
  try {
    (void)parse_scene(doc.dump(), file);
    FAIL() << "accepted: " << doc.dump();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), file.string() + ": " + c.expected);
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "the message must be one line";
  }
}

INSTANTIATE_TEST_SUITE_P(Scene, LoadErrors, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<ErrorCase>& p) { return std::string(p.param.name); });

TEST(LoadErrors, NamesAtTheLimitsAreValid) {
  // The other side of the name cases above: 64 characters, a digit first, '.', '-' and '_' inside.
  for (const std::string& name : {std::string(64, 'a'), std::string("0"), std::string("v1.2-final_b")}) {
    json doc = test::minimal_scene();
    doc["name"] = name;
    doc["objects"][1]["name"] = name;
    EXPECT_EQ(parse_scene(doc.dump(), std::filesystem::path(SHADOWREF_SCENE_TEST_DATA) / "test.json").name, name);
  }
}

TEST(LoadErrors, MinimalSceneIsValid) {
  // The base of every case above must load, or the cases would prove nothing.
  EXPECT_NO_THROW((void)parse_scene(test::minimal_scene().dump(), std::filesystem::path(SHADOWREF_SCENE_TEST_DATA) / "test.json"));
}

TEST(LoadErrors, InvalidJsonNamesFile) {
  try {
    (void)parse_scene("{ \"name\": ", "broken.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("broken.json: invalid JSON: ", 0), 0u) << e.what();
  }
}

TEST(LoadErrors, OverflowingNumberIsOneLine) {
  // JSON has no NaN or infinity; a literal too large for a double is refused by the parser itself
  // (nlohmann reports no position for it), still as a one-line SceneError naming the file.
  std::string text = test::minimal_scene().dump();
  text.replace(text.find("\"near\":0.1"), 10, "\"near\":1e999");
  try {
    (void)parse_scene(text, "big.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("big.json: invalid JSON: ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("1e999"), std::string::npos) << e.what();
  }
}

TEST(LoadErrors, MissingSceneFile) {
  try {
    (void)load_scene("/nonexistent/scene.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/scene.json: cannot open the scene file");
  }
}

// ---- mesh files must lie in the scene's folder -------------------------------------------------------

namespace fs = std::filesystem;

constexpr std::size_t kTriTriangles = 2;  // data/tri.obj: a quad as two triangles

// A folder of its own for each test, holding a scene folder and files beside it.
class MeshConfinement : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::path(::testing::TempDir()) / ("shadowref-mesh-confinement-" +
                                              std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "scenes");
    fs::create_directories(root_ / "outside");
    fs::copy_file(fs::path(SHADOWREF_SCENE_TEST_DATA) / "tri.obj", root_ / "scenes" / "tri.obj");
    fs::copy_file(fs::path(SHADOWREF_SCENE_TEST_DATA) / "tri.obj", root_ / "outside" / "tri.obj");
  }
  void TearDown() override { fs::remove_all(root_); }

  // The minimal scene with objects[1] a mesh from `file`, loaded as root/<scene_dir>/test.json.
  Scene load(const std::string& file, const LoadOptions& options = {}, const fs::path& scene_dir = "scenes") const {
    json doc = test::minimal_scene();
    doc["objects"][1]["shape"] = {{"type", "mesh"}, {"file", file}};
    return parse_scene(doc.dump(), root_ / scene_dir / "test.json", options);
  }
  // The message load() fails with ("" when it loads).
  std::string error(const std::string& file, const fs::path& scene_dir = "scenes") const {
    try {
      (void)load(file, {}, scene_dir);
    } catch (const SceneError& e) {
      return e.what();
    }
    return "";
  }
  fs::path canonical(const fs::path& p) const { return fs::weakly_canonical(root_ / p); }

  fs::path root_;
};

TEST_F(MeshConfinement, MeshesInsideTheFolderLoad) {
  EXPECT_EQ(load("tri.obj").objects[1].mesh.triangles.size(), kTriTriangles);
  EXPECT_EQ(load("./tri.obj").objects[1].mesh.triangles.size(), kTriTriangles);
  // Climbing out and back in resolves inside: accepted.
  EXPECT_EQ(load("../scenes/tri.obj").objects[1].mesh.triangles.size(), kTriTriangles);
}

TEST_F(MeshConfinement, AbsolutePathIsRefused) {
  const std::string file = "/etc/passwd";
  EXPECT_EQ(error(file), (root_ / "scenes" / "test.json").string() + ": objects[1].shape.file: '/etc/passwd' is an absolute path, outside the scene's folder " +
                             canonical("scenes").string());
  // Even one that points inside the folder: a scene must not depend on where it was written.
  const std::string inside = (root_ / "scenes" / "tri.obj").string();
  EXPECT_NE(error(inside).find("'" + inside + "' is an absolute path, outside the scene's folder"), std::string::npos)
      << error(inside);
}

TEST_F(MeshConfinement, ClimbingOutIsRefused) {
  // The file exists (and is a valid mesh): the path alone is refused, before it is read.
  EXPECT_EQ(error("../outside/tri.obj"), (root_ / "scenes" / "test.json").string() + ": objects[1].shape.file: '../outside/tri.obj' resolves to " +
                                             canonical("outside/tri.obj").string() + ", outside the scene's folder " +
                                             canonical("scenes").string());
  // A file that does not exist is refused the same way, not reported missing.
  EXPECT_NE(error("../outside.obj").find("'../outside.obj' resolves to " + canonical("outside.obj").string() + ", outside"),
            std::string::npos)
      << error("../outside.obj");
  // A sibling folder whose name starts with the scene folder's is outside too.
  fs::create_directories(root_ / "scenes2");
  fs::copy_file(root_ / "outside" / "tri.obj", root_ / "scenes2" / "tri.obj");
  EXPECT_NE(error("../scenes2/tri.obj").find("outside the scene's folder"), std::string::npos) << error("../scenes2/tri.obj");
}

TEST_F(MeshConfinement, SymlinkLeadingOutIsRefused) {
  fs::create_symlink(root_ / "outside" / "tri.obj", root_ / "scenes" / "link.obj");
  fs::create_directory_symlink(root_ / "outside", root_ / "scenes" / "linked_folder");
  EXPECT_NE(error("link.obj").find("'link.obj' resolves to " + canonical("outside/tri.obj").string() + ", outside"),
            std::string::npos)
      << error("link.obj");
  EXPECT_NE(error("linked_folder/tri.obj").find("outside the scene's folder"), std::string::npos) << error("linked_folder/tri.obj");
}

TEST_F(MeshConfinement, SymlinkedSceneFolderIsResolvedToo) {
  // The scene folder itself reached through a symlink: both sides are made canonical, so a mesh
  // inside it is inside.
  fs::create_directory_symlink(root_ / "scenes", root_ / "scenes_link");
  EXPECT_EQ(load("tri.obj", {}, "scenes_link").objects[1].mesh.triangles.size(), kTriTriangles);
  EXPECT_NE(error("../outside/tri.obj", "scenes_link").find("outside the scene's folder"), std::string::npos);
}

TEST_F(MeshConfinement, TheOptionAllowsMeshesOutside) {
  LoadOptions allow;
  allow.allow_meshes_outside_scene_folder = true;
  fs::create_symlink(root_ / "outside" / "tri.obj", root_ / "scenes" / "link.obj");
  EXPECT_EQ(load("../outside/tri.obj", allow).objects[1].mesh.triangles.size(), kTriTriangles);
  EXPECT_EQ(load((root_ / "outside" / "tri.obj").string(), allow).objects[1].mesh.triangles.size(), kTriTriangles);
  EXPECT_EQ(load("link.obj", allow).objects[1].mesh.triangles.size(), kTriTriangles);
}

}  // namespace
}  // namespace shadowref::scene
