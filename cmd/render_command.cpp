// render_command.cpp — `shadowref render`: one scene, one technique (or all), on Mesa's llvmpipe
// or softpipe through OSMesa or EGL, into mask(_<i>).png, shaded.png and render.json.
//
// The techniques and their one-sentence descriptions come from the renderer's registry, so
// --help always lists exactly what `--technique` accepts.
#include <CLI/CLI.hpp>

#include <chrono>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "render_variant_options.hpp"
#include "shadowref/renderer/renderer.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/outputs/limits.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::cli {
namespace {

struct RenderArgs {
  std::string scene;
  bool allow_meshes_outside = false;  // LoadOptions::allow_meshes_outside_scene_folder
  std::string technique;
  std::string out;
  std::string convention = "gl";
  std::string backend = "llvmpipe";
  std::string gl = "osmesa";
  int shadow_map_size = 0;
  int frames = 1;
  RenderVariantArgs variants;
};

std::string technique_help() {
  std::string text = "Techniques (--technique NAME, or 'all' for every one into OUT/NAME):\n";
  for (const renderer::Technique& t : renderer::techniques())
    text += "  " + std::string(t.name) + "\n      " + std::string(t.description) + "\n";
  text +=
      "Outputs: mask.png (mask_<i>.png with several lights: 255 lit, 0 shadowed, 128 no surface), "
      "shaded.png, render.json (technique, backend, GL vendor/renderer/version, frame time).";
  return text;
}

void run_render(const RenderArgs& a) {
  std::vector<const renderer::Technique*> chosen;
  if (a.technique == "all") {
    for (const renderer::Technique& t : renderer::techniques()) chosen.push_back(&t);
  } else if (const renderer::Technique* t = renderer::find_technique(a.technique)) {
    chosen.push_back(t);
  } else {
    throw BadInput("--technique: unknown technique '" + a.technique + "' (see --help)");
  }
  renderer::GlApi api;
  renderer::Driver driver;
  try {
    api = renderer::parse_gl_api(a.gl);
    driver = renderer::parse_driver(a.backend);
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
  scene::Scene sc;
  try {
    sc = scene::load_scene(a.scene, {.allow_meshes_outside_scene_folder = a.allow_meshes_outside});
  } catch (const scene::SceneError& e) {
    throw BadInput(e.what());
  }
  renderer::RenderOptions options;
  options.frames = a.frames;
  apply_render_variants(a.variants, a.shadow_map_size, options);
  scene::PrepareOptions prepare;
  prepare.shadow_map_size = a.shadow_map_size;
  const RunConvention& convention = parse_convention(a.convention);
  // Everything that depends on the scene alone, once, outside the timed frames.
  const auto prepare_start = std::chrono::steady_clock::now();
  const scene::PreparedScene prepared = scene::prepare_scene(sc, convention, prepare);
  const double prepare_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - prepare_start).count();
  renderer::Renderer r(api, driver);
  std::cerr << "shadowref render: " << sc.name << " (convention " << convention.name << ", prepared in " << prepare_ms
            << " ms: casters, adjacency, light fits) on " << r.info().renderer << " (" << renderer::to_string(api)
            << ", OpenGL " << r.info().version << ")\n";
  for (const renderer::Technique* t : chosen) {
    const renderer::RenderResult res = r.render(prepared, t->name, options);
    const std::filesystem::path dir =
        a.technique == "all" ? std::filesystem::path(a.out) / std::string(t->name) : std::filesystem::path(a.out);
    renderer::write_outputs(res, r.info(), sc, dir);
    std::cerr << "  " << t->name << ": " << res.median_frame_ms() << " ms/frame -> " << dir.string() << "\n";
    for (const std::string& note : res.notes) std::cerr << "    note: " << note << "\n";
  }
}

}  // namespace

void register_render_command(CLI::App& app, int& exit_code) {
  (void)exit_code;  // render either succeeds (0) or throws (4)
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Render a scene with one shadow technique in OpenGL (Mesa llvmpipe / softpipe) into masks and a picture.");
  cmd->add_option("--scene", args->scene, "scene file: JSON, or a glTF 2.0 scene (.gltf, .glb; docs/scene-format.md)")->required()->check(CLI::ExistingFile);
  cmd->add_flag("--allow-meshes-outside", args->allow_meshes_outside,
                "let the scene's mesh files lie outside its folder (absolute paths, '../'): for local use; a catalogue or a "
                "pack never needs it, and conform and export always refuse such scenes");
  cmd->add_option("--technique", args->technique, "technique name (listed below) or 'all'")->required();
  cmd->add_option("--out", args->out, "output folder (replaced when the render completes)")->required();
  add_convention_option(*cmd, args->convention);
  cmd->add_option("--backend", args->backend,
                  "Mesa driver: llvmpipe, softpipe (sets GALLIUM_DRIVER), or native (leave it: a GPU's EGL)")
      ->capture_default_str();
  cmd->add_option("--gl", args->gl, "context: osmesa, or egl (EGL_MESA_platform_surfaceless / device)")
      ->capture_default_str();
  cmd->add_option("--shadow-map-size", args->shadow_map_size,
                  "shadow-map texels per side; 0: automatic (3 texels per camera pixel at the centre, 1024..8192)")
      ->check(shadow_map_size_check())
      ->capture_default_str();
  add_render_variant_options(*cmd, args->variants);
  cmd->add_option("--frames", args->frames, "frames to render and time (render.json keeps the median)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->footer(technique_help());
  cmd->callback([args] { run_render(*args); });
}

}  // namespace shadowref::cli
