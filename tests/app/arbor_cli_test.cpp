// End-to-end tests of the arbor command line: exit codes, diagnostics, outputs of render,
// compare and export, --help and --version (grow's are in grow_cli_test.cpp).
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include <cstring>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <filesystem>
#include <unistd.h>
#include <gtest/gtest.h>

#include "app/cli.h"

// The options a command's --help lists: the long name of every option line.
static std::set<std::string> listed_options(const std::string& help) {
  std::set<std::string> options;
  static const std::regex line(R"(^\s+(?:-\w,)?(--[a-z-]+))");
  std::istringstream in(help);
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_search(l, m, line)) options.insert(m[1]);
  }
  return options;
}

// --version names the version and the build's commit; every command's --help lists exactly the
// options of the command-line contract (docs/architecture.md), no more and no fewer.
TEST(ArborCli, VersionAndHelp) {
  const CliRun v = run_arbor("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_TRUE(
      std::regex_match(v.out, std::regex(R"(arbor \d+\.\d+\.\d+ \(commit [0-9a-z.-]+\)\n)")))
      << v.out;
  // The build's commit, as git describes it (issue 15), when built from a git checkout.
  if (exists(std::string(ARBOR_SOURCE_DIR) + "/.git")) {
    EXPECT_EQ(v.out.find("(commit unknown)"), std::string::npos) << v.out;
  }
  const std::map<std::string, std::set<std::string>> contract = {
      {"grow",
       {"--help", "--seed", "--time", "--quality", "--output", "--up", "--stats", "--json",
        "--force"}},
      {"render", {"--help",        "--output",     "--png",
                  "--width",       "--height",     "--spp",
                  "--seed",        "--integrator", "--time",
                  "--transparent", "--regularize", "--lod",
                  "--threads",     "--frame",      "--force",
                  "--resume",      "--time-limit", "--checkpoint-seconds",
                  "--passes",      "--crop"}},
      {"compare",
       {"--help", "--heatmap", "--side-by-side", "--display", "--view", "--json",
        "--reference-test", "--fit-treemaker"}},
      {"merge", {"--help", "--output", "--png", "--partial"}},
      {"plan",
       {"--help", "--output", "--png", "--tiles", "--pass-groups", "--frames", "--json", "--width",
        "--height", "--spp", "--seed", "--integrator", "--time", "--transparent", "--regularize",
        "--lod"}},
      {"export",
       {"--help", "--output", "--width", "--height", "--spp", "--time", "--frame",
        "--sky-resolution"}},
  };
  const CliRun top = run_arbor("--help");
  EXPECT_EQ(top.code, 0);
  for (const auto& [command, options] : contract) {
    EXPECT_NE(top.out.find("  " + command + " "), std::string::npos)
        << command << " in " << top.out;
    const CliRun h = run_arbor(command + " --help");
    EXPECT_EQ(h.code, 0) << command;
    EXPECT_EQ(listed_options(h.out), options) << command << " --help:\n" << h.out;
  }
  const CliRun r = run_arbor("render --help");
  EXPECT_NE(r.out.find("treemaker (TREE-MAKER's approximate shading)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("render.treemaker_spp"), std::string::npos) << r.out;
}

TEST(ArborCli, CompareMetricsJsonAndImages) {
  const std::string a = write_exr("cmp_a.exr", 40, 30, 0.6f, 1e-4f);
  const std::string b = write_exr("cmp_b.exr", 40, 30, 0.5f, 1e-4f);
  const std::string heat = ::testing::TempDir() + "cmp_heat.png";
  const std::string side = ::testing::TempDir() + "cmp_side.png";
  std::remove(heat.c_str());
  std::remove(side.c_str());
  const CliRun r =
      run_arbor("compare " + a + " " + b + " --json --heatmap " + heat + " --side-by-side " + side);
  EXPECT_EQ(r.code, 0) << r.err;
  auto value = [&](const std::string& key) {
    const auto at = r.out.find("\"" + key + "\": ");
    EXPECT_NE(at, std::string::npos) << key << " in " << r.out;
    return at == std::string::npos ? -1.0
                                   : std::strtod(r.out.c_str() + at + key.size() + 4, nullptr);
  };
  EXPECT_NEAR(value("rmse"), 0.1, 1e-6);
  EXPECT_NEAR(value("mean_abs"), 0.1, 1e-6);
  EXPECT_NEAR(value("max_abs"), 0.1, 1e-6);
  EXPECT_NEAR(value("rel_mse"), 0.01 / 0.26, 1e-6);
  EXPECT_NEAR(value("psnr"), 20.0, 1e-4);
  OIIO::ImageBuf h(heat), s(side);
  ASSERT_TRUE(h.read()) << h.geterror();
  EXPECT_EQ(h.spec().width, 40);
  EXPECT_GT(h.spec().height, 30);  // the scale bar below
  ASSERT_TRUE(s.read()) << s.geterror();
  EXPECT_GT(s.spec().width, 3 * 40);

  // An unknown view is refused before either picture is written.
  std::remove(heat.c_str());
  std::remove(side.c_str());
  const CliRun bad = run_arbor("compare " + a + " " + b + " --heatmap " + heat +
                               " --side-by-side " + side + " --view 'No Such View'");
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_NE(bad.err.find("No Such View"), std::string::npos) << bad.err;
  // It says what the config offers.
  EXPECT_NE(bad.err.find("--view \"No Such View\" is not a view of display \"sRGB\""),
            std::string::npos)
      << bad.err;
  EXPECT_NE(bad.err.find("it has \"ACES 1.0 SDR-video\", \"Un-tone-mapped\", \"Raw\""),
            std::string::npos)
      << bad.err;
  EXPECT_FALSE(exists(heat));
  EXPECT_FALSE(exists(side));

  // Identical images: PSNR has no finite value and JSON spells it null.
  const CliRun same = run_arbor("compare " + b + " " + b + " --json");
  EXPECT_EQ(same.code, 0);
  EXPECT_NE(same.out.find("\"psnr\": null"), std::string::npos) << same.out;
}

TEST(ArborCli, CompareReferenceTestExitCodes) {
  const std::string ref = write_exr("rt_ref.exr", 16, 16, 0.5f, 1e-4f);
  // 0.014 sigma a pixel, 0.23 sigma in the image mean: passes.
  const std::string close = write_exr("rt_close.exr", 16, 16, 0.5002f, 1e-4f);
  // 0.35 sigma a pixel, every pixel passes; but 5.7 sigma in the image mean: fails, pooled.
  const std::string shifted = write_exr("rt_shifted.exr", 16, 16, 0.505f, 1e-4f);
  const std::string far = write_exr("rt_far.exr", 16, 16, 0.6f, 1e-4f);  // 7 sigma
  const CliRun pass = run_arbor("compare " + close + " " + ref + " --reference-test --json");
  EXPECT_EQ(pass.code, 0) << pass.out << pass.err;
  EXPECT_NE(pass.out.find("\"z_test_pass_fraction\": 1"), std::string::npos) << pass.out;
  EXPECT_NE(pass.out.find("\"passed\": true"), std::string::npos) << pass.out;
  const CliRun pooled = run_arbor("compare " + shifted + " " + ref + " --reference-test");
  EXPECT_EQ(pooled.code, 1) << pooled.out << pooled.err;
  EXPECT_NE(pooled.out.find("pixels: 100.000 % of 256 pass"), std::string::npos) << pooled.out;
  EXPECT_NE(pooled.out.find("image mean: z = 5.66 5.66 5.66 (|z| <= 3.14: alpha 0.005): FAIL"),
            std::string::npos)
      << pooled.out;
  const CliRun fail = run_arbor("compare " + far + " " + ref + " --reference-test");
  EXPECT_EQ(fail.code, 1) << fail.out << fail.err;
  EXPECT_NE(fail.out.find("FAIL"), std::string::npos) << fail.out;
  // The reference must carry variance; inputs are never overwritten.
  const std::string plain = write_exr("rt_plain.exr", 16, 16, 0.5f, -1.0f);
  const CliRun novar = run_arbor("compare " + close + " " + plain + " --reference-test");
  EXPECT_EQ(novar.code, 2);
  EXPECT_NE(novar.err.find(plain + ": error: has no variance"), std::string::npos) << novar.err;
  EXPECT_EQ(run_arbor("compare " + close + " " + ref + " --heatmap " + ref).code, 2);
  EXPECT_EQ(run_arbor("compare " + close + " /no/such.exr").code, 2);
  const CliRun small =
      run_arbor("compare " + close + " " + write_exr("rt_small.exr", 8, 8, 0.5f, 1e-4f));
  EXPECT_EQ(small.code, 2);
  EXPECT_NE(small.err.find("same size"), std::string::npos) << small.err;
}

// The treemaker integrator's EXR: its AOV channels add up to the beauty with the weights the
// EXR names, pixels are identical at one and two threads, and the path integrator refuses the AOV.
TEST(ArborCli, TreemakerRenderWritesTermsThatAddUpToTheBeauty) {
  const std::string dir = ::testing::TempDir();
  const std::string scene = write_temp(
      "tm.toml",
      "[render]\nwidth = 40\nheight = 30\nspp = 4\ntreemaker_spp = 3\nintegrator = \"treemaker\"\n"
      "[camera]\nposition = [10.0, -14.0, 3.0]\nlook_at = [0.0, 0.0, 5.0]\n[[tree]]\nspecies = \"" +
          std::string(ARBOR_SOURCE_DIR) +
          "/species/black_tupelo.toml\"\n"
          "[tree.treemaker]\nambient = 0.2\nlambert = 0.5\nheight = 0.3\nradius = 0.1\nangle = "
          "0.25\n"
          "[output]\naovs = [\"treemaker\"]\npixel_type = \"float\"\n");
  const CliRun one = run_arbor("render " + scene + " --threads 1 -o " + dir + "tm1.exr");
  ASSERT_EQ(one.code, 0) << one.err;
  EXPECT_NE(one.err.find("at 3 spp"), std::string::npos) << one.err;
  ASSERT_EQ(run_arbor("render " + scene + " --threads 2 -o " + dir + "tm2.exr").code, 0);
  OIIO::ImageBuf a(dir + "tm1.exr"), b(dir + "tm2.exr");
  ASSERT_TRUE(a.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  ASSERT_TRUE(b.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  const OIIO::ImageSpec& spec = a.spec();
  ASSERT_EQ(spec.nchannels, 4 + 5 + 18);  // RGBA, the factors, the contributions
  EXPECT_EQ(spec.get_string_attribute("arbor:integrator"), "treemaker");
  EXPECT_EQ(spec.get_int_attribute("arbor:spp"), 3);
  EXPECT_EQ(spec.get_string_attribute("arbor:treemaker_weights"),
            "ambient=0.2 lambert=0.5 height=0.3 radius=0.1 angle=0.25");
  // EXR stores channels by name (OIIO reads them back in its own order): look them up.
  auto channel = [&](const std::string& name) {
    const int c = spec.channelindex(name);
    EXPECT_GE(c, 0) << name;
    return std::max(c, 0);
  };
  const char* terms[5] = {"ambient", "lambert", "height", "radius", "angle"};
  std::vector<float> pa(40 * 30 * 27), pb(pa.size());
  a.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pa.data());
  b.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pb.data());
  EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)), 0);
  const float w[5] = {0.2f, 0.5f, 0.3f, 0.1f, 0.25f};
  const int coverage = channel("term_ambient.X");
  int tree_pixels = 0;
  for (std::size_t p = 0; p < 40 * 30; ++p) {
    const float* px = &pa[p * 27];
    if (px[coverage] > 0.0f) ++tree_pixels;
    EXPECT_GE(px[coverage], 0.0f);
    EXPECT_LE(px[coverage], 1.0f);  // the ambient factor is the tree's coverage of the pixel
    for (int c = 0; c < 3; ++c) {
      const std::string rgb(1, "RGB"[c]);
      float sum = px[channel("tm_rest." + rgb)];
      for (int i = 0; i < 5; ++i)
        sum += w[i] * px[channel(std::string("tm_") + terms[i] + "." + rgb)];
      EXPECT_NEAR(px[c], sum, 1e-5f + 1e-5f * px[c]) << "pixel " << p << " channel " << c;
    }
  }
  EXPECT_GT(tree_pixels, 40);

  const CliRun path = run_arbor("render " + scene + " --integrator path -o " + dir + "tm_path.exr");
  EXPECT_EQ(path.code, 2);
  EXPECT_NE(path.err.find(scene + ":19:9: error: output.aovs lists \"treemaker\", which only the "
                                  "treemaker integrator writes"),
            std::string::npos)
      << path.err;
  EXPECT_FALSE(exists(dir + "tm_path.exr"));
}

