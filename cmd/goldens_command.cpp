// goldens_command.cpp — `shadowref goldens`: the reference masks of the default catalogue, kept in
// goldens/images/<scene>/ (mask(_<i>).png and decided(_<i>).png: what a comparison reads), so that
// any change of the ground truth is a reviewed change.
//
//   --check   re-renders the references and demands the truth of every golden unchanged: each
//             decided image bit for bit, each mask on its decided pixels (reference/truth.hpp; an
//             undecided pixel's value is the reference's guess, which Embree's kernel for the CPU
//             may change, and differences there are printed as information), and the same set of
//             files. Exit 0 or 2.
//   --update  rewrites goldens/images/ from fresh references (and removes stale scene folders).
// With --cache, the references come from the conformance cache, whose key includes the running
// executable (reference_cache.hpp): an entry is what this very binary renders, so a CTest run can
// compute each reference once and check it here.
#include <CLI/CLI.hpp>

#include <algorithm>
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
#include "shadowref/reference/embree_scene.hpp"
#include "shadowref/reference/truth.hpp"
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
  std::string embree_kernel;
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

// What differs between a golden file and the fresh one: `changed` (decided pixels, sizes), empty
// when the truth is the same; `note` counts the undecided pixels whose guesses differ.
struct Difference {
  std::string changed;
  std::string note;
};

std::string at_pixel(const outputs::Image8& a, const outputs::Image8& b, std::ptrdiff_t i) {
  const int x = static_cast<int>(i % a.width), y = static_cast<int>(i / a.width);
  return "the first at (" + std::to_string(x) + ", " + std::to_string(y) + "): " + std::to_string(a.at(x, y)) +
         " became " + std::to_string(b.at(x, y));
}

// A mask's decided image: "mask_3.png" -> "decided_3.png", "mask.png" -> "decided.png"
// (outputs/file_names.hpp's rule, read backwards); "" for a file that is not a mask.
std::string decided_of(const std::string& mask) {
  return mask.rfind("mask", 0) == 0 ? "decided" + mask.substr(4) : "";
}

Difference difference(const fs::path& golden, const fs::path& fresh) {
  const outputs::Image8 a = outputs::read_image8(golden, 1);
  const outputs::Image8 b = outputs::read_image8(fresh, 1);
  if (a.width != b.width || a.height != b.height)
    return {"size " + std::to_string(a.width) + "x" + std::to_string(a.height) + " became " + std::to_string(b.width) +
                "x" + std::to_string(b.height),
            ""};
  const std::string decided = decided_of(golden.filename().string());
  if (decided.empty()) {  // a decided image: bit for bit
    const reference::TruthComparison c = reference::compare_truth(a.pixels, a.pixels, b.pixels, b.pixels);
    if (!c.decided_differ) return {};
    return {std::to_string(c.decided_differ) + " pixel(s) differ, " + at_pixel(a, b, c.first), ""};
  }
  const outputs::Image8 da = outputs::read_image8(golden.parent_path() / decided, 1, a.width, a.height);
  const outputs::Image8 db = outputs::read_image8(fresh.parent_path() / decided, 1, b.width, b.height);
  const reference::TruthComparison c = reference::compare_truth(a.pixels, da.pixels, b.pixels, db.pixels);
  Difference d;
  // Pixels decided in one only are the decided image's change, reported with that file.
  if (c.truth_differ)
    d.changed = std::to_string(c.truth_differ) + " decided pixel(s) differ, " + at_pixel(a, b, c.first);
  if (c.guesses_differ)
    d.note = std::to_string(c.guesses_differ) +
             " undecided pixel(s) guessed otherwise (not part of the truth: the reference's guess, which Embree's "
             "kernel for this CPU may change)";
  return d;
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
  if (!a.embree_kernel.empty()) {
    if (!a.cache.empty()) throw BadInput("--embree-kernel renders fresh references: give no --cache");
    if (a.update) throw BadInput("--embree-kernel checks the goldens: give --check, not --update");
    if (std::find(reference::kEmbreeKernels.begin(), reference::kEmbreeKernels.end(), a.embree_kernel) ==
        reference::kEmbreeKernels.end())
      throw BadInput("--embree-kernel: unknown kernel '" + a.embree_kernel + "' (expected sse2, sse4.2, avx2 or avx512)");
    if (!reference::cpu_runs_embree_kernel(a.embree_kernel)) {
      // Not a failure: the machine has no such kernel to check (CTest reads this line as a skip).
      std::printf("goldens: this CPU cannot run Embree's %s kernel: nothing checked\n", a.embree_kernel.c_str());
      return kExitPass;
    }
    settings.embree_config = "isa=" + a.embree_kernel;
  }
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
      const Difference d = difference(golden / n, fresh / n);
      if (!d.changed.empty()) {
        std::printf("CHANGED %s: %s\n", (golden / n).string().c_str(), d.changed.c_str());
        ++problems;
      }
      if (!d.note.empty()) std::printf("note    %s: %s\n", (golden / n).string().c_str(), d.note.c_str());
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
  std::printf("goldens: %zu file(s) of %zu scene(s) hold the same truth in %s (decided images bit for bit, masks on "
              "their decided pixels)\n",
              checked, files.size(), a.dir.c_str());
  return kExitPass;
}

}  // namespace

void register_goldens_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<GoldensArgs>();
  CLI::App* cmd = app.add_subcommand(
      "goldens", "Check (or update) the reference masks kept in goldens/images/ against freshly rendered references.");
  cmd->add_flag("--check", args->check,
                "re-render and demand the same truth: decided images bit for bit, masks on their decided pixels (exit 2 otherwise)");
  cmd->add_flag("--update", args->update, "rewrite the golden images from fresh references");
  cmd->add_option("--dir", args->dir, "the golden image folder")->capture_default_str();
  cmd->add_option("--scenes", args->scenes, conform::kScenesHelp);
  cmd->add_option("--catalogue", args->catalogue, "scene folder (default: the installed catalogue; from the build tree, the source tree's)");
  cmd->add_option("--cache", args->cache, "take references from this conformance cache (keyed by this executable)");
  cmd->add_option("--embree-kernel", args->embree_kernel,
                  "with --check: render with this Embree kernel (sse2, sse4.2, avx2, avx512) rather than the one Embree picks for "
                  "the CPU, to show the truth does not depend on it (exit 6 when this CPU cannot run it)");
  cmd->add_option("--jobs", args->jobs, "reference threads (0: the cores the machine can spare, all less the one-minute load average, at least 1)")->check(CLI::Range(0, 256));
  cmd->callback([args, &exit_code] { exit_code = run_goldens(*args); });
}

}  // namespace shadowref::cli
