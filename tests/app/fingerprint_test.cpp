// The render fingerprint (app/commands/fingerprint.h): every [render] key changes it by the
// smallest step its value takes (full precision, not six decimals), so do --time, --frame, the
// outputs that change the sums and the bytes of every input; the threads and the spelling of a
// path do not.
#include "app/commands/fingerprint.h"

#include <cmath>
#include <fstream>
#include <string>
#include <type_traits>
#include <variant>

#include <gtest/gtest.h>

#include "formats/scene_file.h"
#include "formats/scene_keys.h"
#include "temp_files.h"

namespace arbor::app {
namespace {

struct Files {
  std::string dir, scene, ocio;
};

Files files(const std::string& name) {
  Files f;
  f.dir = testing::fresh_folder(name);
  f.scene = f.dir + "/s.toml";
  f.ocio = f.dir + "/config.ocio";
  std::ofstream(f.scene) << "[render]\nwidth = 64\n";
  std::ofstream(f.ocio) << "ocio_profile_version: 2\n";
  return f;
}

std::string fingerprint(const spec::SceneDesc& s, const Files& f,
                        std::optional<double> time = std::nullopt,
                        std::optional<int> frame = std::nullopt) {
  std::string settings;
  return render_fingerprint(s, time, frame, f.ocio, settings);
}

// The next value of a field: a flag flipped, a whole number one more, a number one ulp more.
template <class T>
void step(T& v) {
  if constexpr (std::is_same_v<T, bool>)
    v = !v;
  else if constexpr (std::is_integral_v<T>)
    v = v + 1;
  else if constexpr (std::is_same_v<T, double>)
    v = std::nextafter(v, 2.0 * v + 1.0);
}

TEST(Fingerprint, EveryRenderKeyChangesItByItsSmallestStep) {
  const Files f = files("fingerprint_keys");
  const spec::SceneDesc base = formats::load_scene(f.scene);
  const std::string before = fingerprint(base, f);
  EXPECT_EQ(fingerprint(base, f), before);
  int keys = 0;
  for (const formats::Key<spec::RenderSettings>& k : formats::render_keys()) {
    spec::SceneDesc s = base;
    bool stepped = false;
    std::visit(
        [&](auto field) {
          using F = decltype(field);
          if constexpr (!std::is_same_v<F, std::monostate>) {
            using T = typename formats::keys::member<F>::type;
            if constexpr (std::is_arithmetic_v<T>) {
              step(s.render.*field);
              stepped = true;
            }
          }
        },
        k.field);
    if (k.name == "integrator") {
      s.render.integrator = spec::Integrator::Treemaker;
      stepped = true;
    }
    ASSERT_TRUE(stepped) << "render." << k.name << ": give the test a step for it";
    EXPECT_NE(fingerprint(s, f), before) << "render." << k.name;
    ++keys;
  }
  EXPECT_EQ(keys, static_cast<int>(formats::render_keys().size()));
  spec::SceneDesc threads = base;
  threads.render.threads = 7;
  EXPECT_EQ(fingerprint(threads, f), before);  // changes no pixel
}

TEST(Fingerprint, TimeFrameOutputsAndInputsChangeItPathsSpeltOtherwiseDoNot) {
  const Files f = files("fingerprint_inputs");
  const spec::SceneDesc s = formats::load_scene(f.scene);
  const std::string before = fingerprint(s, f);
  // --time apart after its seventh significant digit (std::to_string kept six decimals).
  EXPECT_NE(fingerprint(s, f, 1.0), fingerprint(s, f, std::nextafter(1.0, 2.0)));
  EXPECT_NE(fingerprint(s, f, 0.0), before);  // --time 0 is not no --time
  EXPECT_NE(fingerprint(s, f, std::nullopt, 3), fingerprint(s, f, std::nullopt, 4));
  spec::SceneDesc transparent = s;
  transparent.output.transparent_sky = true;
  EXPECT_NE(fingerprint(transparent, f), before);
  spec::SceneDesc ids = s;
  ids.output.aovs.add(imaging::Aov::ObjectId);
  EXPECT_NE(fingerprint(ids, f), before);
  // The same scene by another spelling of its path.
  EXPECT_EQ(fingerprint(formats::load_scene(f.dir + "/./s.toml"), f), before);
  // The same bytes in another folder are the same render; one byte more in the OCIO config, or
  // in the scene (a comment: the same settings), is another. (An input is read once a run:
  // each case has its own files.)
  const Files same = files("fingerprint_same");
  EXPECT_EQ(fingerprint(formats::load_scene(same.scene), same), before);
  const Files config = files("fingerprint_config");
  std::ofstream(config.ocio, std::ios::app) << " ";
  EXPECT_NE(fingerprint(formats::load_scene(config.scene), config), before);
  const Files scene = files("fingerprint_scene");
  std::ofstream(scene.scene, std::ios::app) << "#\n";
  EXPECT_NE(fingerprint(formats::load_scene(scene.scene), scene), before);
}

}  // namespace
}  // namespace arbor::app
