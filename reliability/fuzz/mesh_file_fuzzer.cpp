// mesh_file_fuzzer.cpp — libFuzzer target: scene::load_mesh_file on arbitrary bytes saved as a
// mesh file (SHADOWREF_FUZZ_MESH_EXT: ".obj" for obj_fuzzer, ".gltf" for gltf_fuzzer), then
// mathlib's build_adjacency on whatever loads, as `shadowref math mesh-report` does. Refusals
// must be MeshFileError (or a failed Result); a loaded mesh must be all finite with every index
// in range — anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_files.hpp"
#include "shadowref/adjacency.hpp"
#include "shadowref/scene/mesh_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = shadowref::fuzz::scratch_dir() / ("input" SHADOWREF_FUZZ_MESH_EXT);
  shadowref::fuzz::write_file(file, data, size);
  shadowref::TriangleMesh<double> mesh;
  try {
    mesh = shadowref::scene::load_mesh_file(file);
  } catch (const shadowref::scene::MeshFileError&) {
    return 0;
  }
  if (mesh.triangles.empty()) std::abort();  // load_mesh_file promises at least one triangle
  for (const auto& p : mesh.positions)
    if (!p.allFinite()) std::abort();  // promised: no NaN or infinite coordinate
  for (const auto& t : mesh.triangles)
    for (const auto i : t)
      if (i >= mesh.positions.size()) std::abort();  // promised: every index in range
  (void)shadowref::build_adjacency(mesh);
  return 0;
}
