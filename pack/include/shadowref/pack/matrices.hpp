// shadowref/pack/matrices.hpp — a scene's matrices.json: the camera and light matrices of every run
// convention, in canonical and D3DX layout (the pack README's "The matrices" says how an engine
// reads them). Every matrix comes from mathlib (view.hpp, projection.hpp, shadow_matrix.hpp,
// light_fit.hpp, cascades.hpp, d3dx.hpp) through scene/prepared_scene.hpp: the very ones our renderer
// and the reference use when run with --convention NAME. Layouts: matrix_json.hpp.
#pragma once

#include <nlohmann/json.hpp>

#include "shadowref/scene/prepared_scene.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::pack {

// The whole matrices.json of scene `s` (without "objects" and "scene_gltf", which the caller adds
// with the files it wrote): the resolution, the pixel, world and layout conventions in words, the
// camera's parameters, one convention_matrices() per kRunConventions entry, the receiver plane when
// the scene has one, and per light its parameters, homogeneous point, mask file and planar shadow
// matrix (or the reason it has none: a light on the receiver plane). Cost: one prepare_scene() per
// run convention (the light fitting over every triangle).
nlohmann::json matrices_json(const scene::Scene& s);

// One run convention's matrices, from scene `p` prepared in it: the convention in words (handedness,
// clip depth, depth buffer, test, clear, compare, polygon-offset sign), the world mirror, the camera's
// view, projections (infinite and finite) and view-projection, the shadow-map bias matrix, and the
// views of every light (light_views: the pack's fits; engine_light_views(); cascade_views).
nlohmann::json convention_matrices(const scene::PreparedScene& p);

// Light views an engine can use as they are, for maps it renders itself ("light_views": "own"): a
// point or rect light as an OpenGL cube map (six views of exactly 90 degrees, no guard band, in
// GL_TEXTURE_CUBE_MAP_POSITIVE_X + i order and orientation), a spot or directional light as its one
// view, each map a power of two (the pack's size rounded up). A left-handed convention (d3d) has no
// cube: OpenGL's cube-map orientation is defined in a right-handed world, and the entry says so.
nlohmann::json engine_light_views(const scene::PreparedScene& p);

}  // namespace shadowref::pack
