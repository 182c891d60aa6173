// renderer_test.cpp — the OpenGL renderer against the Embree reference, on the reference's
// decided pixels (docs/tolerance-model.md), on the Mesa driver named by SHADOWREF_TEST_DRIVER.
//
// Scenes come from the catalogue at a reduced resolution (both renderers use the scene's own
// resolution, so the pixel → surface mapping stays shared) to keep the suite fast.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "shadowref/reference/render.hpp"
#include "shadowref/conform/judge.hpp"
#include "shadowref/conform/reference_cache.hpp"
#include "shadowref/scene/prepared_scene.hpp"

#include <unistd.h>
#include "shadowref/outputs/techniques.hpp"
#include "shadowref/renderer/renderer.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "shadowref/scene/camera.hpp"
#include "shadowref/outputs/image_io.hpp"
#include <nlohmann/json.hpp>

#include "shaders.hpp"
#include "shadow_maps/shadow_map_techniques.hpp"

namespace shadowref::renderer {
namespace {

constexpr int kTestResolution = 96;

Driver test_driver() {
  const char* d = std::getenv("SHADOWREF_TEST_DRIVER");
  return parse_driver(d ? d : "llvmpipe");
}

// One renderer per process (Mesa keeps the first driver).
Renderer& renderer() {
  static Renderer r(GlApi::OSMesa, test_driver());
  return r;
}

scene::Scene load(const std::string& name, int size = kTestResolution) {
  scene::Scene s = scene::load_scene(std::filesystem::path(SHADOWREF_SCENES_DIR) / (name + ".json"));
  s.width = s.height = size;
  return s;
}

// The renderer's defaults (automatic shadow-map size): what the conformance run uses.
RenderOptions fast_options() { return RenderOptions{}; }

reference::Images reference_of(const scene::Scene& s) {
  reference::Options o;
  o.samples_per_axis = 2;
  o.threads = 2;
  return reference::render(s, o);
}

// Agreement of a mask with the reference's light-0 mask on its decided pixels.
struct Agreement {
  int decided = 0;
  int decided_shadowed = 0;  // reference: shadowed
  int wrong = 0;             // decided pixels where the masks differ
  double wrong_fraction() const { return decided ? static_cast<double>(wrong) / decided : 1.0; }
};

Agreement compare(const Image8& mask, const reference::LightImages& ref) {
  Agreement a;
  for (std::size_t i = 0; i < mask.pixels.size(); ++i) {
    if (ref.decided[i] != 255) continue;
    ++a.decided;
    if (ref.mask[i] == outputs::kMaskShadowed) ++a.decided_shadowed;
    if (mask.pixels[i] != ref.mask[i]) ++a.wrong;
  }
  return a;
}

TEST(Renderer, ReportsTheDriverItWasAskedFor) {
  const GlInfo& info = renderer().info();
  EXPECT_NE(info.renderer.find(to_string(test_driver())), std::string::npos) << info.renderer;
  EXPECT_NE(info.version.find("Core Profile"), std::string::npos) << info.version;
  EXPECT_FALSE(info.vendor.empty());
}

// The simplest scene: every technique writes one mask of the right size with only 0 / 128 / 255,
// and z-fail and the shadow map agree with the reference on its decided pixels.
TEST(Renderer, SimplestSceneAgreesWithReference) {
  const scene::Scene s = load("ground_sphere");
  const reference::Images ref = reference_of(s);
  for (const Technique& t : techniques()) {
    SCOPED_TRACE(std::string(t.name));
    const RenderResult r = renderer().render(s, t.name, fast_options());
    ASSERT_EQ(r.masks.size(), 1u);
    ASSERT_EQ(r.masks[0].width, s.width);
    ASSERT_EQ(r.masks[0].height, s.height);
    for (std::uint8_t v : r.masks[0].pixels)
      ASSERT_TRUE(v == outputs::kMaskLit || v == outputs::kMaskShadowed || v == outputs::kMaskNoSurface) << int(v);
    ASSERT_EQ(r.shaded.channels, 3);
    const Agreement a = compare(r.masks[0], ref.lights[0]);
    // The scene must hold a real shadow, or "agreement" proves nothing (an all-lit mask would pass).
    ASSERT_GT(a.decided_shadowed, s.width * s.height / 50) << "the reference shows too little shadow";
    if (t.name == "volume-zfail") {
      // Same triangles, same pixel centres: only pixels whose centre lies within float rounding of
      // a volume edge may differ, and those are rarely decided. 0.2 % of decided pixels.
      EXPECT_LE(a.wrong_fraction(), 0.002) << a.wrong << " of " << a.decided;
    }
    if (t.name == "shadowmap") {
      // The map is a resampling of the shadow: along the shadow's edge a pixel can fall in a
      // texel on the other side (about one pixel row of the edge, ~1 % of this small image's
      // decided pixels). An inverted or offset shadow breaks this by an order of magnitude.
      EXPECT_LE(a.wrong_fraction(), 0.01) << a.wrong << " of " << a.decided;
    }
    // The background (no surface) is the same for every technique and the reference.
    for (std::size_t i = 0; i < r.masks[0].pixels.size(); ++i)
      ASSERT_EQ(r.masks[0].pixels[i] == outputs::kMaskNoSurface, ref.lights[0].mask[i] == outputs::kMaskNoSurface) << "pixel " << i;
  }
}

// Every technique, judged by the one judge (conform/judge.hpp) as `conform` judges it: the small
// scene's reference (the conformance run's settings), our render's folder, its candidate.json, the
// technique's threshold, causes and lit fraction. ground_sphere expects every technique to pass.
TEST(Renderer, EveryTechniqueIsJudgedAPassByTheOneJudge) {
  const scene::Scene s = load("ground_sphere");
  const scene::PreparedScene prepared = scene::prepare_scene(s);
  const std::filesystem::path root = std::filesystem::temp_directory_path() /
                                     ("shadowref-renderer-judged-" + std::to_string(::getpid()));
  std::filesystem::remove_all(root);
  conform::render_reference_to(prepared, root / "reference", conform::ReferenceSettings{});
  conform::Judge judge;
  for (const Technique& t : techniques()) {
    const std::string name(t.name);
    ASSERT_TRUE(s.expect.find(name) == s.expect.end() || s.expect.at(name).pass) << name << ": the scene expects a failure";
    write_outputs(renderer().render(prepared, name), renderer().info(), s, root / name);
    const conform::CaseJudgement j = judge.judge(&prepared, {root / "reference", root / name, name, true, {}});
    const compare::MaskMetrics& m = j.comparison.total;
    EXPECT_EQ(j.status, conform::Status::Pass) << name << ": " << conform::to_string(j.status) << ", " << m.unexplained
                                               << " px unexplained of " << m.wrong << " wrong (core " << m.unexplained_core << ")";
  }
  std::filesystem::remove_all(root);
}

// Planar shadows land on the receiver only: on the scene with a second object in the first one's
// shadow, the ground's shadow is there and the object's is missing (Blinn's documented limit).
TEST(Renderer, PlanarShadowMissingOnSecondObjectPresentOnGround) {
  const scene::Scene s = load("shadow_on_object");
  const reference::Images ref = reference_of(s);
  const RenderResult planar = renderer().render(s, "planar", fast_options());
  // Which pixels show the ground: render the same view without the receiver; a pixel that has a
  // surface with the ground but none without it is ground.
  scene::Scene no_ground = s;
  const std::size_t receiver = *s.receiver_index();
  no_ground.objects.erase(no_ground.objects.begin() + static_cast<std::ptrdiff_t>(receiver));
  const RenderResult objects_only = renderer().render(no_ground, "volume-zfail", fast_options());
  // Without a receiver planar casts nothing: what its mask still calls shadowed is the attached
  // shadow (surfaces facing away from the light), which every technique shows. Those pixels are
  // left out: the limit under test is the CAST shadow on the second object.
  const RenderResult attached_only = renderer().render(no_ground, "planar", fast_options());
  int ground_shadowed = 0, ground_hit = 0, object_shadowed = 0, object_hit = 0;
  const auto& m = planar.masks[0].pixels;
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (ref.lights[0].decided[i] != 255 || ref.lights[0].mask[i] != outputs::kMaskShadowed) continue;
    if (attached_only.masks[0].pixels[i] == outputs::kMaskShadowed) continue;
    const bool on_object = objects_only.masks[0].pixels[i] != outputs::kMaskNoSurface;
    (on_object ? object_shadowed : ground_shadowed)++;
    if (m[i] == outputs::kMaskShadowed) (on_object ? object_hit : ground_hit)++;
  }
  ASSERT_GT(ground_shadowed, 50);
  ASSERT_GT(object_shadowed, 50);
  // Present on the ground: all but the shadow's edge (the projection is exact; the receiver's
  // pixels are rasterised the same way as the reference's pixel centres). 95 %.
  EXPECT_GE(ground_hit, ground_shadowed * 95 / 100) << ground_hit << " of " << ground_shadowed;
  // Missing on the object: planar shadows never touch a non-receiver pixel (stencil-restricted).
  EXPECT_EQ(object_hit, 0) << object_hit << " of " << object_shadowed;
}

// The camera at the light sees only lit surfaces: no technique may show a shadow where the
// reference has decided. Shadow maps included: the pixels they used to mark next to silhouettes
// (a texel whose centre the occluder covers, read by a ground point beside it) are partially
// covered pixels, which the reference calls undecided; anywhere else a shadow is a real error.
TEST(Renderer, CameraAtLightShowsNoShadow) {
  const scene::Scene s = load("camera_at_light");
  const reference::Images ref = reference_of(s);
  for (const Technique& t : techniques()) {
    SCOPED_TRACE(std::string(t.name));
    const RenderResult r = renderer().render(s, t.name, fast_options());
    int shadowed_decided = 0, shadowed_any = 0;
    std::string where;
    for (std::size_t i = 0; i < r.masks[0].pixels.size(); ++i) {
      if (r.masks[0].pixels[i] != outputs::kMaskShadowed) continue;
      ++shadowed_any;
      if (ref.lights[0].decided[i] != 255) continue;
      ++shadowed_decided;
      where += " (" + std::to_string(i % static_cast<std::size_t>(s.width)) + "," +
               std::to_string(i / static_cast<std::size_t>(s.width)) + ")";
    }
    EXPECT_EQ(shadowed_decided, 0)
        << shadowed_any << " shadowed pixels in all; decided ones at" << where;
  }
}

// Several lights: one mask per light.
TEST(Renderer, OneMaskPerLight) {
  const scene::Scene s = load("two_lights", 48);
  ASSERT_EQ(s.lights.size(), 2u);
  for (const Technique& t : techniques()) {
    const RenderResult r = renderer().render(s, t.name, fast_options());
    EXPECT_EQ(r.masks.size(), 2u) << t.name;
  }
}

// Every technique renders every catalogue scene (small) without a GL error or an exception.
// Every scene file, the large ones included, on llvmpipe; softpipe, which runs every shader on one
// core a pixel at a time, draws every scene but those tagged "large" (a million-triangle sphere kept
// for speed measurements: 62 of softpipe's 89 s here, and nothing in it that the other scenes do
// not already ask of the driver).
TEST(Renderer, EveryTechniqueRendersEveryCatalogueScene) {
  for (const auto& entry : std::filesystem::directory_iterator(SHADOWREF_SCENES_DIR)) {
    if (entry.path().extension() != ".json") continue;
    scene::Scene s = scene::load_scene(entry.path());
    if (test_driver() == Driver::Softpipe && std::find(s.tags.begin(), s.tags.end(), "large") != s.tags.end()) continue;
    s.width = s.height = 48;
    for (const Technique& t : techniques()) {
      SCOPED_TRACE(entry.path().filename().string() + " " + std::string(t.name));
      RenderOptions o;
      o.shadow_map_size = 256;
      RenderResult r;
      ASSERT_NO_THROW(r = renderer().render(s, t.name, o));
      EXPECT_EQ(r.masks.size(), s.lights.size());
      // The filtered techniques also write their lit fraction, one image per light.
      const outputs::TechniqueName* named = outputs::find_technique_name(t.name);
      const bool filtered = named && (named->family == outputs::TechniqueFamily::ShadowMapPcf ||
                                      named->family == outputs::TechniqueFamily::SoftShadow);
      EXPECT_EQ(r.visibility.size(), filtered ? s.lights.size() : 0u);
    }
  }
}

// Distance cubes (RenderOptions::cube_depth) are declared per light, where they are drawn: a point
// or spot light's cube under the depth-texture maps, with a range beyond every point of the scene
// from the light and the shader's constant step as its bias; a sun's one view, shadowmap-rgba8's
// packed cubes and pcss's rect light keep window depth (no per-light entry says otherwise).
TEST(Renderer, DistanceCubesAreDeclaredPerLightWhereTheyAreDrawn) {
  RenderOptions o;
  o.cube_depth = outputs::StoredDepth::Distance;
  const scene::Scene two = load("two_lights", 32);
  for (const char* technique : {"shadowmap", "shadowmap-pcf", "csm", "pcss"}) {
    const RenderResult r = renderer().render(two, technique, o);
    ASSERT_EQ(r.declaration.lights.size(), 2u) << technique;
    for (std::size_t i = 0; i < 2; ++i) {
      const outputs::CandidateDeclaration& d = r.declaration.lights[i];
      EXPECT_EQ(d.depth, outputs::StoredDepth::Distance) << technique << " light " << i;
      const Vec3<double> at = two.lights[i].position;
      double farthest = 0;
      for (const scene::Object& obj : two.objects)
        for (const Vec3<float>& v : obj.mesh.positions) farthest = std::max(farthest, (v.cast<double>() - at).norm());
      EXPECT_GT(d.depth_range, farthest) << technique << ": every caster's distance below 1";
      EXPECT_GT(d.depth_bias, 0.0);
      EXPECT_LT(d.depth_bias * d.depth_range, 1e-4) << "a constant step, not a bias that detaches shadows";
    }
  }
  for (const char* technique : {"shadowmap-rgba8", "planar"}) {
    const RenderResult r = renderer().render(two, technique, o);
    EXPECT_TRUE(r.declaration.lights.empty()) << technique;
    EXPECT_EQ(r.declaration.depth, outputs::StoredDepth::Window) << technique;
  }
  // A spot light's map is a cube too (the mask is occlusion everywhere, its cone or not); a sun's
  // one view keeps window depth.
  const RenderResult spot = renderer().render(load("spot_light", 32), "shadowmap", o);
  ASSERT_EQ(spot.declaration.lights.size(), 1u);
  EXPECT_EQ(spot.declaration.lights[0].depth, outputs::StoredDepth::Distance);
  const RenderResult sun = renderer().render(load("directional_light", 32), "shadowmap", o);
  EXPECT_TRUE(sun.declaration.lights.empty()) << "a directional light's one view keeps window depth";
  const RenderResult rect = renderer().render(load("soft_penumbra", 32), "pcss", o);
  EXPECT_TRUE(rect.declaration.lights.empty()) << "pcss's rect light keeps window depth";
}

// Light views of our own (RenderOptions::view_turn_degrees, view_phase_texels): the texel grid
// turns and moves, so the staircases move with it (the verdicts are the conformance sweeps'), and
// the declaration says "own"; neither one set leaves the pack's views, byte for byte.
TEST(Renderer, OwnViewsMoveTheStaircasesAndAreDeclaredOwn) {
  const scene::Scene s = load("grazing_light", 128);
  RenderOptions pack;
  pack.shadow_map_size = 256;
  const RenderResult plain = renderer().render(s, "shadowmap", pack);
  EXPECT_EQ(plain.declaration.light_views, outputs::LightViews::Pack);
  for (const double turn : {0.0, 30.0}) {
    RenderOptions own = pack;
    own.view_turn_degrees = turn;
    own.view_phase_texels = 0.5;
    const RenderResult r = renderer().render(s, "shadowmap", own);
    EXPECT_EQ(r.declaration.light_views, outputs::LightViews::Own) << turn;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < r.masks.at(0).pixels.size(); ++i) differ += r.masks[0].pixels[i] != plain.masks[0].pixels[i];
    // At 128² a 256-texel texel spans several pixels along this ground: a grid moved by half a
    // texel moves the long shadows' staircases by pixels.
    EXPECT_GT(differ, 20u) << "turned " << turn << " degrees, moved half a texel";
  }
}

