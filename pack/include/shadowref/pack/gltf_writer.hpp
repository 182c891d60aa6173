// shadowref/pack/gltf_writer.hpp — the pack's glTF 2.0 files: one object's mesh
// (<scene>/meshes/<object>.gltf) and the whole scene (<scene>/scene.gltf), each one file with one
// embedded base64 buffer, so that an engine's loader opens it in one call. docs/output-contract.md
// ("The pack's whole-scene glTF") is the contract; scene/mesh_file.hpp is the reader that loads
// such meshes back (tinygltf).
//
// glTF's frame is the pack's (right-handed, y up, metres, the gl convention's), so nothing is
// converted: meshes are written in world space, node transforms are identities except the camera's
// and the lights'. Meshes are flat: each triangle its own three vertices with its face normal
// (NORMAL written: a loader left to compute normals may smooth shared vertices), plus a masked
// object's TEXCOORD_0 and COLOR_0 (vertex alpha); buffers hold floats and uint32 indices (4-byte
// elements: every buffer view stays aligned without padding).
#pragma once

#include <nlohmann/json.hpp>

#include "shadowref/scene/scene.hpp"

namespace shadowref::pack {

// One object as a glTF 2.0 document: one node without transform, one mesh (its triangles in world
// space, as the OBJ), no material. Cost: the mesh's bytes, base64-encoded.
nlohmann::json object_gltf(const scene::Object& o);

// The whole scene as a glTF 2.0 document:
//   every object: a node without transform, in the scene's object order, its colour as a
//     material (metallic 0, roughness 1; counter-clockwise outside; doubleSided only for a masked
//     object, as alpha-tested foliage is authored; an open card without a mask is single-sided,
//     and casts from both sides in the reference all the same), extras.receiver; a masked object
//     (scene/alpha_mask.hpp) with alphaMode MASK, its alphaCutoff, its mask as baseColorTexture
//     (an embedded grey + alpha PNG whose alpha is the mask; sampler NEAREST, REPEAT; TEXCOORD_0)
//     and its vertex alpha as COLOR_0's alpha (RGB 1);
//   the camera: a perspective camera (yfov, aspectRatio = W / H, znear, zfar only when the scene's
//     camera has one: the pack's projection is infinite otherwise) on a node whose matrix is the
//     inverse of the gl convention's view; extras carry the gl view and projections exactly
//     (canonical rows, bit for bit those of matrices.json) and the resolution;
//   the lights: KHR_lights_punctual, light i = the scene's light i (extras.mask_file): point, spot
//     (outerConeAngle = the pack's cone half-angle, innerConeAngle 0) and directional, shining along
//     their node's -z; a rect light is a point light at its centre (what hard techniques are judged
//     with) with its parallelogram (and samples) in extras, in scene coordinates: scene/gltf_scene.hpp reads the file back as the same scene.
// Cost: one prepare_scene() in the gl convention and the meshes' bytes.
nlohmann::json scene_gltf(const scene::Scene& s);

// A rigid node transform at `position` whose local -z (where glTF cameras look and glTF lights
// shine) is `forward` (any length but zero). Its up is scene +y unless `forward` is (nearly)
// vertical, then -z: the roll of a light does not matter, only where its -z points.
Mat4<double> node_facing(const Vec3<double>& position, const Vec3<double>& forward);

}  // namespace shadowref::pack
