// shadowref/scene/gltf_scene.hpp — an engine team's own glTF 2.0 scene (.gltf, .glb) read as a
// Scene, so that the same judge rules on a team's level (docs/scene-format.md, "Your own glTF
// scene", says it for users; this is the contract).
//
// What is read, from the default scene (else the first; else every root node), walked depth first
// in the order the file lists nodes and children, node transforms applied (matrix, or T R S):
//   name        the file's stem (a safe identifier: identifier.hpp), e.g. my_level.gltf → my_level.
//   units       glTF's metre, or the unit the scene's extras.units names ("m", "cm", "mm"), as the
//               pack writes a scene in another unit (scene.hpp, LengthUnit); any other value is refused.
//   camera      the first node with a camera in that walk; perspective only: yfov → fovy_deg,
//               znear → near, zfar → far (absent: the far plane at infinity, the suite's default).
//               The eye is the node's origin, it looks along the node's −z with the node's +y up.
//               Resolution: the camera node's extras.resolution [W, H] (what the pack writes), else
//               height 256 and width round(256 · aspectRatio) (aspectRatio absent: 256 × 256); with
//               both, aspectRatio must agree with W / H to within a pixel. The aspect the suite
//               uses is W / H.
//   lights      every node with a KHR_lights_punctual light, in walk order (light i of the scene,
//               its masks mask_<i>.png): directional (shining along the node's −z), point (the
//               node's origin), spot (origin, −z, outerConeAngle as the cone's half-angle; the cone
//               shapes lighting only, never the mask). A rect area light is a point light whose
//               extras say so, as the pack writes it: {"shadowref_type": "rect", "corner",
//               "edge_u", "edge_v" (the parallelogram in scene coordinates; the node's transform is
//               not applied to them, and the node must sit at its centre), "samples" (default 4)}.
//               colour, intensity and range are not read: a mask is visibility.
//   objects     every TRIANGLES primitive of every mesh node, one object each, named by its node
//               (the mesh's name, else "node<i>"; "_<k>" for primitive k > 0 and for repeats; characters
//               outside the identifier rule become '_'), in world space (a mirroring transform flips
//               the winding); colour from baseColorFactor. Every object casts and receives; the
//               node's extras.receiver: true marks the plane planar shadows project onto (at most
//               one, planar), as the pack writes it.
//   masks       a material with alphaMode MASK: alphaCutoff (default 0.5, within [0, 1]); its
//               baseColorTexture's alpha (a PNG; TEXCOORD_<texCoord>, each coordinate within
//               [−64, 64]); COLOR_0's alpha times baseColorFactor's alpha as vertex alpha
//               (alpha_mask.hpp's rule). A texture without an alpha channel has alpha 1 (glTF).
//               The rule reads the nearest texel, wrapped (REPEAT): a LINEAR sampler is read as
//               NEAREST (a warning); a CLAMP_TO_EDGE or MIRRORED_REPEAT sampler is accepted while
//               every coordinate lies in [0, 1] (the same texels), and refused otherwise.
//               alphaMode BLEND is read as OPAQUE (a warning).
//
// Not read, each said once in `not_read` (load_scene prints them as warnings): textures other than
// a MASK material's baseColorTexture, BLEND materials, LINEAR mask samplers, animations, unused
// extensions, morph targets at weight 0. Refused, one line each: skins (not read yet: the bind pose
// would be silently wrong), morph targets with a non-zero weight, orthographic cameras, required
// extensions (extensionsRequired) other than KHR_lights_punctual and KHR_materials_*, a
// KHR_texture_transform on a mask, a mask that is not a PNG.
//
// Every refusal is a SceneError whose what() is one line "<file>: <what is wrong>" (a JSON path
// where the problem is in an extras object), exit code 4 on the command line. External buffers and
// images must lie in the glTF file's folder or below it (gltf_model.hpp; LoadOptions does not lift
// this); nothing is written.
// The scene carries no expectations: every technique is expected to pass it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/scene.hpp"

namespace shadowref::scene {

// The resolution a glTF camera without extras.resolution gets: this height, and the width its
// aspectRatio gives (the JSON format's default resolution is 256 × 256 too).
inline constexpr int kGltfDefaultHeight = 256;

struct GltfScene {
  Scene scene;
  std::vector<std::string> not_read;  // one line each, without the file name: what the scene had and was not read
};

// True for a path whose extension is .gltf or .glb (any case): a scene load_scene reads as glTF.
bool is_gltf_scene_file(const std::filesystem::path& file);

// True when `file` is a glTF file (is_gltf_scene_file) whose JSON (a .glb's JSON chunk) lists a
// camera and a KHR_lights_punctual light: a scene, not a mesh file a JSON scene names (which has
// neither). Reads the JSON only, no buffer; false for anything unreadable. What a catalogue folder
// counts as its glTF scenes (conform/catalogue.hpp).
bool holds_camera_and_light(const std::filesystem::path& file);

// Reads and validates the glTF scene at `file`. Throws SceneError.
GltfScene read_gltf_scene(const std::filesystem::path& file);

}  // namespace shadowref::scene
