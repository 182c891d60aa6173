// alpha_mask_test.cpp — the alpha rule (alpha_mask.hpp): the texel picked (nearest, wrapped), the
// comparison at equality, the interpolation at barycentrics, and what the loader reads from a mask.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <vector>

#include "shadowref/outputs/image.hpp"
#include "shadowref/scene/alpha_mask.hpp"
#include "shadowref/scene/load_scene.hpp"
#include "test_scene_json.hpp"

namespace shadowref::scene {
namespace {

TEST(AlphaRule, TexelIsNearestAndWraps) {
  EXPECT_EQ(alpha_texel(0.0f, 4), 0);
  EXPECT_EQ(alpha_texel(0.2499f, 4), 0);
  EXPECT_EQ(alpha_texel(0.25f, 4), 1);      // a texel's left edge belongs to it
  EXPECT_EQ(alpha_texel(0.99999994f, 4), 3);  // the largest float below 1: still the last texel
  EXPECT_EQ(alpha_texel(1.0f, 4), 0);       // REPEAT: 1 is the next tile's 0
  EXPECT_EQ(alpha_texel(1.3f, 4), 1);
  EXPECT_EQ(alpha_texel(-0.1f, 4), 3);      // below 0 wraps to the end
  EXPECT_EQ(alpha_texel(-1e-9f, 4), 3);     // f = 1 - 1e-9 rounds to 1 in float: clamped to the last texel
  EXPECT_EQ(alpha_texel(63.9f, 8), 7);      // near kMaxAlphaUv
}

TEST(AlphaRule, EqualityIsOpaque) {
  // glTF: "rendered fully opaque when alpha >= alphaCutoff". 0.2 · 255 rounds to exactly 51 in float.
  ASSERT_EQ(alpha_threshold(0.2), 51.0f);
  EXPECT_TRUE(alpha_opaque(51, 1.0f, alpha_threshold(0.2)));
  EXPECT_FALSE(alpha_opaque(50, 1.0f, alpha_threshold(0.2)));
  // 0.5 · 255 = 127.5: 127 lets light through, 128 casts.
  EXPECT_FALSE(alpha_opaque(127, 1.0f, alpha_threshold(0.5)));
  EXPECT_TRUE(alpha_opaque(128, 1.0f, alpha_threshold(0.5)));
  // Cutoff 0: everything casts, even alpha 0; cutoff 1: only 255 with full vertex alpha.
  EXPECT_TRUE(alpha_opaque(0, 0.0f, alpha_threshold(0.0)));
  EXPECT_TRUE(alpha_opaque(255, 1.0f, alpha_threshold(1.0)));
  EXPECT_FALSE(alpha_opaque(255, 0.999f, alpha_threshold(1.0)));
  // Vertex alpha multiplies: 255 · 0.5 = 127.5 >= 127.5.
  EXPECT_TRUE(alpha_opaque(255, 0.5f, alpha_threshold(0.5)));
  EXPECT_FALSE(alpha_opaque(255, 0.49f, alpha_threshold(0.5)));
}

TEST(AlphaRule, InterpolatesAtBarycentrics) {
  // One triangle over the unit square's lower-left half: uv = (b1, b2) at barycentrics (b1, b2).
  AlphaMask mask;
  auto texture = std::make_shared<AlphaTexture>();
  texture->width = 2;
  texture->height = 2;
  texture->alpha = {255, 0, 0, 0};  // only texel (0, 0), the top-left, is opaque
  mask.texture = texture;
  mask.uvs = {Vec2<float>(0, 0), Vec2<float>(1, 0), Vec2<float>(0, 1)};
  mask.vertex_alpha = {1, 1, 1};
  mask.cutoff = 0.5;
  const std::array<std::uint32_t, 3> tri{0, 1, 2};
  EXPECT_TRUE(alpha_opaque_at(mask, tri, 0.1f, 0.1f));
  EXPECT_FALSE(alpha_opaque_at(mask, tri, 0.6f, 0.1f));  // u = 0.6: texel (1, 0)
  EXPECT_FALSE(alpha_opaque_at(mask, tri, 0.1f, 0.6f));  // v = 0.6: texel (0, 1), the second row
  // Vertex alpha interpolated with the same barycentrics, inside the opaque texel: 0.4 at vertex 0.
  mask.vertex_alpha = {0.4f, 1, 1};
  EXPECT_FALSE(alpha_opaque_at(mask, tri, 0.05f, 0.05f));  // a = 0.4·0.9 + 0.1 = 0.46: 117 < 127.5
  EXPECT_TRUE(alpha_opaque_at(mask, tri, 0.2f, 0.2f));     // a = 0.4·0.6 + 0.4 = 0.64: 163
}

std::filesystem::path data(const char* name) { return std::filesystem::path(SHADOWREF_SCENE_TEST_DATA) / name; }

Scene with_card(const nlohmann::json& card) {
  nlohmann::json doc = test::minimal_scene();
  doc["objects"][1] = card;
  return parse_scene(doc.dump(), data("test.json"));
}

// The one reader of a mask texture, under each format's rule for an image without alpha: the
// alpha channel whatever the rule; a grey image's grey (a JSON scene) or none, alpha 1 (glTF).
TEST(AlphaTextureOf, TheAlphaChannelUnderBothRulesAndTheGreyOnlyUnderTheScenesRule) {
  const auto image = [](int channels, std::vector<std::uint8_t> pixels) {
    outputs::Image8 m;
    m.width = 2;
    m.height = 1;
    m.channels = channels;
    m.pixels = std::move(pixels);
    return m;
  };
  const outputs::Image8 grey = image(1, {10, 200}), grey_alpha = image(2, {10, 20, 200, 30}),
                        rgb = image(3, {1, 2, 3, 4, 5, 6}), rgba = image(4, {1, 2, 3, 40, 4, 5, 6, 50});
  for (const WithoutAlpha rule : {WithoutAlpha::Grey, WithoutAlpha::Opaque}) {
    const auto ga = alpha_texture_of(grey_alpha, "ga.png", rule);
    ASSERT_TRUE(ga);
    EXPECT_EQ(ga->alpha, (std::vector<std::uint8_t>{20, 30}));
    EXPECT_EQ(ga->file, "ga.png");
    EXPECT_EQ(ga->width, 2);
    EXPECT_EQ(ga->height, 1);
    const auto c = alpha_texture_of(rgba, "c.png", rule);
    ASSERT_TRUE(c);
    EXPECT_EQ(c->alpha, (std::vector<std::uint8_t>{40, 50}));
  }
  const auto g = alpha_texture_of(grey, "g.png", WithoutAlpha::Grey);
  ASSERT_TRUE(g);
  EXPECT_EQ(g->alpha, (std::vector<std::uint8_t>{10, 200}));
  EXPECT_EQ(alpha_texture_of(grey, "g.png", WithoutAlpha::Opaque), nullptr);
  EXPECT_EQ(alpha_texture_of(rgb, "rgb.png", WithoutAlpha::Opaque), nullptr);
  EXPECT_THROW(alpha_texture_of(rgb, "rgb.png", WithoutAlpha::Grey), std::invalid_argument);
  outputs::Image8 wide = image(2, {});
  wide.width = kMaxAlphaTextureSize + 1;
  wide.pixels.assign(static_cast<std::size_t>(wide.width) * 2, 255);
  EXPECT_THROW(alpha_texture_of(wide, "wide.png", WithoutAlpha::Opaque), std::invalid_argument);
}

TEST(AlphaLoad, ReadsTheAlphaChannelNotTheGrey) {
  const Scene s = with_card({{"shape", {{"type", "plane"}, {"size", {1, 1}}}},
                             {"uvs", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}},
                             {"alpha_texture", "mask_ga.png"},
                             {"alpha_cutoff", 0.2}});
  ASSERT_TRUE(s.objects[1].alpha.has_value());
  const AlphaMask& m = *s.objects[1].alpha;
  EXPECT_EQ(m.texture->width, 2);
  EXPECT_EQ(m.texture->height, 2);
  EXPECT_EQ(m.texture->alpha, (std::vector<std::uint8_t>{0, 51, 128, 255}));
  EXPECT_EQ(m.vertex_alpha, (std::vector<float>(4, 1.0f)));  // none given: 1
  EXPECT_FALSE(m.has_vertex_alpha);
  EXPECT_DOUBLE_EQ(m.cutoff, 0.2);
  EXPECT_EQ(m.uvs[2], Vec2<float>(1, 1));
  EXPECT_FALSE(s.objects[0].alpha.has_value());  // an object without the keys is opaque
}

TEST(AlphaLoad, GreyMaskWithoutAlphaIsTheMask) {
  const Scene s = with_card({{"shape", {{"type", "plane"}, {"size", {1, 1}}}},
                             {"uvs", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}},
                             {"alpha_texture", "mask_grey.png"},
                             {"alpha_cutoff", 0.5}});
  EXPECT_EQ(s.objects[1].alpha->texture->alpha, (std::vector<std::uint8_t>{10, 250}));
}

