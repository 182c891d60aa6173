// goldens_command.cpp — `shadowref goldens`: the reference masks of the default catalogue, kept in
// goldens/images/<scene>/ (mask(_<i>).png and decided(_<i>).png: what a comparison reads), so that
// any change of the ground truth is a reviewed change.
//
//   --check   re-renders the references and demands every golden file is bit-identical (pixel by
//             pixel, and the same set of files); prints each difference. Exit 0 or 2.
//   --update  rewrites goldens/images/ from fresh references (and removes stale scene folders).
// With --cache, the references come from the conformance cache, whose key includes the running
// executable (reference_cache.hpp): an entry is what this very binary renders, so a CTest run can
// compute each reference once and check it here.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <set>
#include <string>
#include <system_error>
#include <unistd.h>

#include "command.hpp"
#include "shadowref/outputs/atomic_file.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/staged_folder.hpp"
#include "shadowref/outputs/spare_cores.hpp"
#include "shadowref/conform/catalogue.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/prepared_scene.hpp"

namespace shadowref::cli {
namespace {

namespace fs = std::filesystem;

struct GoldensArgs {
  bool check = false;
  bool update = false;
  std::string dir = conform::default_golden_images().string();
  std::string scenes;
  std::string catalogue;
  std::string cache;
  int jobs = 0;
};

// The golden files of a reference folder: the masks and the decided images.
std::set<std::string> golden_names(const fs::path& dir) {
  std::set<std::string> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (e.path().extension() == ".png" && (n.rfind("mask", 0) == 0 || n.rfind("decided", 0) == 0)) out.insert(n);
  }
  return out;
}

// "" when identical, else what differs.
std::string difference(const fs::path& golden, const fs::path& fresh) {
  const outputs::Image8 a = outputs::read_image8(golden, 1);
  const outputs::Image8 b = outputs::read_image8(fresh, 1);
  if (a.width != b.width || a.height != b.height)
    return "size " + std::to_string(a.width) + "x" + std::to_string(a.height) + " became " + std::to_string(b.width) +
           "x" + std::to_string(b.height);
  std::size_t diff = 0;
  int fx = -1, fy = -1;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    if (a.pixels[i] != b.pixels[i]) {
      if (!diff) {
        fx = static_cast<int>(i % static_cast<std::size_t>(a.width));
        fy = static_cast<int>(i / static_cast<std::size_t>(a.width));
      }
      ++diff;
    }
  if (!diff) return "";
  return std::to_string(diff) + " pixel(s) differ, the first at (" + std::to_string(fx) + ", " + std::to_string(fy) +
         "): " + std::to_string(a.at(fx, fy)) + " became " + std::to_string(b.at(fx, fy));
}

int run_goldens(const GoldensArgs& a) {
  if (a.check == a.update) throw BadInput("give exactly one of --check and --update");
  std::vector<fs::path> files;
  try {
    files = conform::select_scenes(a.catalogue.empty() ? conform::default_catalogue() : fs::path(a.catalogue),
                                   conform::split_list(a.scenes));
  } catch (const std::invalid_argument& e) {
    throw BadInput(e.what());
  }
  conform::ReferenceSettings settings;
  settings.threads = a.jobs > 0 ? a.jobs : outputs::spare_cores();
  const fs::path scratch = fs::temp_directory_path() / ("shadowref-goldens-" + std::to_string(::getpid()));
  // Removed however the command ends (an error, an interruption), not only at its end.
  const std::unique_ptr<const fs::path, void (*)(const fs::path*)> remove_scratch(&scratch, [](const fs::path* p) {
    std::error_code ignored;
    fs::remove_all(*p, ignored);
  });
  std::size_t problems = 0, checked = 0;
  std::set<std::string> names;
  for (const fs::path& f : files) {
    scene::Scene s;
    try {
      s = scene::load_scene(f);
    } catch (const scene::SceneError& e) {
      throw BadInput(e.what());
    }
    names.insert(s.name);
    fs::path fresh;
    if (!a.cache.empty()) {
      fresh = conform::ensure_reference(scene::prepare_scene(s), a.cache, settings).dir;
    } else {
      fresh = scratch / s.name;
      conform::render_reference_to(scene::prepare_scene(s), fresh, settings);
    }
    const fs::path golden = fs::path(a.dir) / s.name;
    const std::set<std::string> want = golden_names(fresh);
    if (a.update) {
      // Staged: an interrupted or failed update leaves the old goldens, never a folder of some new images.
      outputs::StagedFolder staged(golden);
      for (const std::string& n : want) outputs::copy_file_atomically(fresh / n, staged.path() / n);
      staged.commit();
      std::printf("updated %s (%zu files)\n", golden.string().c_str(), want.size());
      continue;
    }
    const std::set<std::string> have = golden_names(golden);
    for (const std::string& n : want) {
      ++checked;
      if (!have.count(n)) {
        std::printf("MISSING %s (run shadowref goldens --update and review the new image)\n", (golden / n).string().c_str());
        ++problems;
        continue;
      }
      const std::string d = difference(golden / n, fresh / n);
      if (!d.empty()) {
        std::printf("CHANGED %s: %s\n", (golden / n).string().c_str(), d.c_str());
        ++problems;
      }
    }
    for (const std::string& n : have)
      if (!want.count(n)) {
        std::printf("STALE   %s: the reference no longer writes it\n", (golden / n).string().c_str());
        ++problems;
      }
  }
  std::error_code ec;
  if (a.update) {
    // Scene folders whose scene left the catalogue (only when the whole default catalogue was run).
    if (a.scenes.empty())
      for (const auto& e : fs::directory_iterator(a.dir))
        if (e.is_directory() && !names.count(e.path().filename().string())) {
          fs::remove_all(e.path());
          std::printf("removed %s (no longer in the catalogue)\n", e.path().string().c_str());
        }
    return kExitPass;
  }
  if (a.scenes.empty() && fs::is_directory(a.dir, ec))
    for (const auto& e : fs::directory_iterator(a.dir))
      if (e.is_directory() && !names.count(e.path().filename().string())) {
        std::printf("STALE   %s: no such scene in the default catalogue\n", e.path().string().c_str());
        ++problems;
      }
  if (problems) {
    std::printf("goldens: %zu problem(s) in %zu file(s) of %zu scene(s): the reference changed. If that is intended, run\n"
                "  shadowref goldens --update\nand review the images in the diff.\n",
                problems, checked, files.size());
    return kExitFailures;
  }
  std::printf("goldens: %zu file(s) of %zu scene(s) bit-identical in %s\n", checked, files.size(), a.dir.c_str());
  return kExitPass;
}

}  // namespace

void register_goldens_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<GoldensArgs>();
  CLI::App* cmd = app.add_subcommand(
      "goldens", "Check (or update) the reference masks kept in goldens/images/ against freshly rendered references.");
  cmd->add_flag("--check", args->check, "re-render and demand bit-identical masks and decided images (exit 2 otherwise)");
  cmd->add_flag("--update", args->update, "rewrite the golden images from fresh references");
  cmd->add_option("--dir", args->dir, "the golden image folder")->capture_default_str();
  cmd->add_option("--scenes", args->scenes, conform::kScenesHelp);
  cmd->add_option("--catalogue", args->catalogue, "scene folder (default: the installed catalogue; from the build tree, the source tree's)");
  cmd->add_option("--cache", args->cache, "take references from this conformance cache (keyed by this executable)");
  cmd->add_option("--jobs", args->jobs, "reference threads (0: the cores the machine can spare, all less the one-minute load average, at least 1)")->check(CLI::Range(0, 256));
  cmd->callback([args, &exit_code] { exit_code = run_goldens(*args); });
}

}  // namespace shadowref::cli
