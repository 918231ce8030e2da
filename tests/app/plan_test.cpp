// `arbor plan` (issue 16): its commands, run in any order, merge into the image one render gives,
// bit for bit; frames of an animation differ as the clock and seed say; a missing or stopped
// unit is named by merge.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "app/cli.h"

namespace {

std::string plan_scene(const char* name, const std::string& extra = "") {
  return write_temp(
      name,
      "[render]\nwidth = 40\nheight = 30\nspp = 16\npass_spp = 4\n"
      "[camera]\nposition = [0.0, -14.0, 3.0]\nlook_at = [0.0, 0.0, 4.0]\nfov = 50.0\n"
      "[[tree]]\nspecies = \"" +
          species("quaking_aspen.toml") +
          "\"\n"
          "[ground]\nenabled = true\n" +
          extra);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::vector<float> pixels(const std::string& path, int* channels = nullptr) {
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> px(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
  if (channels) *channels = spec.nchannels;
  return px;
}

int run_line(const std::string& line) {
  const int status = std::system((line + " 2>/dev/null").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

// Runs the plan of `split` (plan's options; empty: its defaults, one unit) in a shuffled order
// from another folder, then its merge; the merged pixels must be the single render's.
void expect_plan_merges_bit_exact(const std::string& scene, const std::string& split,
                                  std::size_t units, const std::string& dir) {
  SCOPED_TRACE("plan " + (split.empty() ? std::string("(defaults)") : split));
  std::system(("rm -rf " + dir).c_str());
  const CliRun plan = run_arbor("plan " + scene + " " + split + " --seed 5 -o " + dir + "out.exr");
  ASSERT_EQ(plan.code, 0) << plan.err;
  std::vector<std::string> commands = lines(plan.out);
  ASSERT_EQ(commands.size(), units + 1);  // the units, then the merge
  const std::string merge = commands.back();
  commands.pop_back();
  for (const std::string& c : commands) {
    EXPECT_EQ(c.rfind(std::string(ARBOR_BINARY) + " render " + scene + " --seed 5 --crop ", 0), 0u)
        << c;
  }
  EXPECT_EQ(merge.rfind(std::string(ARBOR_BINARY) + " merge -o " + dir + "out.exr ", 0), 0u)
      << merge;
  std::mt19937 rng(7);
  std::shuffle(commands.begin(), commands.end(), rng);
  for (const std::string& c : commands) ASSERT_EQ(run_line("cd / && " + c), 0) << c;
  ASSERT_EQ(run_line(merge), 0) << merge;
  ASSERT_EQ(run_arbor("render " + scene + " --seed 5 -o " + dir + "single.exr").code, 0);
  int channels = 0;
  const std::vector<float> merged = pixels(dir + "out.exr", &channels),
                           single = pixels(dir + "single.exr");
  ASSERT_EQ(merged.size(), 40u * 30u * static_cast<unsigned>(channels));
  ASSERT_EQ(merged.size(), single.size());
  EXPECT_EQ(std::memcmp(merged.data(), single.data(), merged.size() * sizeof(float)), 0);
  // The merge is the whole render: nothing left to resume or merge.
  EXPECT_NE(std::system(("test -e " + dir + "out.exr.state").c_str()), 0);
}

// Every shape of split, none included: a plan of one unit (the defaults, as docs/farm.md
// recommends for animations) is a finished render that must still merge.
TEST(Plan, UnitsInAnyOrderMergeIntoTheSingleRenderBitForBit) {
  const std::string dir = ::testing::TempDir() + "plan_still/";
  const std::string scene = plan_scene("plan_still.toml");
  expect_plan_merges_bit_exact(scene, "", 1, dir + "none/");
  expect_plan_merges_bit_exact(scene, "--tiles 1x1 --pass-groups 1", 1, dir + "one/");
  expect_plan_merges_bit_exact(scene, "--tiles 2x1", 2, dir + "tiles/");
  expect_plan_merges_bit_exact(scene, "--pass-groups 3", 3, dir + "passes/");
  expect_plan_merges_bit_exact(scene, "--tiles 2x2 --pass-groups 2", 8, dir + "both/");

  // The same plan as JSON: every unit with its tile, window, passes, output and argv.
  const CliRun json = run_arbor("plan " + scene + " --tiles 2x2 --pass-groups 2 --seed 5 -o " +
                                dir + "both/out.exr --json");
  ASSERT_EQ(json.code, 0) << json.err;
  EXPECT_NE(json.out.find("\"units\": ["), std::string::npos);
  EXPECT_NE(json.out.find("\"crop\": [20, 15, 40, 30], \"passes\": [2, 4]"), std::string::npos)
      << json.out;
  const std::string merge =
      lines(run_arbor("plan " + scene + " --tiles 2x2 --pass-groups 2 --seed 5 -o " + dir +
                      "both/out.exr")
                .out)
          .back();
  EXPECT_NE(json.out.find("\"shell\": " + std::string("\"") + merge + "\""), std::string::npos);
}

TEST(Plan, MergeNamesEveryMissingAndStoppedUnit) {
  const std::string dir = ::testing::TempDir() + "plan_faults/";
  std::system(("rm -rf " + dir).c_str());
  const std::string scene = plan_scene("plan_faults.toml");
  const CliRun plan =
      run_arbor("plan " + scene + " --tiles 3x1 --pass-groups 1 -o " + dir + "out.exr");
  ASSERT_EQ(plan.code, 0) << plan.err;
  const std::vector<std::string> commands = lines(plan.out);
  ASSERT_EQ(commands.size(), 4u);
  // Unit 0 finishes; unit 1 is stopped after its first pass (a time limit stands for a kill);
  // unit 2 never runs.
  ASSERT_EQ(run_line(commands[0]), 0);
  ASSERT_EQ(run_line(commands[1] + " --time-limit 0.000001"), 0);
  const std::string part1 = dir + "out.parts/tile-1-0.passes-0-4.exr",
                    part2 = dir + "out.parts/tile-2-0.passes-0-4.exr";
  const CliRun merge = run_arbor(commands[3].substr(commands[3].find(" merge ") + 1));
  EXPECT_EQ(merge.code, 2);
  EXPECT_NE(merge.err.find("2 of the 3 parts cannot be merged"), std::string::npos) << merge.err;
  EXPECT_NE(merge.err.find("missing: " + part2), std::string::npos) << merge.err;
  EXPECT_NE(merge.err.find("incomplete: " + part1 + " (holds pass 0 of its passes 0 to 3)"),
            std::string::npos)
      << merge.err;
  EXPECT_FALSE(exists(dir + "out.exr"));
  // Re-running only those two completes the job.
  ASSERT_EQ(run_line(commands[1]), 0);
  ASSERT_EQ(run_line(commands[2]), 0);
  EXPECT_EQ(run_line(commands[3]), 0);
  EXPECT_TRUE(exists(dir + "out.exr"));
}

TEST(Plan, FramesRenderTheAnimationsClockAndMergeOnePerFrame) {
  const std::string dir = ::testing::TempDir() + "plan_frames/";
  std::system(("rm -rf " + dir).c_str());
  // One seed for every frame: what differs between frames is the clock (the aspen's sway).
  const std::string scene =
      plan_scene("plan_frames.toml", "[animation]\nframes = 4\nfps = 2.0\npin_seed = true\n");
  const CliRun plan =
      run_arbor("plan " + scene + " --tiles 1x2 --frames 1:3 --spp 4 -o " + dir + "f.####.exr");
  ASSERT_EQ(plan.code, 0) << plan.err;
  const std::vector<std::string> commands = lines(plan.out);
  ASSERT_EQ(commands.size(), 6u);  // 2 frames × 2 tiles, then 2 merges
  EXPECT_NE(commands[0].find(" --frame 1 "), std::string::npos) << commands[0];
  EXPECT_NE(commands[2].find(" --frame 2 "), std::string::npos) << commands[2];
  EXPECT_NE(commands[4].find("merge -o " + dir + "f.0001.exr"), std::string::npos) << commands[4];
  EXPECT_NE(commands[5].find("merge -o " + dir + "f.0002.exr"), std::string::npos) << commands[5];
  for (const std::string& c : commands) ASSERT_EQ(run_line(c), 0) << c;
  // Frame 2 merged = frame 2 rendered alone; frame 1 differs (another clock).
  ASSERT_EQ(run_arbor("render " + scene + " --frame 2 --spp 4 -o " + dir + "alone.####.exr").code,
            0);
  const std::vector<float> f1 = pixels(dir + "f.0001.exr"), f2 = pixels(dir + "f.0002.exr"),
                           alone = pixels(dir + "alone.0002.exr");
  ASSERT_EQ(f2.size(), alone.size());
  EXPECT_EQ(std::memcmp(f2.data(), alone.data(), f2.size() * sizeof(float)), 0);
  EXPECT_NE(f1, f2);

  // Bad requests: no [animation], frames outside it, no '#' in the output, too many tiles.
  const std::string still = plan_scene("plan_frames_still.toml");
  EXPECT_EQ(run_arbor("plan " + still + " --frames 0:2 -o " + dir + "g.####.exr").code, 2);
  EXPECT_EQ(run_arbor("plan " + scene + " --frames 0:5 -o " + dir + "g.####.exr").code, 2);
  EXPECT_EQ(run_arbor("plan " + scene + " --frames 0:2 -o " + dir + "g.exr").code, 2);
  const CliRun hashes = run_arbor("plan " + scene + " -o " + dir + "g.####.exr");
  EXPECT_EQ(hashes.code, 2);
  EXPECT_NE(hashes.err.find("give --frames A:B"), std::string::npos) << hashes.err;
  EXPECT_EQ(run_arbor("plan " + scene + " --tiles 41x1 -o " + dir + "g.exr").code, 2);
  EXPECT_EQ(run_arbor("plan " + scene + " --pass-groups 5 -o " + dir + "g.exr").code, 2);
  EXPECT_EQ(run_arbor("plan " + scene + " --tiles 2 -o " + dir + "g.exr").code, 2);
  const CliRun no_frame = run_arbor("render " + scene + " -o " + dir + "h.####.exr");
  EXPECT_EQ(no_frame.code, 2);
  EXPECT_NE(no_frame.err.find("give --frame N"), std::string::npos) << no_frame.err;
  const CliRun outside = run_arbor("render " + scene + " --frame 4 -o " + dir + "h.exr");
  EXPECT_EQ(outside.code, 2);
  EXPECT_NE(outside.err.find("outside the animation's frames 0 to 3"), std::string::npos)
      << outside.err;
}
