// convention_masks_test.cpp — the same scene gives the same masks in every run convention.
//
// For every scene of the default catalogue and every technique, the renderer's masks in gl-zo,
// reversed-z and d3d are compared with its masks in gl on the pixels the gl reference marks
// decided. The masks are the ones the per-case conformance tests rendered and judged (their
// `renders/` folders: each scene is drawn once per technique and convention in the test command,
// and this test, their fixture's consumer, reads those very renders); the gl reference is the
// fixtures' cache entry. The conventions change every depth value, the depth test, the clear, the shadow
// compare, the polygon-offset sign and (d3d) the handedness of every matrix, but not which surface
// a pixel sees or which side of a shadow boundary it lies on, so on a decided pixel the answer must
// be the same. What may differ, and the bound for it (kMaxDifferingFraction), is said below.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "catalogue_scene.hpp"
#include "shadowref/conform/catalogue.hpp"
#include "shadowref/convention.hpp"
#include "shadowref/outputs/file_names.hpp"
#include "shadowref/outputs/image.hpp"
#include "shadowref/outputs/image_io.hpp"
#include "shadowref/outputs/techniques.hpp"

namespace shadowref {
namespace {

namespace fs = std::filesystem;

// A decided pixel may still differ between two conventions where a triangle edge or a shadow-map
// texel boundary passes within float rounding of its centre: the conventions compute the same
// clip x, y through different matrix products (d3d: a mirror and a left-handed look-at), so an edge
// can move by an ulp, and shadow maps compare depths of different precision (24-bit fixed against
// 32-bit float, with polygon offset in its own units). Isolated pixels, as between two correct
// renderers; a convention bug (a wrong compare, clear, offset sign or handedness) flips whole
// shadows. Measured (llvmpipe, 2026-11-22): at most 2 of 46239 decided pixels (0.0043 %), on
// volume-zfail-clamp and volume-finite edges; every shadow-map case identical. Bound: 0.05 % of the
// decided surface pixels (the exact-geometry fail bound), a 10-fold margin over what was seen.
constexpr double kMaxDifferingFraction = 0.0005;

// Where the per-case tests (conformance/tests/CMakeLists.txt) leave a render: in gl one run per
// scene and technique, in the other conventions one run per scene with every technique.
fs::path render_dir(const RunConvention& c, const std::string& scene, std::string_view technique) {
  const fs::path cases = fs::path(SHADOWREF_TEST_CASES) / std::string(c.name);
  const fs::path run = &c == &kDefaultConvention ? cases / scene / std::string(technique) : cases / scene;
  return run / "renders" / scene / std::string(technique);
}

TEST(ConventionMasks, EveryConventionGivesTheGlMasksOnDecidedPixels) {
  const auto files = conform::select_scenes(conform::default_catalogue(), {});
  ASSERT_FALSE(files.empty());
  std::size_t cases = 0, max_differing = 0;
  for (const auto& file : files) {
    const test::CatalogueScene gl(file.stem().string());
    const scene::Scene& s = gl.scene;
    const std::size_t lights = s.lights.size();
    std::vector<outputs::Image8> decided, reference;
    for (std::size_t l = 0; l < lights; ++l) {
      decided.push_back(outputs::read_image8(gl.reference / outputs::decided_name(l, lights), 1, s.width, s.height));
      reference.push_back(outputs::read_image8(gl.reference / outputs::mask_name(l, lights), 1, s.width, s.height));
    }
    for (const outputs::TechniqueName& t : outputs::kTechniques) {
      std::vector<outputs::Image8> base;
      for (std::size_t l = 0; l < lights; ++l)
        base.push_back(outputs::read_image8(render_dir(kDefaultConvention, s.name, t.name) / outputs::mask_name(l, lights), 1,
                                            s.width, s.height));
      for (const RunConvention& other : kRunConventions) {
        if (&other == &kDefaultConvention) continue;
        std::size_t decided_count = 0, differing = 0;
        for (std::size_t l = 0; l < lights; ++l) {
          const outputs::Image8 r = outputs::read_image8(render_dir(other, s.name, t.name) / outputs::mask_name(l, lights), 1,
                                                         s.width, s.height);
          for (std::size_t i = 0; i < r.pixels.size(); ++i) {
            if (decided[l].pixels[i] < 128 || reference[l].pixels[i] == outputs::kMaskNoSurface) continue;
            ++decided_count;
            differing += r.pixels[i] != base[l].pixels[i];
          }
        }
        ++cases;
        max_differing = std::max(max_differing, differing);
        EXPECT_LE(static_cast<double>(differing), kMaxDifferingFraction * static_cast<double>(decided_count))
            << s.name << " x " << t.name << " in " << other.name << ": " << differing << " of " << decided_count
            << " decided pixels differ from gl";
        if (differing) std::printf("%-32s %-20s %-11s %zu of %zu decided pixels differ\n", s.name.c_str(),
                                   std::string(t.name).c_str(), std::string(other.name).c_str(), differing, decided_count);
      }
    }
  }
  std::printf("%zu scene x technique x convention cases compared with gl; at most %zu differing pixels\n", cases, max_differing);
}

}  // namespace
}  // namespace shadowref