// A treemaker render with other weights is exactly rest + Σ w × tm_i: the fit gives those
// weights back with no error left, in either argument order; bad pairs exit 2.
TEST(ArborCli, FitTreemakerRecoversTheWeightsOfAnotherRender) {
  const std::string dir = ::testing::TempDir();
  const std::string head =
      "[render]\nwidth = 48\nheight = 36\ntreemaker_spp = 2\nintegrator = \"treemaker\"\n"
      "[camera]\nposition = [10.0, -14.0, 3.0]\nlook_at = [0.0, 0.0, 5.0]\n[[tree]]\nspecies = \"" +
      std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml\"\n";
  const std::string with_aovs =
      write_temp("fit_a.toml", head + "[output]\naovs = [\"treemaker\"]\npixel_type = \"float\"\n");
  const std::string target = write_temp(
      "fit_b.toml",
      head +
          "[tree.treemaker]\nambient = 0.05\nlambert = 0.3\nheight = 0.0\nradius = 0.25\n"
          "angle = 0.15\n[output]\npixel_type = \"float\"\n");
  ASSERT_EQ(run_arbor("render " + with_aovs + " -o " + dir + "fit_a.exr").code, 0);
  ASSERT_EQ(run_arbor("render " + target + " -o " + dir + "fit_b.exr").code, 0);
  for (const std::string& order :
       {dir + "fit_b.exr " + dir + "fit_a.exr", dir + "fit_a.exr " + dir + "fit_b.exr"}) {
    const CliRun r = run_arbor("compare " + order + " --fit-treemaker --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("\"exact\": \"" + dir + "fit_b.exr\""), std::string::npos) << r.out;
    auto number_after = [&](const std::string& key) {
      const auto at = r.out.find("\"" + key + "\": ");
      EXPECT_NE(at, std::string::npos) << key;
      return at == std::string::npos ? -1.0 : std::atof(r.out.c_str() + at + key.size() + 4);
    };
    EXPECT_NEAR(number_after("ambient"), 0.05, 1e-4);
    EXPECT_NEAR(number_after("lambert"), 0.3, 1e-4);
    EXPECT_NEAR(number_after("height"), 0.0, 1e-4);
    EXPECT_NEAR(number_after("radius"), 0.25, 1e-4);
    EXPECT_NEAR(number_after("angle"), 0.15, 1e-4);
    const auto fit = r.out.find("\"treemaker_fit\"");
    ASSERT_NE(fit, std::string::npos);
    EXPECT_LT(std::atof(r.out.c_str() + r.out.find("\"rmse\": ", fit) + 8), 1e-5) << r.out;
    EXPECT_NE(
        r.out.find(
            "\"render_weights\": \"ambient=0.1 lambert=0.4 height=0.2 radius=0.2 angle=0.1\""),
        std::string::npos)
        << r.out;
  }
  const CliRun text =
      run_arbor("compare " + dir + "fit_b.exr " + dir + "fit_a.exr --fit-treemaker");
  EXPECT_NE(text.out.find("[tree.treemaker]"), std::string::npos) << text.out;
  const CliRun neither =
      run_arbor("compare " + dir + "fit_b.exr " + dir + "fit_b.exr --fit-treemaker");
  EXPECT_EQ(neither.code, 2);
  EXPECT_NE(neither.err.find("neither image has them"), std::string::npos) << neither.err;
  const CliRun both =
      run_arbor("compare " + dir + "fit_a.exr " + dir + "fit_a.exr --fit-treemaker");
  EXPECT_EQ(both.code, 2);
  EXPECT_NE(both.err.find("both images have them"), std::string::npos) << both.err;
}

