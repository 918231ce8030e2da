// The command line against hostile input and hostile conditions: outputs are never lost or
// half-written, inputs are never overwritten, bad values are refused with their position.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "temp_files.h"
// Named before app/cli.h declares its function run_arbor(), which hides the namespace.
using arbor::testing::files_in;
namespace {
std::string fresh_folder(const std::string& name) {
  return arbor::testing::fresh_folder("robust_" + name);
}
}  // namespace

#include "app/cli.h"

namespace {

// A 160x120 image of smooth noise: its PNG heatmap is tens of kilobytes.
std::string noisy_exr(const std::string& path, int seed) {
  OIIO::ImageBuf buf(OIIO::ImageSpec(160, 120, 3, OIIO::TypeDesc::FLOAT));
  unsigned state = 12345u + static_cast<unsigned>(seed);
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 160; ++x) {
      state = state * 1664525u + 1013904223u;
      const float v = static_cast<float>(state >> 8) / 16777216.0f;
      const float px[3] = {v, 0.5f * v, 0.25f};
      buf.setpixel(x, y, px);
    }
  }
  EXPECT_TRUE(buf.write(path));
  return path;
}

}  // namespace

// A full disk (here a file-size limit, which fails writes the same way) must not replace the
// old picture with a truncated one, and must say so with exit code 1.
TEST(Robustness, FailedPngWriteKeepsTheOldFile) {
  const std::string dir = fresh_folder("png_limit");
  const std::string a = noisy_exr(dir + "/a.exr", 1), b = noisy_exr(dir + "/b.exr", 2);
  const std::string heat = dir + "/heat.png";
  write_temp("robust_png_limit/heat.png", "the old picture");
  const CliRun r =
      run_arbor_with("trap '' XFSZ; ulimit -f 8;", "compare " + a + " " + b + " --heatmap " + heat);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("cannot write " + heat), std::string::npos) << r.err;
  EXPECT_EQ(slurp(heat), "the old picture");
  EXPECT_EQ(files_in(dir), (std::vector<std::string>{"a.exr", "b.exr", "heat.png"}));
  // Without the limit the same command writes it.
  const CliRun ok = run_arbor("compare " + a + " " + b + " --heatmap " + heat);
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_GT(slurp(heat).size(), 8u * 1024u);
}

TEST(Robustness, OutputsNeverOverwriteInputsHoweverSpelled) {
  const std::string dir = fresh_folder("overwrite");
  const std::string a = noisy_exr(dir + "/a.exr", 1), b = noisy_exr(dir + "/b.exr", 2);
  ASSERT_EQ(symlink("a.exr", (dir + "/link.exr").c_str()), 0);
  const std::string before = slurp(a);
  for (const std::string& out :
       {dir + "/./a.exr", dir + "/../robust_overwrite/a.exr", dir + "/link.exr"}) {
    const CliRun r = run_arbor("compare " + a + " " + b + " --heatmap " + out);
    EXPECT_EQ(r.code, 2) << out;
    EXPECT_NE(r.err.find("would overwrite the input"), std::string::npos) << r.err;
    const CliRun s = run_arbor("compare " + a + " " + b + " --side-by-side " + out);
    EXPECT_EQ(s.code, 2) << out;
  }
  EXPECT_EQ(slurp(a), before);
  // Both pictures to one file is refused too.
  const CliRun both = run_arbor("compare " + a + " " + b + " --heatmap " + dir +
                                "/x.png --side-by-side " + dir + "/./x.png");
  EXPECT_EQ(both.code, 2) << both.err;
  // A render whose output is one of the scene's inputs (here its environment map).
  const std::string scene = write_temp(
      "robust_overwrite/env.toml",
      "[render]\nwidth = 8\nheight = 8\nspp = 1\n[sky]\nmodel = \"envmap\"\npath = \"a.exr\"\n");
  const CliRun r = run_arbor("render " + scene + " -o " + dir + "/link.exr");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("would overwrite the input"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(a), before);
  // grow -o onto its own species file.
  const std::string sp = dir + "/tree.skel";
  ASSERT_EQ(std::system(("cp " + std::string(ARBOR_SOURCE_DIR) + "/species/*.skel " + sp).c_str()),
            0);
  const std::string skel = slurp(sp);
  const CliRun g = run_arbor("grow " + sp + " -o " + dir + "/./tree.skel");
  EXPECT_EQ(g.code, 2) << g.err;
  EXPECT_EQ(slurp(sp), skel);
}