// Every shadow-map technique × every light type × the options that change a depth pass: each
// light's candidate.json declaration says what its depth pass drew with, as read back from GL
// (RenderResult::drawn_maps: the polygon offset or the depth shader's own, the faces kept on closed
// casters, the map's texels, distances). The soft techniques draw lights without an area with PCF's
// map (front faces culled, PCF's slope factor), their rect lights with the first surfaces and the
// plain factor, and declare each as drawn.
TEST(Renderer, EveryMapDeclarationSaysWhatItsDepthPassDrew) {
  // One light each: directional, spot, point, rect; each scene has a closed caster (box or sphere).
  const char* const scenes[] = {"directional_light", "spot_light", "ground_sphere", "soft_penumbra"};
  std::vector<RenderOptions> variants(7);
  for (RenderOptions& o : variants) o.shadow_map_size = 128;
  variants[1].depth_faces = outputs::DepthFaces::Front;
  variants[2].guard_band_texels = 3;
  variants[3].cube_depth = outputs::StoredDepth::Distance;
  variants[4].random_taps = 16;
  variants[4].normal_offset_texels = 1.0;
  variants[5].faults.shadow_map.no_polygon_offset = true;
  // Float depth maps, whose offset GL would take in a unit relative to the depth.
  variants[6].convention = find_run_convention("reversed-z");
  variants[6].depth_faces = outputs::DepthFaces::Front;
  // glPolygonOffset's unit on a 24-bit map is one step of the depth (2^-24 of the window range, the
  // declared unit); the shaders that add it by hand divide by 2^24 (a packed depth: 2^24 - 1, the two
  // agreeing to 6e-8 relative), a distance cube's by 2^24 - 1 (its declared unit). A float map's
  // offset is drawn by hand: GL's own unit there (relative to the depth, DrawnMap::unit_depth 0)
  // is no depth_bias a declaration could state.
  constexpr double kWindowStep = 1.0 / 16777216.0, kShaderStep = 1.0 / 16777215.0;
  int lights_checked = 0;
  for (const outputs::TechniqueName& t : outputs::kTechniques) {
    if (t.family == outputs::TechniqueFamily::ExactGeometry) continue;
    for (const char* name : scenes) {
      const scene::Scene s = load(name, 32);
      for (std::size_t v = 0; v < variants.size(); ++v) {
        SCOPED_TRACE(std::string(t.name) + " on " + name + ", options " + std::to_string(v));
        const RenderResult r = renderer().render(s, t.name, variants[v]);
        ASSERT_EQ(r.drawn_maps.size(), s.lights.size());
        for (std::size_t i = 0; i < s.lights.size(); ++i) {
          const outputs::CandidateDeclaration& d = r.declaration.for_light(i);
          const DrawnMap& m = r.drawn_maps[i];
          ASSERT_TRUE(m.closed_faces.has_value()) << "every scene here has a closed caster";
          EXPECT_EQ(d.depth_faces, *m.closed_faces) << m.lookup;
          EXPECT_EQ(d.slope_bias_texels, double{m.slope_factor}) << m.lookup;
          EXPECT_EQ(d.depth == outputs::StoredDepth::Distance, m.distance) << m.lookup;
          const double step = m.distance ? kShaderStep : kWindowStep;
          EXPECT_NEAR(m.unit_depth, step, 1e-7 * step) << m.lookup << ": the offset's unit is not the declared step";
          EXPECT_NEAR(d.depth_bias, double{m.offset_units} * step, 1e-7 * d.depth_bias) << m.lookup;
          const int texels = d.atlas_tile_size > 0 ? d.atlas_tile_size : d.shadow_map_size;
          EXPECT_EQ(texels, m.texels) << m.lookup;
          ++lights_checked;
        }
      }
    }
  }
  EXPECT_EQ(lights_checked, 7 * 4 * 7);
}

