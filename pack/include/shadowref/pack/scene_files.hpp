// shadowref/pack/scene_files.hpp — one scene's files in the pack, and its manifest entry (the pack's
// layout: cmd/export_command.cpp's head comment; the pack README says how an engine reads them).
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "shadowref/scene/scene.hpp"

namespace shadowref::pack {

// `name` with every character but [A-Za-z0-9_-] replaced by '_': an object's mesh file name.
std::string safe_name(std::string name);

// Writes scene `s`, loaded from `scene_file`, into the pack folder `out`:
//   out/scenes/<scene_file's name>, and the mesh files it names, at the same relative paths;
//   out/<s.name>/meshes/<object>.obj and .gltf (obj_writer.hpp, gltf_writer.hpp), scene.gltf and
//   matrices.json (matrices.hpp, with "objects": each object's files, receiver flag and colour).
// Every file is written whole or not at all (outputs::write_file_atomically). The reference masks
// are not written here (the caller computes them). Throws std::filesystem::filesystem_error or
// outputs' file errors. Cost: matrices_json()'s four prepare_scene() and the meshes' bytes.
void write_scene_files(const scene::Scene& s, const std::filesystem::path& scene_file, const std::filesystem::path& out);

// manifest.json without its scenes: the tool, the mask values, and an empty "scenes" array.
nlohmann::json manifest_head();

// The manifest's entry of scene `s` loaded from `scene_file`: name, description, resolution,
// lights, scene_file (under scenes/) and, per technique, the catalogue's expectation ("pass", or
// "fail" / "warn" with its why).
nlohmann::json manifest_entry(const scene::Scene& s, const std::filesystem::path& scene_file);

}  // namespace shadowref::pack
