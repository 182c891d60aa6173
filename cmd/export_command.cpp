// export_command.cpp — `shadowref export`: the scene pack an engine team renders with its own
// engine and hands back to `shadowref conform --candidate-dir`. The pack is a library (pack/): this
// file reads the arguments, selects and loads the scenes, computes the references and commits the
// pack as one folder.
//
// The pack (OUT/):
//   README.md                    what to render, how to name the files, how to get a verdict
//                                (pack/README.template.md filled: pack/readme.hpp)
//   manifest.json                scenes, resolutions, lights, techniques with the expectations
//   scenes/<scene>.json          the scene files as the catalogue has them (+ scenes/meshes/)
//   <scene>/meshes/<object>.obj  every object in world space (the transform applied), CCW outside
//   <scene>/meshes/<object>.gltf the same as glTF 2.0 (one embedded buffer)
//   <scene>/scene.gltf           the whole scene as glTF 2.0: every object, the camera, the lights
//                                (KHR_lights_punctual), for engines that load a scene in one call
//   <scene>/matrices.json        per run convention (gl, gl-zo, reversed-z, d3d): the camera's view,
//                                projection (infinite, and a finite one), view-projection, the world
//                                mirror, the bias matrix and every light's shadow-map views; per light
//                                its parameters, homogeneous point and planar shadow matrix — every
//                                matrix in canonical (column vectors) and D3DX (row vectors) layout
//   <scene>/reference/           mask(_<i>).png, decided(_<i>).png, covered.png, shaded.png, visibility(_<i>).exr
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>
#include <string>
#include <system_error>

#include "command.hpp"
#include "shadowref/conform/catalogue.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/json_text.hpp"
#include "shadowref/outputs/spare_cores.hpp"
#include "shadowref/outputs/staged_folder.hpp"
#include "shadowref/pack/readme.hpp"
#include "shadowref/pack/scene_files.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct ExportArgs {
  std::string out;
  std::string scenes;
  std::string catalogue;
  std::string cache;  // empty: a cache inside the staging folder, removed before the pack is committed
  int jobs = 0;
};

// The selected scenes, every one loaded and validated before anything is written: a bad scene
// leaves no pack.
std::vector<std::pair<fs::path, scene::Scene>> load_scenes(const ExportArgs& a) {
  std::vector<fs::path> files;
  try {
    files = conform::select_scenes(a.catalogue.empty() ? conform::default_catalogue() : fs::path(a.catalogue),
                                   conform::split_list(a.scenes));
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
  std::vector<std::pair<fs::path, scene::Scene>> scenes;
  for (const fs::path& f : files) {
    try {
      scenes.emplace_back(f, scene::load_scene(f));
    } catch (const scene::SceneError& e) {
      throw BadInput(e.what());
    }
  }
  return scenes;
}

// The scene's reference (computed, or from `cache`) copied into <scene>/reference/; whether it was
// computed.
bool write_reference(const scene::Scene& s, const fs::path& dir, const fs::path& cache, const conform::ReferenceSettings& settings) {
  const conform::CachedReference ref = conform::ensure_reference(scene::prepare_scene(s), cache, settings);
  std::error_code ec;
  fs::remove_all(dir / "reference", ec);
  fs::create_directories(dir / "reference");
  for (const auto& e : fs::directory_iterator(ref.dir))
    if (e.path().filename() != "key.json") fs::copy_file(e.path(), dir / "reference" / e.path().filename());
  return ref.computed;
}

void run_export(const ExportArgs& a) {
  const std::vector<std::pair<fs::path, scene::Scene>> scenes = load_scenes(a);
  // The template is read before anything is written: an installation without it leaves no pack.
  const std::string readme_template = pack::read_readme_template(pack::readme_template_path(conform::data_dir()));
  // The pack is written into a staging folder beside --out and renamed into place when complete,
  // so an interrupted or failed export never leaves a folder that looks like a pack.
  const fs::path final_out = fs::absolute(fs::path(a.out)).lexically_normal();
  std::error_code ec;
  if (fs::exists(final_out, ec)) {
    const bool is_pack = fs::exists(final_out / "manifest.json", ec);
    const bool is_empty = fs::is_directory(final_out, ec) && fs::is_empty(final_out, ec);
    if (!is_pack && !is_empty)
      throw BadInput("--out " + a.out + ": exists and is not a shadowref pack (no manifest.json): choose another folder");
  }
  outputs::StagedFolder staging(final_out);
  const fs::path& out = staging.path();
  fs::create_directories(out / "scenes", ec);
  if (ec) throw BadInput("--out " + a.out + ": " + ec.message());
  conform::ReferenceSettings settings;
  settings.threads = a.jobs > 0 ? a.jobs : outputs::spare_cores();
  // Export writes only under --out: without --cache, the references are computed into the staging
  // folder and the cache is dropped before the commit (the pack keeps copies in <scene>/reference/).
  const fs::path private_cache = out / ".reference-cache";
  const fs::path cache = a.cache.empty() ? private_cache : fs::path(a.cache);
  json manifest = pack::manifest_head();
  for (const auto& [f, s] : scenes) {
    pack::write_scene_files(s, f, out);
    const bool computed = write_reference(s, out / s.name, cache, settings);
    manifest["scenes"].push_back(pack::manifest_entry(s, f));
    std::printf("exported %s (%zu objects, %zu light(s), reference %s)\n", s.name.c_str(), s.objects.size(),
                s.lights.size(), computed ? "computed" : "cached");
  }
  if (a.cache.empty()) fs::remove_all(private_cache);
  outputs::write_file_atomically(out / "README.md", pack::fill_readme(readme_template, manifest));
  // Last: its presence marks a complete pack.
  outputs::write_file_atomically(out / "manifest.json", outputs::json_text(manifest, 2) + "\n");
  staging.commit();
  std::printf("pack: %s (README.md says what to render and how to name the files)\n", final_out.string().c_str());
}

}  // namespace

void register_export_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Write a scene pack for engine teams: scenes, meshes (OBJ, glTF), camera and light matrices in canonical and "
      "D3DX layout, reference masks, and a README saying what to render and how to name the files.");
  cmd->add_option("--out", args->out, "the pack folder")->required();
  cmd->add_option("--scenes", args->scenes, conform::kScenesHelp);
  cmd->add_option("--catalogue", args->catalogue, "scene folder (default: the installed catalogue; from the build tree, the source tree's)");
  cmd->add_option("--cache", args->cache, "reference cache folder, kept between runs (default: none; the references are computed inside the "
                  "pack's staging folder, and nothing is written outside --out). `shadowref conform --out O` keeps "
                  "its cache in O/reference-cache: name it to reuse conform's references");
  cmd->add_option("--jobs", args->jobs, "reference threads (0: the cores the machine can spare, all less the one-minute load average, at least 1)")->check(CLI::Range(0, 256));
  cmd->callback([args, &exit_code] {
    run_export(*args);
    exit_code = kExitPass;
  });
}

}  // namespace shadowref::cli