TEST(ArborCli, RenderedExrPixelsAreIdenticalAtOneAndTwoThreads) {
  const std::string dir = ::testing::TempDir();
  const std::string scene = write_temp(
      "threads.toml",
      "[render]\nwidth = 40\nheight = 30\nspp = 4\n[camera]\nposition = [10.0, -14.0, 3.0]\n"
      "look_at = [0.0, 0.0, 5.0]\n[[tree]]\nspecies = \"" +
          std::string(ARBOR_SOURCE_DIR) +
          "/species/black_tupelo.toml\"\n[output]\naovs = [\"albedo\", \"normal\", "
          "\"depth\", \"variance\"]\npixel_type = \"float\"\n");
  ASSERT_EQ(run_arbor("render " + scene + " --threads 1 -o " + dir + "one.exr").code, 0);
  ASSERT_EQ(run_arbor("render " + scene + " --threads 2 -o " + dir + "two.exr").code, 0);
  OIIO::ImageBuf one(dir + "one.exr"), two(dir + "two.exr");
  ASSERT_TRUE(one.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  ASSERT_TRUE(two.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  ASSERT_EQ(one.nchannels(), 14);  // RGBA, albedo, N, Z, variance
  std::vector<float> a(40 * 30 * 14), b(a.size());
  one.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, a.data());
  two.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, b.data());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
  EXPECT_EQ(one.spec().get_string_attribute("arbor:colorspace"),
            "Linear Rec.709 (sRGB)");  // the default (issue 25)
  EXPECT_EQ(one.spec().get_int_attribute("arbor:spp"), 4);
}

