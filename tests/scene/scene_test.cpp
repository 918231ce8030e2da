// build_scene (scene/scene.h): trees grown once per (species, seed, time) and shared as
// prototypes, placed by their instances, named for compositing, the ground added.
#include "formats/scene_file.h"
#include "scene/scene.h"

#include <cstring>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <cmath>

#include <gtest/gtest.h>

namespace arbor::scene {
namespace {

const std::string kOcio = std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio";

std::string tree(const char* species, int seed, double x) {
  return "[[tree]]\nspecies = \"" + std::string(ARBOR_SOURCE_DIR) + "/species/" + species +
         "\"\nseed = " + std::to_string(seed) + "\nposition = [" + std::to_string(x) +
         ", 0.0, 0.0]\n";
}

TEST(BuildScene, TreesOfOneSpeciesAndSeedShareOnePrototype) {
  const spec::SceneDesc desc =
      formats::parse_scene(tree("young_tree.skel", 1, 0.0) + tree("young_tree.skel", 1, 4.0) +
                               tree("young_tree.skel", 2, 8.0) + tree("dogwood.tmpl", 1, 12.0),
                           "/tmp/scene.toml");
  const std::unique_ptr<const Scene> scene = build_scene(desc, kOcio);
  ASSERT_EQ(scene->instances.size(), 4u);
  // One prototype per (species, seed, time): the two trees of seed 1 share theirs; seed 2 and the
  // dogwood have their own.
  EXPECT_EQ(scene->prototypes.size(), 3u);
  EXPECT_EQ(scene->stats.prototypes, 3u);
  EXPECT_EQ(scene->instances[0].prototype, scene->instances[1].prototype);
  EXPECT_NE(scene->instances[0].prototype, scene->instances[2].prototype);
  EXPECT_NE(scene->instances[0].prototype, scene->instances[3].prototype);
  EXPECT_NE(scene->instances[2].prototype, scene->instances[3].prototype);
  // Each instance sits where its [[tree]] says.
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(scene->instances[i].to_world[3][0], 4.0f * static_cast<float>(i), 1e-5f) << i;
    EXPECT_NEAR(scene->instances[i].to_world[3][1], 0.0f, 1e-6f) << i;
  }
  // Compositing ids: one per tree in scene order, then the ground; names unique.
  ASSERT_EQ(scene->object_names.size(), 5u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(scene->instances[i].object_id, i + 1) << i;
  EXPECT_EQ(scene->object_names.back(), "ground");
  EXPECT_TRUE(scene->has_ground);
  for (std::size_t a = 0; a < scene->object_names.size(); ++a) {
    for (std::size_t b = a + 1; b < scene->object_names.size(); ++b) {
      EXPECT_NE(scene->object_names[a], scene->object_names[b]);
    }
  }
}

// The same bytes: a vector of trivially copyable values compared as memory.
template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Growing prototypes in parallel builds the scene growing them one by one builds: the same
// prototypes in the same order, byte for byte, and the same instances.
TEST(BuildScene, ParallelGrowthBuildsTheSceneSerialGrowthBuilds) {
  const spec::SceneDesc desc = formats::parse_scene(
      tree("young_tree.skel", 1, 0.0) + tree("dogwood.tmpl", 3, 4.0) +
          tree("young_tree.skel", 1, 8.0) + tree("dogwood.tmpl", 4, 12.0) +
          "[[forest]]\nspecies = \"" + std::string(ARBOR_SOURCE_DIR) +
          "/species/dogwood.tmpl\"\ncount = 12\nvariants = 5\narea = [[-9.0, -9.0], [9.0, 9.0]]\n",
      "/tmp/scene.toml");
  const std::unique_ptr<const Scene> one = build_scene(desc, kOcio, nullptr, 0, 1);
  ASSERT_EQ(one->prototypes.size(), 3u + 5u);
  for (unsigned threads : {2u, 3u, 0u}) {
    SCOPED_TRACE(threads);
    const std::unique_ptr<const Scene> many = build_scene(desc, kOcio, nullptr, 0, threads);
    ASSERT_EQ(many->prototypes.size(), one->prototypes.size());
    for (std::size_t p = 0; p < one->prototypes.size(); ++p) {
      const generator::TreeGeometry& a = *one->prototypes[p].geometry;
      const generator::TreeGeometry& b = *many->prototypes[p].geometry;
      EXPECT_TRUE(same_bytes(a.curves.points, b.curves.points)) << p;
      EXPECT_TRUE(same_bytes(a.leaves.positions, b.leaves.positions)) << p;
      EXPECT_TRUE(same_bytes(a.cards.corners, b.cards.corners)) << p;
    }
    ASSERT_EQ(many->instances.size(), one->instances.size());
    for (std::size_t i = 0; i < one->instances.size(); ++i) {
      EXPECT_EQ(many->instances[i].prototype, one->instances[i].prototype) << i;
      EXPECT_EQ(many->instances[i].to_world, one->instances[i].to_world) << i;
    }
  }
  // The variants differ from each other (so the comparison above could see a swap).
  EXPECT_FALSE(same_bytes(one->prototypes[3].geometry->leaves.positions,
                          one->prototypes[4].geometry->leaves.positions));
}

// `[tree.leaf] season`: autumn turns a species' leaves towards its autumn colour (the tint is its
// ratio to the summer front); a species without one keeps its leaves; spring tints every leaf.
TEST(BuildScene, TheSeasonTintsLeavesByTheSpeciesAutumnColour) {
  const std::string broadleaf = tree("fractal_broadleaf.toml", 1, 0.0);
  const std::string evergreen = tree("young_tree.skel", 1, 4.0);
  const auto leaf = [&](const std::string& text) {
    return build_scene(formats::parse_scene(text, "/tmp/scene.toml"), kOcio)
        ->instances.front()
        .leaf.as<materials::LeafMaterial>()
        ->season;
  };
  EXPECT_FALSE(leaf(broadleaf).any());  // summer: as given
  const materials::LeafSeason autumn = leaf(broadleaf + "[tree.leaf]\nseason = \"autumn\"\n");
  EXPECT_EQ(autumn.turned, 0.85f);
  // fractal_broadleaf: front (0.08, 0.13, 0.04), autumn (0.55, 0.33, 0.03).
  EXPECT_NEAR(autumn.autumn.x, 0.55f / 0.08f, 1e-4f);
  EXPECT_NEAR(autumn.autumn.y, 0.33f / 0.13f, 1e-4f);
  EXPECT_NEAR(autumn.autumn.z, 0.03f / 0.04f, 1e-4f);
  EXPECT_FALSE(leaf(evergreen + "[tree.leaf]\nseason = \"autumn\"\n").any());
  const materials::LeafSeason spring = leaf(evergreen + "[tree.leaf]\nseason = \"spring\"\n");
  EXPECT_NEAR(spring.spring.x, std::exp(0.35f), 1e-6f);
  EXPECT_NEAR(spring.spring.y, std::exp(0.35f * 0.35f), 1e-6f);
  EXPECT_EQ(spring.spring.z, 1.0f);
}

TEST(BuildScene, AGroundlessSceneHasNoGround) {
  const spec::SceneDesc desc = formats::parse_scene(
      "[ground]\nenabled = false\n" + tree("young_tree.skel", 1, 0.0), "/tmp/scene.toml");
  const std::unique_ptr<const Scene> scene = build_scene(desc, kOcio);
  EXPECT_FALSE(scene->has_ground);
  EXPECT_EQ(scene->object_names.size(), 1u);
}

}  // namespace
}  // namespace arbor::scene
