// shadowref/scene/scene.hpp — a loaded scene: camera, lights, world-space meshes, expectations.
//
// This is the in-memory form of one scene file (load_scene.hpp says the format key by key); load_scene.hpp fills it
// and validates everything, so every field here is finite and within its documented range.
// Units are whatever the scene file uses (metres for most of the catalogue, millimetres for the
// Cornell box), stated by its "units" (LengthUnit); nothing in shadowref's maths reads the unit,
// epsilons scale with the scene's extent.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "shadowref/conventions.hpp"
#include "shadowref/mesh.hpp"
#include "shadowref/plane.hpp"
#include "shadowref/scene/alpha_mask.hpp"
#include "shadowref/scene/skin.hpp"

namespace shadowref::scene {

// A length unit a scene may be written in ("units" in the scene file, default metres). The pack
// states it and its glTF carries it, because an engine takes glTF's metres for granted and a
// physically based light falls off with distance in metres: a scene in millimetres (the Cornell
// box's published data) is lit 10^6 times dimmer there. Shadows do not depend on it.
struct LengthUnit {
  std::string_view symbol;  // the scene file's value: "m", "cm", "mm"
  std::string_view name;    // in words, plural: "metres"
  double metres = 1;        // one unit, in metres
};
inline constexpr std::array<LengthUnit, 3> kLengthUnits{{{"m", "metres", 1.0}, {"cm", "centimetres", 0.01}, {"mm", "millimetres", 0.001}}};
// The unit with this symbol; nullptr when none has it.
const LengthUnit* find_length_unit(std::string_view symbol);
// Every unit's symbol, for messages: "m, cm, mm".
std::string length_unit_symbols();

// The perspective camera. Aspect = width / height of the scene's resolution.
struct Camera {
  Vec3<double> position = Vec3<double>::Zero();
  Vec3<double> target = Vec3<double>(0, 0, -1);
  Vec3<double> up = Vec3<double>(0, 1, 0);
  double fovy_deg = 45;               // vertical field of view, in (0, 180)
  double near = 0.1;                  // > 0
  std::optional<double> far;          // > near; absent: the far plane is at infinity
};

enum class LightType { Point, Directional, Spot, Rect };

const char* to_string(LightType type);

// One light. Which fields matter depends on `type`:
//   point:       position
//   directional: direction (unit, from the scene TOWARD the light, like mathlib's w = 0 light)
//   spot:        position, direction (unit, the axis the spot shines along, from the light into
//                the scene), cone_deg (half-angle of the cone, in (0, 90])
//   rect:        corner, edge_u, edge_v (a parallelogram; it emits on both sides), samples (an
//                samples × samples stratified grid over it for the soft-shadow ground truth)
// The spot's cone is an illumination term: it shapes shaded.png, never the shadow mask.
struct Light {
  LightType type = LightType::Point;
  Vec3<double> position = Vec3<double>::Zero();
  Vec3<double> direction = Vec3<double>(0, 1, 0);
  double cone_deg = 45;
  Vec3<double> corner = Vec3<double>::Zero();
  Vec3<double> edge_u = Vec3<double>(1, 0, 0);
  Vec3<double> edge_v = Vec3<double>(0, 0, 1);
  int samples = 4;
};

// The light as mathlib's homogeneous point L = (x, y, z, w): w = 1 at the position for point and
// spot lights, w = 0 with xyz toward the light for directional lights, and w = 1 at the centre of
// the parallelogram for rect lights (what a hard-shadow technique approximates an area light by).
Vec4<double> homogeneous(const Light& light);

// One object: its mesh already in world space (the transform is applied at load time, and the
// winding flipped when the transform mirrors, so counter-clockwise still means outside).
struct Object {
  std::string name;
  std::string shape;                  // "plane", "box", "sphere", "torus", "stairs", "mesh"
  TriangleMesh<float> mesh;
  bool receiver = false;              // the plane planar shadows project onto
  Vec3<float> color = Vec3<float>(0.8f, 0.8f, 0.8f);  // albedo for shaded.png, in [0, 1]
  // A masked caster (alpha_mask.hpp): where its alpha is below the cutoff it lets light and the
  // camera's rays through. Absent: opaque everywhere.
  std::optional<AlphaMask> alpha;
  // A skinned object (skin.hpp): `mesh` is already posed (what the reference and every CPU consumer
  // read); the skin is how it was posed, for producers that pose it themselves (our renderer's vertex
  // shader, the pack's glTF). Absent: a rigid object.
  std::optional<Skin> skin;
};

// A technique's expected verdict on this scene: pass, or fail with the reason (the known
// limitation the catalogue wants to see detected).
// The kind of error an expected failure predicts ("errors" in the scene file): a FAIL counts as the
// expected one only when the errors of the other kind would not fail on their own.
enum class PredictedErrors {
  Any,       // no prediction
  TooLight,  // false light / a lit fraction above the truth (a leak, light bleeding)
  TooDark,   // false shadow / a lit fraction below the truth
};

struct Expectation {
  bool pass = true;
  PredictedErrors errors = PredictedErrors::Any;
  // "warn": an expected quality warning (explained errors beyond the quality bound, e.g. one map
  // over a kilometre of ground): a WARN verdict is then no warning of the run; PASS and FAIL count as usual.
  bool warn = false;
  std::string why;                    // non-empty when pass == false or warn
  // "from_height" of an expected failure: a limitation whose errors have a fixed size in the world
  // (a few centimetres of contact shadow) spans more pixels the taller the image (the camera's
  // field of view is vertical), so the judge resolves it only from some image height on. From
  // this height (pixels) the failure must show (a PASS is XPASS); below it a PASS is expected
  // too, and a FAIL still counts as this expected failure (with its predicted errors). 0: always.
  int from_height = 0;
  // Whether a PASS is as expected at an image `height` pixels tall.
  bool passes_at(int height) const { return pass || height < from_height; }
};

struct Scene {
  std::filesystem::path file;         // the scene file it was loaded from
  std::string name;
  std::string description;
  LengthUnit units = kLengthUnits[0];  // what one unit of every coordinate is
  int width = 256;                    // resolution, each in [1, 16384]
  int height = 256;
  Camera camera;
  std::vector<Light> lights;          // at least one
  std::vector<Object> objects;        // at least one, each with a non-empty mesh
  std::map<std::string, Expectation> expect;  // technique name -> expectation
  std::vector<std::string> tags;      // e.g. "large": the default conformance run skips it
  // "invariants": ["no-cast-shadow"]: no cast shadow is visible anywhere (the camera at the light),
  // so the judge checks every surface pixel for false shadows, not only the decided ones.
  bool invariant_no_cast_shadow = false;

  bool has_tag(const std::string& tag) const;
  // The index of the object marked `receiver`, if any (the loader allows at most one).
  std::optional<std::size_t> receiver_index() const;
};

// The receiver's plane (normal along its first triangle's face normal, normalised), if the scene
// has a receiver. The loader has checked that every receiver vertex lies on it.
std::optional<Plane<double>> receiver_plane(const Scene& scene);

// The axis-aligned bounds of every object's vertices: {min, max}. An empty scene gives zeros.
std::array<Vec3<double>, 2> bounds(const Scene& scene);

}  // namespace shadowref::scene
