// reference_command.cpp — `shadowref reference`: renders a scene's ray-traced ground truth.
//
// Loads the scene (any SceneError → one line, exit 4), renders it with the reference renderer
// and writes mask/visibility/decided/shaded images into --out (write_images.hpp). Prints one
// summary line with the timings and ray counts on stdout.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "command.hpp"
#include "shadowref/reference/render.hpp"
#include "shadowref/outputs/staged_folder.hpp"
#include "shadowref/reference/write_images.hpp"
#include "shadowref/scene/prepared_scene.hpp"
#include "shadowref/scene/load_scene.hpp"

namespace shadowref::cli {
namespace {

struct ReferenceArgs {
  std::string scene;
  bool allow_meshes_outside = false;  // LoadOptions::allow_meshes_outside_scene_folder
  std::string out;
  std::string convention = "gl";
  int spp = 16;
  int threads = 0;
  bool quiet = false;
};

// The sub-pixel grid is n × n: --spp must be a perfect square (1, 4, 9, 16, …, 256).
int samples_per_axis(int spp) {
  for (int n = 1; n <= 16; ++n)
    if (n * n == spp) return n;
  throw BadInput("--spp " + std::to_string(spp) + ": must be a square number in [1, 256] (an n x n sub-pixel grid)");
}

void run_reference(const ReferenceArgs& a) {
  reference::Options options;
  options.samples_per_axis = samples_per_axis(a.spp);
  if (a.threads < 0) throw BadInput("--threads " + std::to_string(a.threads) + ": must be >= 0 (0: all cores)");
  options.threads = a.threads;
  scene::Scene s;
  try {
    s = scene::load_scene(a.scene, {.allow_meshes_outside_scene_folder = a.allow_meshes_outside});
  } catch (const scene::SceneError& e) {
    throw BadInput(e.what());
  }
  const scene::PreparedScene prepared = scene::prepare_scene(s, parse_convention(a.convention));
  reference::Stats stats;
  const reference::Images images = reference::render(prepared, options, &stats);
  std::vector<std::string> files;
  try {
    outputs::StagedFolder folder(a.out);
    files = reference::write_images(images, folder.path());
    folder.commit();
  } catch (const std::runtime_error& e) {
    throw BadInput(e.what());  // an unwritable --out: the user's file error
  }
  if (!a.quiet) {
    const double shadow_rate = stats.seconds_shadow_calls > 0 ? static_cast<double>(stats.shadow_rays) / stats.seconds_shadow_calls / 1e6 : 0.0;
    std::printf("%s: %dx%d, %zu light(s), %llu primary + %llu shadow rays, build %.3f s, render %.3f s "
                "(shadow rays %.1f M/s per thread inside Embree, %.0f %% of the shadow phase), wrote %zu files to %s\n",
                s.name.c_str(), s.width, s.height, s.lights.size(), static_cast<unsigned long long>(stats.primary_rays),
                static_cast<unsigned long long>(stats.shadow_rays), stats.seconds_build, stats.seconds_render, shadow_rate,
                stats.seconds_shadow_phase > 0 ? 100.0 * stats.seconds_shadow_calls / stats.seconds_shadow_phase : 0.0,
                files.size(), a.out.c_str());
  }
}

}  // namespace

void register_reference_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ReferenceArgs>();
  CLI::App* cmd = app.add_subcommand(
      "reference",
      "Render a scene's ray-traced ground truth (Embree): mask.png, visibility.exr, decided.png, shaded.png "
      "(mask_<i>.png etc. per light when there are several).");
  cmd->add_option("--scene", args->scene, "the scene file: JSON, or a glTF 2.0 scene (.gltf, .glb; docs/scene-format.md)")->required();
  cmd->add_flag("--allow-meshes-outside", args->allow_meshes_outside,
                "let the scene's mesh files lie outside its folder (absolute paths, '../'): for local use; a catalogue or a "
                "pack never needs it, and conform and export always refuse such scenes");
  cmd->add_option("--out", args->out, "the output folder (created if needed)")->required();
  add_convention_option(*cmd, args->convention);
  cmd->add_option("--spp", args->spp, "sub-pixel samples per pixel, a square number (n x n grid)")->capture_default_str();
  cmd->add_option("--threads", args->threads, "worker threads, 0 = all cores (outputs are identical for any value)")->capture_default_str();
  cmd->add_flag("--quiet", args->quiet, "print nothing on success");
  cmd->callback([args, &exit_code] {
    run_reference(*args);
    exit_code = kExitPass;
  });
}

}  // namespace shadowref::cli
