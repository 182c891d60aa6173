// shadowref/pack/obj_writer.hpp — one scene object as a Wavefront OBJ file of the pack
// (<scene>/meshes/<object>.obj).
#pragma once

#include <string>

#include "shadowref/scene/scene.hpp"

namespace shadowref::pack {

// The OBJ text of `o`'s mesh in world space (its transform applied, as the scene holds it): a comment
// line, `o <name>`, one `v x y z` per position (%.9g: a float read back exactly) and one `f a b c` per
// triangle (1-based, counter-clockwise = outside). No normals, no texture coordinates. Cost: one
// line per vertex and per triangle.
std::string obj_text(const scene::Object& o);

}  // namespace shadowref::pack