// The alpha rule's GLSL (scene::alpha_rule_glsl, shaders.cpp's alpha_test) against its C++
// (scene/alpha_mask.hpp), texel by texel: a masked card seen straight down fills the image, with
// nothing behind it, so a pixel shows no surface exactly where the camera pass discarded. Every
// pixel centre away from a texel's edge must agree with the C++ rule at that point. The texels hold
// the values around the threshold (cutoff 0.2: exactly 51 in float, so 51 is opaque and 50 is not),
// and the coordinates run past 1 so that REPEAT is exercised.
TEST(Renderer, AlphaRuleInGlslAgreesWithTheCppTexelByTexel) {
  namespace fs = std::filesystem;
  constexpr int kTexels = 16;
  constexpr double kRepeat = 1.5;  // uv from 0 to 1.5: the texture and half of it again
  const fs::path dir = fs::path(::testing::TempDir()) / "shadowref-alpha-rule";
  fs::create_directories(dir);
  Image8 png{kTexels, kTexels, 2, {}};
  std::uint32_t seed = 12345;
  const std::uint8_t near_threshold[] = {50, 51, 52, 0, 255};
  for (int k = 0; k < kTexels * kTexels; ++k) {
    seed = seed * 1664525u + 1013904223u;  // Numerical Recipes' LCG: deterministic
    const std::uint8_t a = (seed >> 28) < 10 ? near_threshold[(seed >> 24) % 5] : static_cast<std::uint8_t>(seed >> 24);
    png.pixels.insert(png.pixels.end(), {std::uint8_t{200}, a});
  }
  outputs::write_png(png, dir / "mask.png");
  // The camera 10 above the card's centre, image top toward -z (v = 0); the card's 2 × 2 square
  // spans 2.4 / 2 of the view.
  const nlohmann::json doc = {
      {"name", "alpha_rule"},
      {"resolution", {240, 240}},
      {"camera", {{"position", {0, 10, 0}}, {"target", {0, 0, 0}}, {"up", {0, 0, -1}}, {"fovy_deg", 13.69}, {"near", 1}}},
      {"lights", {{{"type", "directional"}, {"direction", {0, 1, 0}}}}},
      {"objects",
       {{{"name", "card"},
         {"shape", {{"type", "plane"}, {"size", {2, 2}}}},
         {"uvs", {{0, 0}, {kRepeat, 0}, {kRepeat, kRepeat}, {0, kRepeat}}},
         {"alpha_texture", "mask.png"},
         {"alpha_cutoff", 0.2}}}}};
  const scene::Scene s = scene::parse_scene(doc.dump(), dir / "scene.json");
  const scene::AlphaMask& mask = *s.objects[0].alpha;
  const Mat4<double> world_from_clip = (scene::projection_matrix<double>(s.camera, s.width, s.height).value() *
                                        scene::view_matrix<double>(s.camera).value()).inverse();
  for (const char* technique : {"planar", "shadowmap", "volume-zfail"}) {
    SCOPED_TRACE(technique);
    const RenderResult r = renderer().render(s, technique, fast_options());
    int compared = 0, discarded = 0, wrong = 0;
    std::vector<int> texels_seen(kTexels * kTexels, 0);
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const Vec2<double> ndc = scene::pixel_to_ndc<double>(x, y, 0.5, 0.5, s.width, s.height);
        const Vec4<double> a = world_from_clip * Vec4<double>(ndc.x(), ndc.y(), -1, 1);
        const Vec4<double> b = world_from_clip * Vec4<double>(ndc.x(), ndc.y(), 0, 1);
        const Vec3<double> o = a.head<3>() / a.w(), d = b.head<3>() / b.w() - o;
        const Vec3<double> p = o + (-o.y() / d.y()) * d;
        if (std::abs(p.x()) >= 1 || std::abs(p.z()) >= 1) continue;
        const double u = (p.x() + 1) / 2 * kRepeat, v = (p.z() + 1) / 2 * kRepeat;
        // Away from a texel's edge by a tenth of a texel: float interpolation decides the edge itself.
        const double fu = u * kTexels - std::floor(u * kTexels), fv = v * kTexels - std::floor(v * kTexels);
        if (fu < 0.1 || fu > 0.9 || fv < 0.1 || fv > 0.9) continue;
        const int i = scene::alpha_texel(static_cast<float>(u), kTexels), j = scene::alpha_texel(static_cast<float>(v), kTexels);
        const bool opaque = scene::alpha_opaque(mask.texture->at(i, j), 1.0f, scene::alpha_threshold(mask.cutoff));
        const std::uint8_t got = r.masks[0].pixels[static_cast<std::size_t>(y * s.width + x)];
        ++compared;
        ++texels_seen[static_cast<std::size_t>(j * kTexels + i)];
        discarded += got == outputs::kMaskNoSurface ? 1 : 0;
        if ((got == outputs::kMaskNoSurface) == opaque) ++wrong;
      }
    EXPECT_EQ(wrong, 0) << "of " << compared;
    EXPECT_EQ(std::count(texels_seen.begin(), texels_seen.end(), 0), 0) << "every texel must be compared";
    EXPECT_GT(discarded, compared / 10);
    EXPECT_LT(discarded, compared * 9 / 10);
  }
}

