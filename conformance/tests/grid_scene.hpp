// grid_scene.hpp — what the declaration-grid tests share: a scene with our correct shadow-map
// render of it as the control, the judge that judges a mask of it under a declaration, and the
// blatant mutations of a mask (the resolving power's probes, tolerance/resolving_power.hpp). The
// including target defines SHADOWREF_EXE, SHADOWREF_TEST_CACHE and SHADOWREF_TEST_OUT (the folder
// each judged mask is written to).
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "catalogue_scene.hpp"
#include "llvmpipe_renderer.hpp"
#include "shadowref/conform/judge.hpp"
#include "shadowref/tolerance/resolving_power.hpp"
#include "shadowref/outputs/candidate.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/image_io.hpp"

namespace shadowref::test {

namespace fs = std::filesystem;
using outputs::Image8;
using outputs::kMaskLit;
using outputs::kMaskNoSurface;
using outputs::kMaskShadowed;

// A mutant: the control mask with one blatant defect. Surface pixels only: a mutant never changes
// coverage (that would fail on its own, whatever the shadows).
using Mutation = std::function<void(Image8&)>;

inline void for_surface(Image8& m, const std::function<void(std::uint8_t&)>& f) {
  for (std::uint8_t& v : m.pixels)
    if (v != kMaskNoSurface) f(v);
}

// Every surface pixel takes the answer of the one `dx` to its left (silhouettes stay put): the
// resolving power's shift probe, tolerance::shifted.
inline Mutation shifted(int dx) {
  return [dx](Image8& m) { m = tolerance::shifted(m, dx, 0); };
}

// The shadow grown (or, with `grow` false, shrunk) by `n` px: a surface pixel takes the answer
// `grow ? shadowed : lit` when any surface pixel within n px (a square) has it.
inline Mutation morphed(int n, bool grow) {
  return [n, grow](Image8& m) {
    const Image8 was = m;
    const std::uint8_t into = grow ? kMaskShadowed : kMaskLit;
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) {
        std::uint8_t& v = m.pixels[static_cast<std::size_t>(y * m.width + x)];
        if (v == kMaskNoSurface) continue;
        for (int dy = -n; dy <= n && v != into; ++dy)
          for (int dx = -n; dx <= n; ++dx) {
            const int u = x + dx, w = y + dy;
            if (u < 0 || w < 0 || u >= m.width || w >= m.height) continue;
            if (was.pixels[static_cast<std::size_t>(w * m.width + u)] == into) {
              v = into;
              break;
            }
          }
      }
  };
}

// An 8 x 8 tile swapped with the one 8 px to its right, at the `rank`-th busiest place (the
// resolving power's probe, tolerance::swapped_tile).
inline Mutation swapped_tile(int rank) {
  return [rank](Image8& m) { m = tolerance::swapped_tile(m, rank); };
}

// Stands for our render's own declaration with its light matrices ("light_views": "declared", the
// exact views and projections the maps were drawn with): SceneUnderTest::judged fills it in.
constexpr const char* kOurMatrices = "@declared";

// One scene: its prepared form, the reference (from the CTest fixtures' cache), our render's masks.
struct SceneUnderTest : CatalogueScene {
  explicit SceneUnderTest(const std::string& name)
      : CatalogueScene(name), masks(llvmpipe_renderer().render(prepared, "shadowmap").masks), control(masks.at(0)) {
    renderer::RenderOptions o;
    o.declare_light_matrices = true;
    const renderer::RenderResult declared = llvmpipe_renderer().render(prepared, "shadowmap", o);
    // The same drawing: declaring the matrices changes what is said, not what is drawn.
    for (std::size_t i = 0; i < masks.size(); ++i)
      if (declared.masks.at(i).pixels != masks[i].pixels) ADD_FAILURE() << "declaring the matrices changed mask " << i;
    nlohmann::json keys = nlohmann::json::parse(outputs::declaration_text(declared.declaration));
    keys.erase("technique");
    our_matrices = keys.dump();
    our_matrices = our_matrices.substr(1, our_matrices.size() - 2);  // the keys, without the braces
  }
  std::vector<Image8> masks;  // our render's, one per light
  Image8 control;             // light 0's (the single-light scenes' one mask)
  std::string our_matrices;   // our render's declaration with its light matrices, kOurMatrices
  conform::Judge judge;

  // Judges `mask` as light `light`'s, beside our render's masks of the other lights, declared with
  // `keys` (kOurMatrices: our_matrices), in folder `name`, as `technique`.
  conform::CaseJudgement judged(const std::string& name, const Image8& mask, const std::string& keys, std::size_t light = 0,
                                const std::string& technique = "shadowmap") {
    const fs::path dir = fs::path(SHADOWREF_TEST_OUT) / scene.name / name;
    fs::remove_all(dir);  // no mask of an earlier run's layout left beside these
    fs::create_directories(dir);
    for (std::size_t i = 0; i < masks.size(); ++i)
      outputs::write_png(i == light ? mask : masks[i], dir / outputs::mask_name(i, masks.size()));
    const std::string& said = keys == kOurMatrices ? our_matrices : keys;
    std::ofstream(dir / "candidate.json") << "{\"technique\": \"" << technique << "\"" << (said.empty() ? "" : ", ") << said << "}\n";
    return judge.judge(&prepared, {reference, dir, "", false, {}});
  }
  // A mutant's name, with the light it mutates where the scene has several ("shifted-1px@light2").
  std::string mutant_name(const char* mutant, std::size_t light) const {
    return masks.size() == 1 ? std::string(mutant) : std::string(mutant) + "@light" + std::to_string(light);
  }
};

}  // namespace shadowref::test
