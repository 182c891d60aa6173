// shadowref/scene/load_scene.hpp — reading and validating scene files.
//
// The format, key by key (every other key is an error, so a typo never goes unnoticed):
//   name (string, required, a safe identifier: identifier.hpp), description (string),
//   units (string: "m", "cm" or "mm", default "m": what one unit of every coordinate is; scene.hpp, LengthUnit),
//   resolution ([W, H], integers in [1, 16384], default [256, 256]), tags (array of strings),
//   invariants (array of strings: "no-cast-shadow" — no cast shadow is visible anywhere, judged on
//   every surface pixel), expect ({technique: {result: "pass"|"fail", why: string (required for fail)}}, technique
//   names from outputs::kTechniques),
//   camera {position, target, up (default [0,1,0]), fovy_deg (default 45), near (default 0.1), far},
//   lights [{type: point, position} | {type: directional, direction} |
//           {type: spot, position, direction, cone_deg} |
//           {type: rect, corner, edge_u, edge_v, samples (default 4: a 4 × 4 grid, in [1, 64])}],
//   objects [{name (a safe identifier; absent: "objects[i]"), shape,
//             transform {scale (number or [x,y,z], non-zero), rotate {axis, degrees}, translate},
//             receiver (bool), color ([r,g,b] in [0,1]),
//             uvs ([[u, v], ...] one per mesh vertex, each in [-64, 64]), alpha_texture (a PNG
//             relative to the scene, confined like mesh files), vertex_alpha ([a, ...] one per mesh
//             vertex, in [0, 1]), alpha_cutoff (in [0, 1]): an alpha-masked caster (alpha_mask.hpp,
//             docs/scene-format.md); uvs only with alpha_texture, alpha_cutoff with either}],
//   shape: {type: plane, size [sx, sz]} | {type: box, size [x,y,z]} |
//          {type: sphere, radius, segments (32), rings (segments / 2)} |
//          {type: torus, major_radius, minor_radius, segments (48), sides (24)} |
//          {type: stairs, steps (5), size [W, H, D]} |
//          {type: mesh, file (relative to the scene), pose_time (seconds, >= 0; a glTF file's
//           animation time, default its first animation's extras.pose_time, else 0: skin.hpp,
//           docs/scene-format.md "Skins")}.
// Transforms apply scale, then rotate, then translate (M = T R S); a mirroring transform flips
// the triangles' winding so that counter-clockwise still means outside.
//
// Confinement. Names become paths (the scene's: renders/<name>/, the reference cache's
// <name>-<key>/; an object's: meshes/<name>.obj in an export), so they must be safe identifiers:
// joined to a folder, they name one entry inside it. A mesh file must lie in the scene file's
// folder or below it: the folder and the mesh path are both made canonical
// (std::filesystem::weakly_canonical: symlinks resolved, "." and ".." folded) and the mesh's must
// start with the folder's, so absolute paths, "../" paths and symlinks leading out are refused;
// LoadOptions::allow_meshes_outside_scene_folder lifts this for local use. A scene from elsewhere
// thus reads only files that travel with it, and whatever is written for it stays under --out.
//
// Every refusal is a SceneError whose what() is one line: "<file>: <json.path>: <what is wrong>",
// e.g. "scenes/a.json: objects[2].shape.radius: must be > 0". Checked: JSON syntax, unknown keys,
// wrong types, names that are not safe identifiers, NaN/infinite numbers (1e999), ranges
// (resolution before anything is allocated, radii, segment counts), degenerate cameras (through
// mathlib's look_at / perspective), zero directions and edges, mesh files outside the scene's
// folder, missing or broken mesh files (mesh_file.hpp), empty meshes, a receiver that is not
// planar or more than one receiver, no lights, no objects; a mask that is missing, unreadable or RGB
// without alpha, a cutoff outside [0, 1] or alone, uvs or vertex_alpha whose count is not the mesh's.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string_view>

#include "shadowref/scene/identifier.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::scene {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a load may do beyond the default.
struct LoadOptions {
  // Accept mesh files outside the scene file's folder (absolute paths, "../", symlinks leading
  // out). For local use on one's own files; off by default.
  bool allow_meshes_outside_scene_folder = false;
};

// Loads and validates the scene file at `file`. Throws SceneError.
Scene load_scene(const std::filesystem::path& file, const LoadOptions& options = {});

// The same from JSON text; `file` names the scene in messages and anchors relative mesh paths
// (its folder is the one mesh files must lie in).
Scene parse_scene(std::string_view json_text, const std::filesystem::path& file, const LoadOptions& options = {});

}  // namespace shadowref::scene