// Outputs write through a symlink to its target; the link stays a link.
TEST(Robustness, OutputsWriteThroughSymlinks) {
  const std::string dir = fresh_folder("symlink");
  const std::string a = noisy_exr(dir + "/a.exr", 1), b = noisy_exr(dir + "/b.exr", 2);
  ASSERT_EQ(mkdir((dir + "/real").c_str(), 0755), 0);
  write_temp("robust_symlink/real/heat.png", "old");
  ASSERT_EQ(symlink("real/heat.png", (dir + "/heat.png").c_str()), 0);
  const CliRun r = run_arbor("compare " + a + " " + b + " --heatmap " + dir + "/heat.png");
  ASSERT_EQ(r.code, 0) << r.err;
  struct stat st;
  ASSERT_EQ(lstat((dir + "/heat.png").c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  OIIO::ImageBuf shown(dir + "/real/heat.png");
  EXPECT_TRUE(shown.read()) << shown.geterror();
  EXPECT_EQ(files_in(dir + "/real"), std::vector<std::string>{"heat.png"});
}

// Every number on the command line is checked as strictly as the scene keys.
TEST(Robustness, CommandLineNumbersAreCheckedStrictly) {
  const std::string skel = species("young_tree.skel");
  const std::string scene = std::string(ARBOR_SOURCE_DIR) + "/scenes/default.toml";
  for (const std::string& args :
       {"grow " + skel + " --seed 18446744073709551616",
        "grow " + skel + " --seed 99999999999999999999999", "grow " + skel + " --seed -1",
        "grow " + skel + " --seed 1e3", "grow " + skel + " --time nan",
        "grow " + skel + " --time inf", "grow " + skel + " --time 1e308",
        "grow " + skel + " --quality nan", "grow " + skel + " --quality 0",
        "render " + scene + " --time nan -o x.exr", "render " + scene + " --time inf -o x.exr",
        "render " + scene + " --time 1e308 -o x.exr",
        "render " + scene + " --seed 18446744073709551616 -o x.exr",
        "render " + scene + " --spp 0 -o x.exr", "render " + scene + " --width -5 -o x.exr",
        "render " + scene + " --threads nan -o x.exr"}) {
    const CliRun r = run_arbor(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
  }
  // The largest seed is a seed like any other, and it differs from its neighbour.
  const CliRun top = run_arbor("grow " + species("lsystem_weed.lsys") +
                               " --seed 18446744073709551615 --stats --json");
  EXPECT_EQ(top.code, 0) << top.err;
  EXPECT_NE(top.out.find("\"seed\": 18446744073709551615"), std::string::npos) << top.out;
}

// The largest image the scene allows is refused before anything is built (exit 2, naming
// --force), instead of exhausting the machine's memory. (The largest forest, which fits in this
// machine's 24 GB but not in the report's 8 GB, is tested with that limit in render_budget_test.)
TEST(Robustness, AbsurdRendersAreRefusedUpFront) {
  const std::string image =
      write_temp("robust_image.toml", "[render]\nwidth = 16384\nheight = 16384\nspp = 1\n");
  const CliRun big = run_arbor("render " + image + " -o " + ::testing::TempDir() + "big.exr");
  EXPECT_EQ(big.code, 2) << big.err;
  EXPECT_NE(big.err.find(image + ": error: the render would need about"), std::string::npos)
      << big.err;
  EXPECT_NE(big.err.find("16384x16384"), std::string::npos) << big.err;
  EXPECT_NE(big.err.find("--force"), std::string::npos) << big.err;
  EXPECT_FALSE(exists(::testing::TempDir() + "big.exr"));
}

// A second SIGTERM or SIGINT (the first asks the render to stop after its pass) ends a render
// by the signal at once and leaves neither an output nor a temporary. (The first signal alone:
// long_render_test.cpp.)
TEST(Robustness, AnInterruptedRenderLeavesNothingBehind) {
  for (const int sig : {SIGTERM, SIGINT}) {
    const std::string dir = fresh_folder("interrupt_" + std::to_string(sig));
    const std::string scene = std::string(ARBOR_SOURCE_DIR) + "/scenes/default.toml";
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      signal(SIGINT, SIG_DFL);
      if (chdir(dir.c_str()) != 0) _exit(3);
      if (!freopen("/dev/null", "w", stderr)) _exit(3);
      execl(ARBOR_BINARY, ARBOR_BINARY, "render", scene.c_str(), "--spp", "4096", "-o", "out.exr",
            "--png", "out.png", static_cast<char*>(nullptr));
      _exit(3);
    }
    sleep(1);
    kill(child, sig);
    usleep(200000);
    kill(child, sig);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "exit " << WEXITSTATUS(status);
    EXPECT_EQ(WTERMSIG(status), sig);  // a shell reports it as 128 + signal: 143, 130
    EXPECT_TRUE(files_in(dir).empty());
  }
}