// GPU skinning (kSceneVertex's Skin block) against the CPU's pose (scene/skin.hpp): the skinned
// character rendered with its skin and as the rigid, CPU-posed mesh gives the same masks up to
// rounding on edges, for shadow maps (skinned depth and camera passes) and the planar projection;
// the reference agrees with the skinned shadow maps, and the bind-pose fault moves their shadow.
TEST(Renderer, GpuSkinningMatchesTheCpuPose) {
  const scene::Scene skinned = load("skinned_character", 128);
  ASSERT_TRUE(skinned.objects[1].skin);
  scene::Scene rigid = skinned;
  rigid.objects[1].skin.reset();
  const auto differing = [](const Image8& a, const Image8& b) {
    int n = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) n += a.pixels[i] != b.pixels[i];
    return n;
  };
  const reference::Images ref = reference_of(skinned);
  for (const char* technique : {"shadowmap", "planar", "shadowmap-pcf"}) {
    SCOPED_TRACE(technique);
    const RenderResult gpu = renderer().render(skinned, technique, fast_options());
    const RenderResult cpu = renderer().render(rigid, technique, fast_options());
    // Rounding of the float sums may flip a pixel whose centre lies on an edge: a handful at most.
    EXPECT_LE(differing(gpu.masks[0], cpu.masks[0]), 8);
    if (std::string(technique) == "planar") continue;  // the character shadows itself, which planar cannot
    const Agreement a = compare(gpu.masks[0], ref.lights[0]);
    EXPECT_GT(a.decided_shadowed, 200);
    EXPECT_LT(a.wrong_fraction(), 0.01) << a.wrong << " of " << a.decided;
  }
  RenderOptions bind_pose = fast_options();
  bind_pose.faults.shadow_map.skin_bind_pose = true;
  const RenderResult posed = renderer().render(skinned, "shadowmap", fast_options());
  const RenderResult wrong = renderer().render(skinned, "shadowmap", bind_pose);
  EXPECT_GT(differing(posed.masks[0], wrong.masks[0]), 100);
  EXPECT_EQ(wrong.faults, "shadow_map.skin=bind_pose");
}