TEST(ArborCli, RenderRejectsBadScenesWithPosition) {
  const std::string bad = write_temp("bad_scene.toml", "[render]\nwidth = 64\nspp = 0\n");
  const CliRun r = run_arbor("render " + bad + " -o out.exr");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find(bad + ":3:7: error: render.spp = 0 is out of range"), std::string::npos)
      << r.err;
  const std::string unknown = write_temp("unknown_key.toml", "[camera]\nfov = 40\nzoom = 2\n");
  const CliRun u = run_arbor("render " + unknown + " -o out.exr");
  EXPECT_EQ(u.code, 2);
  EXPECT_NE(u.err.find(unknown + ":3:1: error: unknown key 'zoom' in [camera]"), std::string::npos)
      << u.err;
  const CliRun missing = run_arbor("render /no/such/scene.toml -o out.exr");
  EXPECT_EQ(missing.code, 2);
}

TEST(ArborCli, ExportWritesAPbrtSceneAndRefusesBadOutputs) {
  const std::string dir = ::testing::TempDir() + "cli_export/";
  const std::string scene = write_temp(
      "export_scene.toml", "[render]\nwidth = 24\nheight = 16\nspp = 2\n[[tree]]\nspecies = \"" +
                               std::string(ARBOR_SOURCE_DIR) + "/species/young_tree.skel\"\n");
  std::remove((dir + "s.pbrt").c_str());
  std::remove((dir + "s.sky.exr").c_str());
  const CliRun r =
      run_arbor("export " + scene + " -o " + dir + "s.pbrt --spp 7 --sky-resolution 32");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("wrote " + dir + "s.pbrt, " + dir + "s.sky.exr"), std::string::npos)
      << r.err;
  const std::string text = slurp(dir + "s.pbrt");
  EXPECT_NE(text.find("Sampler \"zsobol\" \"integer pixelsamples\" 7"), std::string::npos);
  EXPECT_NE(text.find("\"string filename\" \"s.sky.exr\""), std::string::npos);
  EXPECT_TRUE(exists(dir + "s.sky.exr"));

  const CliRun ext = run_arbor("export " + scene + " -o " + dir + "s.txt");
  EXPECT_EQ(ext.code, 2);
  EXPECT_NE(ext.err.find("must end in .pbrt"), std::string::npos) << ext.err;
  // The sky beside the output would be the scene's environment map: refused, nothing written.
  const std::string envmap = write_temp("export_env.sky.exr", "stands for an image");
  const std::string with_map =
      write_temp("export_env.toml", "[sky]\nmodel = \"envmap\"\npath = \"" + envmap + "\"\n");
  const std::string out = envmap.substr(0, envmap.size() - 8) + ".pbrt";
  const CliRun clash = run_arbor("export " + with_map + " -o " + out);
  EXPECT_EQ(clash.code, 2);
  EXPECT_NE(clash.err.find("would overwrite the input " + envmap), std::string::npos) << clash.err;
  EXPECT_FALSE(exists(out));
  EXPECT_EQ(slurp(envmap), "stands for an image");
  const CliRun bad_sky = run_arbor("export " + scene + " --sky-resolution 3 -o " + dir + "t.pbrt");
  EXPECT_EQ(bad_sky.code, 2);
  EXPECT_FALSE(exists(dir + "t.pbrt"));
  // A frame of an animation: the wind scene at frame 12 differs from frame 0 (the willow sways).
  const std::string wind = std::string(ARBOR_SOURCE_DIR) + "/scenes/wind.toml";
  ASSERT_EQ(
      run_arbor("export " + wind + " --frame 0 --sky-resolution 16 -o " + dir + "w0.pbrt").code, 0);
  ASSERT_EQ(
      run_arbor("export " + wind + " --frame 12 --sky-resolution 16 -o " + dir + "w12.pbrt").code,
      0);
  EXPECT_NE(slurp(dir + "w0.pbrt"), slurp(dir + "w12.pbrt"));
  EXPECT_EQ(run_arbor("export " + wind + " --frame 48 -o " + dir + "w48.pbrt").code, 2);
  const CliRun h = run_arbor("export --help");
  EXPECT_EQ(h.code, 0);
  EXPECT_NE(h.out.find("pbrt-v4"), std::string::npos);
}