TEST(AlphaLoad, VertexAlphaAloneHasAnOpaqueTexel) {
  const Scene s = with_card({{"shape", {{"type", "plane"}, {"size", {1, 1}}}},
                             {"vertex_alpha", {1, 0.5, 0, 0.25}},
                             {"alpha_cutoff", 0.5}});
  const AlphaMask& m = *s.objects[1].alpha;
  EXPECT_TRUE(m.has_vertex_alpha);
  EXPECT_EQ(m.vertex_alpha, (std::vector<float>{1, 0.5f, 0, 0.25f}));
  EXPECT_EQ(m.texture->alpha, (std::vector<std::uint8_t>{255}));
  EXPECT_TRUE(m.texture->file.empty());
}

TEST(AlphaLoad, CatalogueMasksLoad) {
  // The catalogue's masked scenes (scripts/make_alpha_content.py) load, with the masks they name.
  for (const char* name : {"alpha_cards.json", "alpha_fence.json", "alpha_vertex.json"}) {
    const Scene s = load_scene(std::filesystem::path(SHADOWREF_SCENES_DIR) / name);
    int masked = 0;
    for (const Object& o : s.objects) masked += o.alpha ? 1 : 0;
    EXPECT_GE(masked, 1) << name;
  }
}

}  // namespace
}  // namespace shadowref::scene
