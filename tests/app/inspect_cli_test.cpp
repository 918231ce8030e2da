// End-to-end tests of `arbor inspect`: what it reports is what the scene builds (every instance,
// the terrain under it, the counts), it writes nothing, and bad scenes are refused; a landscape
// renders bit for bit at any thread count.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/cli.h"

namespace {

// The steepest terrain arbor ships (ridged mountains at 60 m relief over 200 m), a tree, a forest
// and a community on it.
std::string landscape_scene() {
  const std::string sp = std::string(ARBOR_SOURCE_DIR) + "/species/";
  return "[terrain]\nkind = \"mountains\"\nsize = 200\nrelief = 60\nresolution = 2\nseed = 3\n"
         "[[tree]]\nspecies = \"" +
         sp +
         "black_spruce.toml\"\nposition = [10, 20, 0]\n"
         "[[forest]]\nspecies = \"" +
         sp +
         "black_spruce.toml\"\ncount = 40\nvariants = 2\n"
         "area = [[-90, -90], [90, 90]]\n"
         "[community]\narea = [[-80, -80], [80, 80]]\nyears = 40\n"
         "[[community.species]]\nspecies = \"" +
         sp +
         "black_spruce.toml\"\nvariants = 3\n"
         "radius = 1.5\nmaturity = 15\nseedlings = 1e-3\nseeds = 1\ndispersal = 4\n"
         "slope_max = 60\n";
}

struct Instance {
  std::string species;
  double z = 0.0, ground = 0.0, age = -1.0;
};

std::vector<Instance> instances_of(const std::string& json) {
  std::vector<Instance> out;
  const std::regex one(
      "\\{\"species\": \"([^\"]+)\", \"prototype\": [0-9]+(, \"variant\": [0-9]+)?"
      "(, \"age\": ([-0-9.e]+))?, \"position\": \\[[-0-9.e]+, [-0-9.e]+, ([-0-9.e]+)\\], "
      "\"rotation\": [-0-9.e]+, \"scale\": [-0-9.e]+, \"ground\": ([-0-9.e]+)");
  for (auto it = std::sregex_iterator(json.begin(), json.end(), one); it != std::sregex_iterator();
       ++it) {
    Instance i;
    i.species = (*it)[1];
    if ((*it)[4].matched) i.age = std::stod((*it)[4]);
    i.z = std::stod((*it)[5]);
    i.ground = std::stod((*it)[6]);
    out.push_back(i);
  }
  return out;
}

long long json_count(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": \\{\"instances\": ([0-9]+)")))
    return -1;
  return std::stoll(m[1]);
}

}  // namespace

// Every instance the scene builds is listed with the terrain's height under it, on which its base
// stands (within 1 cm); the counts per species are the instances listed; the community's plants
// carry their age.
TEST(Inspect, ListsEveryInstanceStandingOnTheTerrain) {
  const std::string scene = write_temp("inspect_landscape.toml", landscape_scene());
  const CliRun r = run_arbor("inspect " + scene + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<Instance> all = instances_of(r.out);
  ASSERT_GT(all.size(), 60u) << r.out.substr(0, 2000);
  EXPECT_EQ(json_count(r.out, "black_spruce"), static_cast<long long>(all.size()));
  EXPECT_NE(r.out.find("\"rocks\": {\"rocks\": 0, \"shapes\": 0}"), std::string::npos);
  std::size_t aged = 0, on_slopes = 0;
  for (const Instance& i : all) {
    EXPECT_NEAR(i.z, i.ground, 0.01);
    if (i.age >= 0.0) ++aged;
    if (std::abs(i.ground) > 1.0) ++on_slopes;
  }
  EXPECT_EQ(aged, all.size() - 41);      // the tree and the forest have no age
  EXPECT_GT(on_slopes, all.size() / 2);  // the terrain is not flat where they stand
  // The text report's table lists the same instances.
  const CliRun text = run_arbor("inspect " + scene + " --instances");
  ASSERT_EQ(text.code, 0) << text.err;
  std::size_t lines = 0;
  for (std::size_t p = text.out.find("\nblack_spruce\t"); p != std::string::npos;
       p = text.out.find("\nblack_spruce\t", p + 1))
    ++lines;
  EXPECT_EQ(lines, all.size());
  EXPECT_NE(text.out.find("mountains, 200 × 200 m at 2 m"), std::string::npos) << text.out;
}

TEST(Inspect, RefusesABadSceneAtItsPlace) {
  const std::string scene = write_temp("inspect_bad.toml", "[community]\nyears = 10\n");
  const CliRun r = run_arbor("inspect " + scene);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("inspect_bad.toml:1:1: error: [community] needs [[community.species]]"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// A whole landscape — terrain, a community grown from seed, rocks, a meadow on the slope, the
// camera standing on the ground — builds and renders the same image bit for bit at one and two
// threads (growth, the simulation's placement, the rocks and the render all run in parallel).
TEST(Landscape, RendersBitForBitAtOneAndTwoThreads) {
  const std::string dir = ::testing::TempDir();
  const std::string scene =
      write_temp("landscape_threads.toml",
                 landscape_scene() +
                     "[rocks]\ndensity = 0.02\nsize_min = 0.3\nsize_max = 2\n"
                     "[meadow]\ndensity = 300\narea = [[-75, -80], [-55, -60]]\nheight = 0.3\n"
                     "[render]\nwidth = 48\nheight = 32\nspp = 4\n"
                     "[camera]\nposition = [-70, -75, 0]\nabove_ground = 6\nlook_at = [0, 0, 10]\n"
                     "[output]\naovs = [\"depth\"]\npixel_type = \"float\"\n");
  const CliRun one = run_arbor("render " + scene + " --threads 1 -o " + dir + "land1.exr");
  ASSERT_EQ(one.code, 0) << one.err;
  ASSERT_EQ(run_arbor("render " + scene + " --threads 2 -o " + dir + "land2.exr").code, 0);
  OIIO::ImageBuf a(dir + "land1.exr"), b(dir + "land2.exr");
  ASSERT_TRUE(a.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  ASSERT_TRUE(b.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  ASSERT_EQ(a.nchannels(), 5);  // RGBA, Z
  std::vector<float> pa(48 * 32 * 5), pb(pa.size());
  a.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pa.data());
  b.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pb.data());
  EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)), 0);
  // What it builds, listed, is the same too; and it has all its parts.
  const CliRun i1 = run_arbor("inspect " + scene + " --json --instances");
  ASSERT_EQ(i1.code, 0) << i1.err;
  std::smatch rocks, blades;
  ASSERT_TRUE(std::regex_search(i1.out, rocks, std::regex("\"rocks\": \\{\"rocks\": ([0-9]+)")));
  EXPECT_GT(std::stoll(rocks[1]), 50);
  ASSERT_TRUE(std::regex_search(i1.out, blades, std::regex("\"blades\": ([0-9]+)")));
  EXPECT_GT(std::stoll(blades[1]), 10000);
  // The depth channel sees the near ground (the camera stands 6 m over it) and the far slopes.
  float nearest = 1e30f, farthest = 0.0f;
  for (std::size_t p = 4; p < pa.size(); p += 5) {
    nearest = std::min(nearest, pa[p]);
    if (std::isfinite(pa[p])) farthest = std::max(farthest, pa[p]);
  }
  EXPECT_LT(nearest, 15.0f);
  EXPECT_GT(farthest, 30.0f);
}