TEST(ArborCli, RenderWritesExrAndPngAndNothingOnFailure) {
  const std::string dir = ::testing::TempDir();
  const std::string scene = write_temp(
      "tiny.toml",
      "[render]\nwidth = 24\nheight = 16\nspp = 2\n[camera]\nposition = [10.0, -14.0, 3.0]\n"
      "look_at = [0.0, 0.0, 5.0]\n[[tree]]\nspecies = \"" +
          std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml\"\n");
  const CliRun r =
      run_arbor("render " + scene + " -o " + dir + "tiny.exr --png " + dir + "tiny.png");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(exists(dir + "tiny.exr"));
  EXPECT_TRUE(exists(dir + "tiny.png"));
  EXPECT_NE(r.err.find("samples/s"), std::string::npos);
  // A folder that cannot be made (a file is in its way): exit 1, nothing written.
  const CliRun bad = run_arbor("render " + scene + " -o " + dir + "tiny.png/sub/tiny.exr");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("cannot create its folder"), std::string::npos) << bad.err;
  EXPECT_FALSE(exists(dir + "tiny.png/sub/tiny.exr"));
}

// Issue 15: a display-encoded PNG and a scene-linear EXR are refused together; like with like
// works.
TEST(ArborCli, CompareRefusesAPngAgainstAnExr) {
  const std::string dir = ::testing::TempDir();
  const std::string scene = write_temp(
      "cmp_kinds.toml",
      "[render]\nwidth = 12\nheight = 8\nspp = 2\n[camera]\nposition = [10.0, -14.0, 3.0]\n"
      "look_at = [0.0, 0.0, 5.0]\n[[tree]]\nspecies = \"" +
          std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml\"\n");
  ASSERT_EQ(
      run_arbor("render " + scene + " -o " + dir + "kinds.exr --png " + dir + "kinds.png").code, 0);
  const CliRun mixed = run_arbor("compare " + dir + "kinds.png " + dir + "kinds.exr");
  EXPECT_EQ(mixed.code, 2);
  EXPECT_NE(mixed.err.find("display-encoded"), std::string::npos) << mixed.err;
  EXPECT_NE(mixed.err.find(dir + "kinds.png"), std::string::npos) << mixed.err;
  EXPECT_EQ(run_arbor("compare " + dir + "kinds.exr " + dir + "kinds.png").code, 2);
  EXPECT_EQ(run_arbor("compare " + dir + "kinds.png " + dir + "kinds.png").code, 0);
  EXPECT_EQ(run_arbor("compare " + dir + "kinds.exr " + dir + "kinds.exr").code, 0);
}

