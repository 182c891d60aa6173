// shard_plan_test.cpp — the assignment of scenes to shards and the CI systems' protocols
// (shard_plan.hpp): adding a scene moves that scene alone, weights balance deterministically, and
// each protocol's index base and malformed values.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "shadowref/ci/shard_plan.hpp"

namespace shadowref::ci {
namespace {

const std::vector<std::string> kCatalogue = {
    "beyond_light_and_below_receiver", "camera_at_light", "camera_in_shadow", "contact_shadow", "cornell_box", "cube_seams",
    "directional_light", "grazing_light", "ground_sphere", "light_bleeding", "light_near_caster", "nested_256_volumes",
    "offscreen_caster", "open_mesh_crack", "shadow_on_object", "soft_cube_seam", "soft_penumbra", "spot_light",
    "stairs_room", "sun_horizon", "torus_self_shadow", "two_lights"};

TEST(ShardPlan, AddingASceneMovesOnlyThatScene) {
  for (int total : {2, 3, 4, 7}) {
    const auto before = assign_shards(kCatalogue, total, {});
    std::vector<std::string> more = kCatalogue;
    more.insert(more.begin() + 5, "a_new_scene");
    const auto after = assign_shards(more, total, {});
    for (const auto& [scene, shard] : before) EXPECT_EQ(after.at(scene), shard) << scene << " moved, " << total << " shards";
    // Removing one moves nothing either.
    std::vector<std::string> fewer(kCatalogue.begin() + 1, kCatalogue.end());
    for (const auto& [scene, shard] : assign_shards(fewer, total, {})) EXPECT_EQ(before.at(scene), shard);
  }
  // A count-based deal (scene i to shard i mod N) would fail the above; the hash spreads the
  // catalogue over every shard.
  std::map<int, int> per_shard;
  for (const auto& [scene, shard] : assign_shards(kCatalogue, 4, {})) ++per_shard[shard];
  EXPECT_EQ(per_shard.size(), 4u);
}

TEST(ShardPlan, WeightsBalanceDeterministically) {
  std::map<std::string, double> weights;
  for (std::size_t i = 0; i < kCatalogue.size(); ++i) weights[kCatalogue[i]] = (i % 5 == 0) ? 10.0 : 1.0;
  const auto plan = assign_shards(kCatalogue, 4, weights);
  EXPECT_EQ(plan, assign_shards(kCatalogue, 4, weights));
  std::vector<double> load(4, 0.0);
  for (const auto& [scene, shard] : plan) load[static_cast<std::size_t>(shard)] += weights.at(scene);
  const auto [lo, hi] = std::minmax_element(load.begin(), load.end());
  EXPECT_LE(*hi - *lo, 10.0) << "the heaviest shard carries more than one heavy scene beyond the lightest";
  // A scene the weights do not know goes by its hash and moves no weighed scene.
  std::vector<std::string> more = kCatalogue;
  more.push_back("a_new_scene");
  const auto after = assign_shards(more, 4, weights);
  for (const auto& [scene, shard] : plan) EXPECT_EQ(after.at(scene), shard) << scene;
  EXPECT_EQ(after.at("a_new_scene"), static_cast<int>(stable_hash("a_new_scene") % 4));
}

std::optional<ShardSpec> from(const std::map<std::string, std::string>& env) {
  return shard_from_environment([&](const char* name) -> const char* {
    const auto it = env.find(name);
    return it == env.end() ? nullptr : it->second.c_str();
  });
}

TEST(ShardPlan, Protocols) {
  EXPECT_FALSE(from({}));
  const auto bazel = from({{"TEST_TOTAL_SHARDS", "4"}, {"TEST_SHARD_INDEX", "0"}, {"TEST_SHARD_STATUS_FILE", "/tmp/s"}});
  ASSERT_TRUE(bazel);
  EXPECT_EQ(bazel->index, 0);
  EXPECT_EQ(bazel->total, 4);
  EXPECT_EQ(bazel->status_file, "/tmp/s");
  const auto gtest = from({{"GTEST_TOTAL_SHARDS", "3"}, {"GTEST_SHARD_INDEX", "2"}});
  ASSERT_TRUE(gtest);
  EXPECT_EQ(gtest->index, 2);
  const auto gitlab = from({{"CI_NODE_TOTAL", "4"}, {"CI_NODE_INDEX", "4"}});  // 1-based
  ASSERT_TRUE(gitlab);
  EXPECT_EQ(gitlab->index, 3);
  EXPECT_EQ(gitlab->source, "CI_NODE_TOTAL");
  EXPECT_THROW(from({{"CI_NODE_TOTAL", "4"}, {"CI_NODE_INDEX", "0"}}), std::invalid_argument);
  EXPECT_THROW(from({{"TEST_TOTAL_SHARDS", "4"}, {"TEST_SHARD_INDEX", "4"}}), std::invalid_argument);
  EXPECT_THROW(from({{"TEST_TOTAL_SHARDS", "4"}}), std::invalid_argument);
  EXPECT_THROW(from({{"TEST_TOTAL_SHARDS", "x"}, {"TEST_SHARD_INDEX", "0"}}), std::invalid_argument);
  const ShardSpec flag = parse_shard_flag("2/4");
  EXPECT_EQ(flag.index, 1);
  EXPECT_EQ(flag.total, 4);
  for (const char* bad : {"0/4", "5/4", "4", "a/b", "1/0", "-1/4", "1/4x"}) EXPECT_THROW(parse_shard_flag(bad), std::invalid_argument) << bad;
}

}  // namespace
}  // namespace shadowref::ci