TEST(Renderer, UnknownTechniqueIsRefused) {
  const scene::Scene s = load("ground_sphere", 16);
  EXPECT_THROW((void)renderer().render(s, "no-such-technique"), std::invalid_argument);
  EXPECT_EQ(find_technique("no-such-technique"), nullptr);
}

// A map larger than the GL holds in one texture is said with its size, and the renderer draws the
// next render as before. llvmpipe refuses any texture over 1 GiB: a point light's cube of six
// 8192-texel layers of 32-bit depth is 1.5 GiB (before, the line was "the shadow-map framebuffer
// is incomplete", which names neither the map nor the way out).
TEST(Renderer, AMapTheGlCannotHoldIsSaidWithItsSize) {
  const scene::Scene s = load("ground_sphere", 32);
  RenderOptions big;
  big.shadow_map_size = 8192;
  if (test_driver() == Driver::Llvmpipe) {
    try {
      (void)renderer().render(s, "shadowmap", big);
      ADD_FAILURE() << "llvmpipe held a 1.5 GiB cube";
    } catch (const GlError& e) {
      EXPECT_NE(std::string(e.what()).find("8192 x 8192 texels x 6 layer(s) (1536 MiB)"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("a smaller --shadow-map-size fits"), std::string::npos) << e.what();
    }
  }
  const RenderResult after = renderer().render(s, "shadowmap");
  ASSERT_EQ(after.masks.size(), 1u);
  EXPECT_EQ(after.masks[0].width, 32);
}

// Only a masked object draws with a program that can discard. A fragment shader with a discard in
// its text loses the rasteriser's early depth test (llvmpipe decides it from the shader), which made
// every pass of scenes without a single mask half again slower (cascades of a self-shadowing torus,
// 42 → 65 ms) when the alpha test first went into every program.
TEST(Programs, OnlyTheAlphaTestedBuildsCanDiscard) {
  std::vector<std::pair<std::string, std::vector<std::string>>> fragments = {
      {"flat", {shaders::kVersion, shaders::kFlatFragment}},
      {"moments", {shaders::kVersion, shaders::kMomentsFragment}},
      {"offset depth", {shaders::kVersion, shaders::kOffsetDepthFragment}},
      {"moments and offset depth", {shaders::kVersion, shaders::kDepthByHand, shaders::kMomentsFragment}},
      {"distance", {shaders::kVersion, shaders::kDistanceFragment}},
      {"packed depth", {shaders::kVersion, shaders::kDepthPacking, shaders::kPackedDepthFragmentBody}},
      {"surface", shaders::surface_fragment(nullptr)},
      {"surface (pcf)", shaders::surface_fragment(&kPcfLookup)},  // every soft technique's lights without an area
  };
  for (const outputs::TechniqueName& t : outputs::kTechniques)
    if (const MapTechnique* m = find_map_technique(t.name))
      fragments.emplace_back("surface (" + std::string(t.name) + ")", shaders::surface_fragment(&m->lookup));
  const auto joined = [](const std::vector<std::string>& strings) {
    std::string all;
    for (const std::string& s : strings) all += s;
    return all;
  };
  for (const auto& [name, fragment] : fragments) {
    EXPECT_EQ(joined(shaders::with_alpha_test(fragment, false)).find("discard"), std::string::npos) << name;
    EXPECT_NE(joined(shaders::with_alpha_test(fragment, true)).find("discard"), std::string::npos) << name;
  }
}

// A mode is a lookup's own code or a bool, never an integer a branch compares with a literal (a
// number whose meaning lives in the C++ that sets it): every program's source, both builds.
TEST(Programs, NoBranchComparesAnIntegerWithALiteral) {
  std::vector<std::pair<std::string, std::string>> sources = {{"scene vertex", shaders::kSceneVertex}};
  std::vector<std::pair<std::string, std::vector<std::string>>> fragments = {
      {"flat", {shaders::kFlatFragment}},
      {"moments", {shaders::kMomentsFragment}},
      {"distance", {shaders::kDistanceFragment}},
      {"packed depth", {shaders::kDepthPacking, shaders::kPackedDepthFragmentBody}},
      {"surface", shaders::surface_fragment(nullptr)},
  };
  for (const outputs::TechniqueName& t : outputs::kTechniques)
    if (const MapTechnique* m = find_map_technique(t.name))
      fragments.emplace_back("surface (" + std::string(t.name) + ")", shaders::surface_fragment(&m->lookup));
  for (const auto& [name, fragment] : fragments)
    for (const bool tested : {false, true}) {
      std::string all;
      for (const std::string& s : shaders::with_alpha_test(fragment, tested)) all += s;
      sources.emplace_back(name + (tested ? " (alpha-tested)" : ""), all);
    }
  // `if (` then, before its closing parenthesis, `==` or `!=` and an integer literal (a float such
  // as 0.0 is a value, not a mode).
  const std::regex branch(R"(\bif\s*\([^)]*[=!]=\s*-?[0-9]+[uU]?\s*\))");
  for (const auto& [name, source] : sources) {
    std::smatch m;
    EXPECT_FALSE(std::regex_search(source, m, branch)) << name << ": " << m.str();
  }
}

}  // namespace
}  // namespace shadowref::renderer