// Issue 15: -o replaces the scene's outputs (its PNG is written only with --png); missing output
// folders are made; arbor:variance is only written with the variance channels it describes.
TEST(ArborCli, MinusOReplacesTheScenesOutputsAndMissingFoldersAreMade) {
  const std::string dir = ::testing::TempDir() + "outputs_" + std::to_string(::getpid()) + "/";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string scene = write_temp(
      "outputs.toml",
      "[render]\nwidth = 16\nheight = 12\nspp = 2\n[camera]\nposition = [10.0, -14.0, 3.0]\n"
      "look_at = [0.0, 0.0, 5.0]\n[[tree]]\nspecies = \"" +
          std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml\"\n[output]\nexr = \"" +
          dir + "named.exr\"\npng = \"" + dir + "named.png\"\naovs = [\"albedo\"]\n");
  const CliRun a = run_arbor("render " + scene + " -o " + dir + "fresh/deeper/a.exr");
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_TRUE(exists(dir + "fresh/deeper/a.exr"));
  EXPECT_FALSE(exists(dir + "named.png"));  // the scene's PNG is not written behind -o's back
  EXPECT_FALSE(exists(dir + "named.exr"));
  const CliRun b = run_arbor("render " + scene + " -o " + dir + "b.exr --png " + dir + "png/b.png");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_TRUE(exists(dir + "png/b.png"));
  EXPECT_FALSE(exists(dir + "named.png"));
  // No variance channels, no arbor:variance; with them, it says how they were estimated.
  OIIO::ImageBuf plain(dir + "fresh/deeper/a.exr");
  ASSERT_TRUE(plain.init_spec(dir + "fresh/deeper/a.exr", 0, 0));
  EXPECT_EQ(plain.spec().find_attribute("arbor:variance"), nullptr);
  std::string text = slurp(scene);
  text.replace(text.find("aovs = [\"albedo\"]"), 17, "aovs = [\"variance\"]");
  const std::string with_variance = write_temp("outputs_variance.toml", text);
  const CliRun v = run_arbor("render " + with_variance + " -o " + dir + "v.exr");
  ASSERT_EQ(v.code, 0) << v.err;
  OIIO::ImageBuf with(dir + "v.exr");
  ASSERT_TRUE(with.init_spec(dir + "v.exr", 0, 0));
  EXPECT_NE(with.spec().find_attribute("arbor:variance"), nullptr);
  // Without -o the scene's own outputs are written, folders made.
  const CliRun c = run_arbor("render " + scene);
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_TRUE(exists(dir + "named.exr"));
  EXPECT_TRUE(exists(dir + "named.png"));
  std::filesystem::remove_all(dir);
}

