// Frames of an [animation] (issue 16): the clock, the seed, the outputs' frame numbers, and which
// trees move — Weber & Penn trees sway with the clock, fractal trees grow only when the scene
// gives years_per_second.
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "common/rng.h"
#include "expect_input_error.h"
#include "formats/scene_file.h"
#include "scene/frame.h"
#include "tracer/test_world.h"

namespace arbor::tracer {
namespace {

spec::SceneDesc animated(const std::string& species, const std::string& animation) {
  return formats::parse_scene(
      "[render]\nseed = 9\n[[tree]]\nspecies = \"" + std::string(ARBOR_SOURCE_DIR) + "/species/" +
          species + "\"\n[output]\nexr = \"out/f.####.exr\"\npng = \"out/f.##.png\"\n" + animation,
      "/tmp/scene.toml");
}

std::size_t segments(const spec::SceneDesc& s) {
  return scene::build_scene(s, kOcioConfig)->stats.curve_segments;
}

}  // namespace

TEST(Frames, FrameSetsClockSeedAndOutputNames) {
  spec::SceneDesc s = animated("quaking_aspen.toml", "[animation]\nframes = 10\nfps = 4.0\n");
  scene::apply_frame(s, 6);
  EXPECT_DOUBLE_EQ(s.clock, 1.5);
  EXPECT_EQ(s.render.seed, derive_key(9, 6));
  EXPECT_EQ(s.output.exr, "/tmp/out/f.0006.exr");
  EXPECT_EQ(s.output.png, "/tmp/out/f.06.png");
  EXPECT_EQ(spec::frame_path("a.#.exr", 123), "a.123.exr");
  EXPECT_EQ(spec::frame_path("plain.exr", 3), "plain.exr");

  spec::SceneDesc pinned =
      animated("quaking_aspen.toml", "[animation]\nframes = 10\npin_seed = true\n");
  scene::apply_frame(pinned, 6);
  EXPECT_EQ(pinned.render.seed, 9u);
  EXPECT_DOUBLE_EQ(pinned.clock, 0.25);  // fps 24 by default

  spec::SceneDesc no_frame = animated("quaking_aspen.toml", "[animation]\nframes = 10\n");
  EXPECT_THROW(scene::apply_frame(no_frame, std::nullopt), InputError);  // #### but no --frame
  spec::SceneDesc outside = animated("quaking_aspen.toml", "[animation]\nframes = 10\n");
  EXPECT_THROW(scene::apply_frame(outside, 10), InputError);
}

TEST(Frames, AnimationTableIsChecked) {
  using arbor::testing::expect_input_error;
  expect_input_error([] { animated("quaking_aspen.toml", "[animation]\nfps = 24.0\n"); },
                     "/tmp/scene.toml", 8, 1, "[animation] needs frames");
  expect_input_error([] { animated("quaking_aspen.toml", "[animation]\nframes = 4\nspeed = 2\n"); },
                     "/tmp/scene.toml", 10, 1, "unknown key 'speed' in [animation]");
  expect_input_error([] { animated("quaking_aspen.toml", "[animation]\nframes = 0\n"); },
                     "/tmp/scene.toml", 9, 10, "animation.frames = 0 is out of range");
}

TEST(Frames, WindSwaysWithTheClockAndGrowthOnlyWhenAsked) {
  // Weber & Penn: the sway moves the limbs, the tree keeps its structure.
  spec::SceneDesc still = animated("quaking_aspen.toml", "[animation]\nframes = 48\n");
  spec::SceneDesc later = still;
  later.clock = 1.0;
  const auto a = scene::build_scene(still, kOcioConfig), b = scene::build_scene(later, kOcioConfig);
  const generator::TreeGeometry &ga = *a->prototypes.at(0).geometry,
                                &gb = *b->prototypes.at(0).geometry;
  // The same limbs (how finely a bent limb is cut into curve segments may change as it bends).
  EXPECT_EQ(ga.stats.limbs, gb.stats.limbs);
  EXPECT_EQ(ga.grids.vertices.size(), gb.grids.vertices.size());
  const generator::CurveSet &ca = ga.curves, &cb = gb.curves;
  bool moved = false;
  for (std::size_t i = 0; i < std::min(ca.points.size(), cb.points.size()) && !moved; ++i)
    moved = ca.points[i] != cb.points[i];
  EXPECT_TRUE(moved);

  // The fractal model: its time is an age; without years_per_second it stands still.
  spec::SceneDesc young = animated("fractal_broadleaf.toml", "[animation]\nframes = 48\n");
  young.trees.at(0).time = 3.0;
  spec::SceneDesc same = young;
  same.clock = 2.0;
  EXPECT_EQ(segments(young), segments(same));
  spec::SceneDesc growing = young;
  growing.animation.years_per_second = 2.0;
  growing.clock = 2.0;  // 3 + 4 years old
  EXPECT_GT(segments(growing), segments(young));
}

}  // namespace arbor::tracer
