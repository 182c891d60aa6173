// catalogue_scene.hpp — a catalogue scene as the in-process verdict tests use it: loaded, prepared
// in the default convention, and its reference read from the CTest fixtures' cache (filled by
// conformance.reference.gl.<scene>; computed here only when run alone). The including target
// defines SHADOWREF_EXE (the reference cache's key) and SHADOWREF_TEST_CACHE.
#pragma once

#include <filesystem>
#include <string>

#include "shadowref/conform/catalogue.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::test {

struct CatalogueScene {
  explicit CatalogueScene(const std::string& name)
      : scene(scene::load_scene(conform::default_catalogue() / (name + ".json"))), prepared(scene::prepare_scene(scene)) {
    conform::ReferenceSettings settings;
    settings.key_executable = SHADOWREF_EXE;
    reference = conform::ensure_reference(prepared, SHADOWREF_TEST_CACHE, settings).dir;
  }
  CatalogueScene(const CatalogueScene&) = delete;  // `prepared` points into `scene`
  CatalogueScene& operator=(const CatalogueScene&) = delete;

  scene::Scene scene;
  scene::PreparedScene prepared;
  std::filesystem::path reference;
};

}  // namespace shadowref::test