// $OCIO names the config of the whole run (read once, at start): an unreadable one is an input
// error naming it, a copy of arbor's own renders the same pixels, a config without the scene's
// colour space is refused at the scene key, and an empty $OCIO means arbor's own config.
TEST(ArborCli, OcioNamesTheConfigOfTheRun) {
  const std::string dir = ::testing::TempDir();
  const std::string scene = write_temp(
      "ocio_scene.toml",
      "[render]\nwidth = 12\nheight = 8\nspp = 2\n[camera]\nposition = [10.0, -14.0, 3.0]\n"
      "look_at = [0.0, 0.0, 5.0]\n[output]\ncolorspace = \"ACEScg\"\n[[tree]]\nspecies = \"" +
          std::string(ARBOR_SOURCE_DIR) + "/species/quaking_aspen.toml\"\n");
  const std::string args = "render " + scene + " -o " + dir + "ocio.exr --png " + dir + "ocio.png";
  std::remove((dir + "ocio.exr").c_str());  // left by an earlier run
  const CliRun missing = run_arbor_with("OCIO=/no/such/config.ocio", args);
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("/no/such/config.ocio"), std::string::npos) << missing.err;
  EXPECT_FALSE(exists(dir + "ocio.exr"));

  const std::string shipped = slurp(std::string(ARBOR_SOURCE_DIR) + "/imaging/ocio/config.ocio");
  const std::string copy = write_temp("ocio_copy.ocio", shipped);
  ASSERT_EQ(run_arbor_with("OCIO=" + copy, args).code, 0);
  OIIO::ImageBuf with_copy(dir + "ocio.exr");
  ASSERT_EQ(run_arbor_with("OCIO=", args).code, 0);  // empty: arbor's own
  OIIO::ImageBuf with_own(dir + "ocio.exr");
  ASSERT_TRUE(with_copy.read(0, 0, true, OIIO::TypeDesc::FLOAT) &&
              with_own.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  EXPECT_EQ(OIIO::ImageBufAlgo::compare(with_copy, with_own, 0.0f, 0.0f).nfail, 0u);

  std::string renamed = shipped;
  const std::string from = "    name: ACEScg\n";
  ASSERT_NE(renamed.find(from), std::string::npos);
  renamed.replace(renamed.find(from), from.size(), "    name: AP1 linear\n");
  const std::string other = write_temp("ocio_other.ocio", renamed);
  const CliRun refused = run_arbor_with("OCIO=" + other, args);
  EXPECT_EQ(refused.code, 2);
  EXPECT_NE(
      refused.err.find(
          scene + ":9:14: error: output.colorspace \"ACEScg\" is not in the OCIO config " + other),
      std::string::npos)
      << refused.err;
}

