// Tests of the [terrain] table and camera.above_ground as the scene reader reads them: values,
// ranges, keys of another kind and the rules across keys, each refused at its line and column.
#include <string>

#include <gtest/gtest.h>

#include "expect_scene_error.h"

#include "formats/scene_file.h"

namespace arbor::formats {

TEST(SceneTerrain, ItsKeysAreRead) {
  const spec::SceneDesc none = parse_scene("", "s.toml");
  EXPECT_FALSE(none.terrain.enabled);
  const spec::SceneDesc s = parse_scene(
      "[terrain]\nkind = \"mountains\"\nsize = 2000\nrelief = 350\nseed = 7\nresolution = 4\n"
      "rock_slope = 40\nrock_albedo = [0.3, 0.3, 0.3]\nsurround = 2.5\n[camera]\nposition = [1, 2, "
      "3]\n"
      "above_ground = 1.7\n",
      "s.toml");
  EXPECT_TRUE(s.terrain.enabled);
  EXPECT_EQ(s.terrain.kind, spec::TerrainKind::Mountains);
  EXPECT_EQ(s.terrain.size, 2000.0);
  EXPECT_EQ(s.terrain.relief, 350.0);
  EXPECT_EQ(s.terrain.seed, 7u);
  EXPECT_EQ(s.terrain.resolution, 4.0);
  EXPECT_EQ(s.terrain.rock_slope, 40.0);
  EXPECT_EQ(s.terrain.surround, 2.5);
  EXPECT_EQ(none.terrain.surround, 4.0);  // the default: far hills to the horizon
  ASSERT_TRUE(s.camera.above_ground.has_value());
  EXPECT_EQ(*s.camera.above_ground, 1.7);
  EXPECT_EQ(s.camera.focus_distance, 0.0);  // measured once the eye stands on the terrain
  const spec::SceneDesc image = parse_scene(
      "[terrain]\nkind = \"image\"\npath = \"dem.png\"\nmetres_per_pixel = 30\n"
      "height_scale = 1000\n",
      "scenes/s.toml");
  EXPECT_EQ(image.terrain.path, "scenes/dem.png");
  EXPECT_EQ(image.terrain.metres_per_pixel, 30.0);
  EXPECT_EQ(image.terrain.path_where.line, 3);
}

TEST(SceneTerrain, BadValuesAreRefusedAtTheirPosition) {
  expect_scene_error("[terrain]\nrelief = 1e30\n", 2, 10, "out of range [0, 10000] metres");
  expect_scene_error("[terrain]\nrelief = nan\n", 2, 10, "relief");
  expect_scene_error("[terrain]\nkind = \"volcano\"\n", 2, 8,
                     "one of \"hills\", \"mountains\", \"image\"");
  expect_scene_error(
      "[terrain]\nkind = \"image\"\nsize = 100\npath = \"d.png\"\n", 3, 8,
      "terrain.size belongs to terrain.kind = \"hills\" or \"mountains\", not \"image\"");
  expect_scene_error("[terrain]\npath = \"d.png\"\n", 2, 8,
                     "terrain.path belongs to terrain.kind = \"image\", not \"hills\"");
  expect_scene_error("[terrain]\nkind = \"image\"\n", 1, 1, "needs terrain.path");
  expect_scene_error("[terrain]\nsize = 40000\nresolution = 0.5\n", 3, 14,
                     "at most 32766 samples across (80000 asked)");
  expect_scene_error("[terrain]\ncliffs = true\n", 2, 1, "unknown key 'cliffs' in [terrain]");
  expect_scene_error("[camera]\nabove_ground = 1.7\n", 2, 16,
                     "camera.above_ground needs a [terrain]");
  expect_scene_error("[terrain]\nresolution = 4\n[meadow]\ndensity = 100\ntile = 2\n", 5, 8,
                     "meadow.tile is the terrain's cell on a [terrain] (4 m); leave it out");
  expect_scene_error("[terrain]\n[camera]\nabove_ground = -1\n", 3, 16, "out of range [0, 100000]");
  // An image has no model to continue beyond its square.
  expect_scene_error(
      "[terrain]\nkind = \"image\"\nsurround = 2\npath = \"d.png\"\n", 3, 12,
      "terrain.surround belongs to terrain.kind = \"hills\" or \"mountains\", not \"image\"");
  expect_scene_error("[terrain]\nsurround = 50\n", 2, 12, "out of range [0, 20]");
}

TEST(SceneCommunity, IsReadWithItsSpecies) {
  const spec::SceneDesc s = parse_scene(
      "[community]\narea = [[-10, -20], [30, 40]]\nyears = 60\nseed = 3\n"
      "[[community.species]]\nspecies = \"aspen.toml\"\nradius = 5\nshade_tolerance = 0.5\n"
      "altitude_max = 120\n[[community.species]]\nspecies = \"fir.toml\"\nsown = 0.01\n",
      "scenes/s.toml");
  ASSERT_TRUE(s.community.enabled);
  EXPECT_EQ(s.community.area[1], -20.0);
  EXPECT_EQ(s.community.years, 60.0);
  EXPECT_EQ(s.community.seed, 3u);
  ASSERT_EQ(s.community.species.size(), 2u);
  EXPECT_EQ(s.community.species[0].species, "scenes/aspen.toml");
  EXPECT_EQ(s.community.species[0].radius, 5.0);
  EXPECT_EQ(s.community.species[0].shade_tolerance, 0.5);
  EXPECT_EQ(s.community.species[0].altitude_max, 120.0);
  EXPECT_EQ(s.community.species[0].where.line, 5);
  EXPECT_EQ(s.community.species[1].sown, 0.01);
  EXPECT_EQ(s.community.species[1].radius, 4.0);  // the default
}

TEST(SceneCommunity, BadTablesAreRefusedAtTheirPlace) {
  expect_scene_error("[community]\nyears = 10\n", 1, 1,
                     "[community] needs [[community.species]] (at least one)");
  expect_scene_error("[community]\n[[community.species]]\nradius = 3\n", 2, 1,
                     "needs a species file");
  expect_scene_error(
      "[community]\n[[community.species]]\nspecies = \"a.toml\"\naltitude_min = 50\n"
      "altitude_max = 10\n",
      2, 1, "altitude_min 50 exceeds altitude_max 10");
  expect_scene_error("[community]\n[[community.species]]\nspecies = \"a.toml\"\nbogus = 1\n", 4, 1,
                     "unknown key 'bogus' in [[community.species]]");
  expect_scene_error(
      "[community]\n[[community.species]]\nspecies = \"a.toml\"\nshade_tolerance = 1\n", 4, 19,
      "out of range [0, 0.999]");
  expect_scene_error("[community]\nyears = 1e30\n[[community.species]]\nspecies = \"a.toml\"\n", 2,
                     9, "out of range [1, 2000]");
}

TEST(SceneRocks, AreReadAndBadValuesRefusedAtTheirPlace) {
  const spec::SceneDesc s = parse_scene(
      "[terrain]\n[rocks]\ndensity = 0.1\nsize_min = 0.5\nsize_max = 4\nexponent = 3\n"
      "buried = 0.2\nvariants = 4\nseed = 9\n",
      "s.toml");
  ASSERT_TRUE(s.rocks.enabled);
  EXPECT_EQ(s.rocks.density, 0.1);
  EXPECT_EQ(s.rocks.size_max, 4.0);
  EXPECT_EQ(s.rocks.exponent, 3.0);
  EXPECT_EQ(s.rocks.variants, 4);
  EXPECT_FALSE(s.rocks.area.has_value());
  const spec::SceneDesc flat = parse_scene("[rocks]\narea = [[-5, -5], [5, 5]]\n", "s.toml");
  ASSERT_TRUE(flat.rocks.area.has_value());
  EXPECT_EQ((*flat.rocks.area)[2], 5.0);
  expect_scene_error("[rocks]\ndensity = 1\n", 1, 1,
                     "[rocks] needs an area ([[x0, y0], [x1, y1]]) without a [terrain]");
  expect_scene_error("[terrain]\n[rocks]\nsize_min = 5\nsize_max = 2\n", 2, 1,
                     "rocks.size_min 5 exceeds rocks.size_max 2");
  expect_scene_error("[terrain]\n[rocks]\nexponent = 1\n", 3, 12, "out of range [1.01, 6]");
  expect_scene_error("[terrain]\n[rocks]\ndensity = nan\n", 3, 11, "density");
  expect_scene_error("[terrain]\n[rocks]\nboulders = 3\n", 3, 1,
                     "unknown key 'boulders' in [rocks]");
}

}  // namespace arbor::formats
