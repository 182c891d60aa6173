// shadowref/scene/load_scene.hpp — reading and validating scene files (DESIGN.md "Scene files").
//
// The format, key by key (every other key is an error, so a typo never goes unnoticed):
//   name (string, required), description (string), resolution ([W, H], integers in [1, 16384],
//   default [256, 256]), tags (array of strings), expect ({technique: {result: "pass"|"fail",
//   why: string (required for fail)}}, technique names from outputs::kTechniques),
//   camera {position, target, up (default [0,1,0]), fovy_deg (default 45), near (default 0.1), far},
//   lights [{type: point, position} | {type: directional, direction} |
//           {type: spot, position, direction, cone_deg} |
//           {type: rect, corner, edge_u, edge_v, samples (default 4: a 4 × 4 grid, in [1, 64])}],
//   objects [{name, shape, transform {scale (number or [x,y,z], non-zero),
//             rotate {axis, degrees}, translate}, receiver (bool), color ([r,g,b] in [0,1])}],
//   shape: {type: plane, size [sx, sz]} | {type: box, size [x,y,z]} |
//          {type: sphere, radius, segments (32), rings (segments / 2)} |
//          {type: torus, major_radius, minor_radius, segments (48), sides (24)} |
//          {type: stairs, steps (5), size [W, H, D]} | {type: mesh, file (relative to the scene)}.
// Transforms apply scale, then rotate, then translate (M = T R S); a mirroring transform flips
// the triangles' winding so that counter-clockwise still means outside.
//
// Every refusal is a SceneError whose what() is one line: "<file>: <json.path>: <what is wrong>",
// e.g. "scenes/a.json: objects[2].shape.radius: must be > 0". Checked: JSON syntax, unknown keys,
// wrong types, NaN/infinite numbers (1e999), ranges (resolution before anything is allocated,
// radii, segment counts), degenerate cameras (through mathlib's look_at / perspective), zero
// directions and edges, missing or broken mesh files (mesh_file.hpp), empty meshes, a receiver
// that is not planar or more than one receiver, no lights, no objects.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string_view>

#include "shadowref/scene/scene.hpp"

namespace shadowref::scene {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Loads and validates the scene file at `file`. Throws SceneError.
Scene load_scene(const std::filesystem::path& file);

// The same from JSON text; `file` names the scene in messages and anchors relative mesh paths.
Scene parse_scene(std::string_view json_text, const std::filesystem::path& file);

}  // namespace shadowref::scene
