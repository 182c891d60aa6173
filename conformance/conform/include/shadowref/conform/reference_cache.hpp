// shadowref/conform/reference_cache.hpp — reference images computed once per scene and reused.
//
// The key is a 64-bit FNV-1a hash of: the scene file's bytes, the bytes of every mesh file it
// names, the reference settings, the run convention, and the bytes of the running executable (so that a rebuilt
// reference renderer never reads a stale picture: a cache that can lie is worse than none; a test
// program may name another executable built from the same tree: ReferenceSettings::key_executable).
// An entry is a folder <cache>/<scene name>-<16 hex digits>/ holding what `shadowref reference`
// writes plus key.json (the inputs of the key, for people; a format number; and the FNV-1a 64 hash
// of every file the entry holds). It is written into a temporary sibling and renamed into place, so
// concurrent runs (CTest fixtures, --jobs) never see half an entry; two runs racing for the same key
// both compute it and one rename wins.
// Before each use the entry is verified: every file key.json lists, with the bytes it recorded. An
// entry that fails (a truncated or bit-flipped file after a crash or a bad disk, a missing or
// unparsable key.json, an entry of another format) is recomputed and replaced, and the caller is told
// which file and why (CachedReference::recomputed_because): a damaged cache heals, never misleads.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::conform {

struct ReferenceSettings {
  int samples_per_axis = 4;  // the sub-pixel grid of reference::Options: 4 × 4 = 16 samples
  int threads = 0;           // not part of the key: the images do not depend on it (tested bit for bit)
  // The executable whose bytes enter the key; empty: the running one. A test program linking the
  // same reference library, built with it from the same tree, names the `shadowref` built beside
  // it, and so reads the entries that its CTest fixtures (`shadowref conform --references-only`) computed.
  std::filesystem::path key_executable;
  // Embree's device configuration (reference::Options::embree_config): empty in production. Not
  // part of the key, so ensure_reference refuses a non-empty one (a forced kernel renders fresh).
  std::string embree_config;
};

// The key of the prepared scene (loaded from scene.file, in its convention) under `settings`, as 16
// hex digits.
std::string reference_key(const scene::PreparedScene& scene, const ReferenceSettings& settings);

struct CachedReference {
  std::filesystem::path dir;  // the entry folder: mask(_<i>).png, decided(_<i>).png, visibility.exr, shaded.png
  bool computed = false;      // false: found in the cache
  double seconds = 0;         // time spent computing it (0 when found)
  std::string recomputed_because;  // non-empty: an entry was there but failed verification (which file, why)
};

// The entry of `scene`, computed with the Embree reference when missing. Throws
// std::runtime_error on file-system or Embree failures.
CachedReference ensure_reference(const scene::PreparedScene& scene, const std::filesystem::path& cache,
                                 const ReferenceSettings& settings);

// The same, written to `dir` with no caching (goldens --check / --update).
void render_reference_to(const scene::PreparedScene& scene, const std::filesystem::path& dir, const ReferenceSettings& settings);

}  // namespace shadowref::conform
