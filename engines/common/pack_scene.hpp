// engines/common/pack_scene.hpp — one scene of an exported pack, read the way an engine team reads
// it: the pack's manifest.json and the scene's matrices.json (its README documents both), nothing
// of shadowref's own code. The harnesses use the gl convention (right-handed, clip depth -1..1),
// which is what both engines hand to OpenGL.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace engines {

// Canonical layout: rows of a column-vector matrix (v' = M v), as matrices.json lists them.
using Mat4 = std::array<std::array<double, 4>, 4>;
using Vec3 = std::array<double, 3>;

Mat4 multiply(const Mat4& a, const Mat4& b);

struct PackLight {
  std::string type;                  // point, directional, spot, rect: the mask is the visibility of
  std::array<double, 4> homogeneous; // this point (w = 1) or direction toward the light (w = 0)
  std::string mask_file;             // mask.png, or mask_<i>.png with several lights
};

struct PackObject {
  std::string name;
  std::filesystem::path obj;  // absolute; world space, counter-clockwise = outside
};

struct PackScene {
  std::string name;
  std::filesystem::path dir;
  int width = 0, height = 0;
  Vec3 camera_position{};
  double near = 0;
  Mat4 view{};               // conventions.gl.view
  Mat4 projection_finite{};  // conventions.gl.projection_finite: a far plane behind the whole scene
  std::vector<PackLight> lights;
  std::vector<PackObject> objects;
};

// The scene names of the pack, in manifest.json's order. Throws std::runtime_error.
std::vector<std::string> pack_scene_names(const std::filesystem::path& pack);

// `pack`/`name`/matrices.json. Throws std::runtime_error naming the file and key.
PackScene read_pack_scene(const std::filesystem::path& pack, const std::string& name);

// The scenes named in `wanted` (comma-separated; empty: all), in the pack's order.
std::vector<std::string> select_scenes(const std::filesystem::path& pack, const std::string& wanted);

}  // namespace engines