// exposure = "auto": the render says the metered stops in arbor:exposure with every digit, and a
// render given those stops as its exposure makes the same pixels; a fixed exposure is recorded
// as given.
TEST(ArborCli, AMeteredExposureIsRecordedAndReproducible) {
  const std::string dir = ::testing::TempDir();
  const std::string body = "[render]\nwidth = 40\nheight = 30\nspp = 4\n[[tree]]\nspecies = \"" +
                           std::string(ARBOR_SOURCE_DIR) +
                           "/species/black_tupelo.toml\"\n[output]\npixel_type = \"float\"\n";
  const std::string metered = write_temp("metered.toml", "[camera]\nexposure = \"auto\"\n" + body);
  const CliRun m = run_arbor("render " + metered + " -o " + dir + "metered.exr");
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_NE(m.err.find("arbor: metered exposure"), std::string::npos) << m.err;
  OIIO::ImageBuf a(dir + "metered.exr");
  ASSERT_TRUE(a.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  const std::string said = a.spec().get_string_attribute("arbor:exposure");
  ASSERT_NE(said.find(" (metered)"), std::string::npos) << said;
  const std::string stops = said.substr(0, said.find(' '));
  const std::string fixed = write_temp("fixed.toml", "[camera]\nexposure = " + stops + "\n" + body);
  ASSERT_EQ(run_arbor("render " + fixed + " -o " + dir + "fixed.exr").code, 0);
  OIIO::ImageBuf b(dir + "fixed.exr");
  ASSERT_TRUE(b.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  EXPECT_EQ(b.spec().get_string_attribute("arbor:exposure"), stops);
  std::vector<float> pa(40 * 30 * 4), pb(pa.size());
  a.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pa.data());
  b.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pb.data());
  EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)), 0);
}
