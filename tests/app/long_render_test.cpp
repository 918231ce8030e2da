// Long renders through the command line: a signal stops after the running pass and writes what
// is done, --resume continues it to the image an uninterrupted render gives, --time-limit stops
// in time, checkpoints survive kill -9, and work units (--passes, --crop) merge back exactly.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "temp_files.h"
using arbor::testing::files_in;
namespace {
std::string fresh_folder(const std::string& name) {
  return arbor::testing::fresh_folder("long_" + name);
}
}  // namespace

#include "app/cli.h"

namespace {

// A small scene of many short passes: 32x24, `spp` samples in passes of 4, every AOV that
// depends on the passes, float pixels.
std::string scene_file(const std::string& dir, int spp, const std::string& extra = "") {
  const std::string path = dir + "/scene.toml";
  std::ofstream(path)
      << "[render]\nwidth = 32\nheight = 24\nspp = " << spp
      << "\npass_spp = 4\nseed = 5\nmax_depth = 4\n"
      << extra
      << "[camera]\nposition = [10.0, -14.0, 3.0]\nlook_at = [0.0, 0.0, 4.0]\n"
         "[[tree]]\nspecies = \""
      << ARBOR_SOURCE_DIR << "/species/lsystem_weed.lsys\"\nseed = 2\n"
      << "[output]\naovs = [\"variance\", \"samples\", \"albedo\"]\npixel_type = \"float\"\n";
  return path;
}

struct Exr {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;
};

Exr read_exr(const std::string& path) {
  Exr e;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  if (!in) return e;
  e.spec = in->spec();
  e.pixels.resize(static_cast<std::size_t>(e.spec.width) * e.spec.height * e.spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, e.spec.nchannels, OIIO::TypeDesc::FLOAT, e.pixels.data()));
  return e;
}

bool same_pixels(const Exr& a, const Exr& b) {
  return a.spec.channelnames == b.spec.channelnames && a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

// Starts `arbor ARGS...` in `dir` with stderr to dir/err.txt.
pid_t start_arbor(const std::string& dir, const std::vector<std::string>& args) {
  const pid_t child = fork();
  if (child == 0) {
    signal(SIGINT, SIG_DFL);
    if (chdir(dir.c_str()) != 0) _exit(3);
    if (!freopen("err.txt", "w", stderr)) _exit(3);
    std::vector<char*> argv{const_cast<char*>(ARBOR_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(ARBOR_BINARY, argv.data());
    _exit(3);
  }
  return child;
}

// Waits until `path` exists (up to 60 s).
bool wait_for(const std::string& path) {
  for (int i = 0; i < 6000 && !exists(path); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return exists(path);
}

}  // namespace

// The first SIGINT or SIGTERM stops after the running pass: a valid EXR and PNG of the passes
// done, marked incomplete, its film state beside it, exit 130 / 143, no temporary; --resume then
// finishes it to exactly the uninterrupted image.
TEST(LongRender, ASignalStopsAfterThePassAndResumeFinishesItExactly) {
  const std::string whole_dir = fresh_folder("whole");
  const std::string whole_scene = scene_file(whole_dir, 1024);
  const CliRun whole = run_arbor("render " + whole_scene + " -o " + whole_dir + "/whole.exr");
  ASSERT_EQ(whole.code, 0) << whole.err;
  EXPECT_FALSE(exists(whole_dir + "/whole.exr.state"));  // finished: nothing to resume
  const Exr reference = read_exr(whole_dir + "/whole.exr");
  EXPECT_EQ(reference.spec.get_int_attribute("arbor:passes"), 256);
  EXPECT_EQ(reference.spec.get_int_attribute("arbor:spp"), 1024);
  EXPECT_EQ(reference.spec.get_int_attribute("arbor:incomplete", 0), 0);

  for (const int sig : {SIGINT, SIGTERM}) {
    const std::string dir = fresh_folder("signal_" + std::to_string(sig));
    const std::string scene = scene_file(dir, 1024);
    const pid_t child = start_arbor(
        dir, {"render", scene, "-o", "out.exr", "--png", "out.png", "--checkpoint-seconds", "0.2"});
    // The first checkpoint shows that passes are being rendered; then the signal.
    ASSERT_TRUE(wait_for(dir + "/out.exr.state"));
    kill(child, sig);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << "died by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"err.txt", "out.exr", "out.exr.state",
                                                       "out.png", "scene.toml"}));
    const Exr part = read_exr(dir + "/out.exr");
    EXPECT_EQ(part.spec.get_int_attribute("arbor:incomplete"), 1);
    EXPECT_EQ(part.spec.get_string_attribute("arbor:stopped"), "interrupted");
    const int passes = part.spec.get_int_attribute("arbor:passes");
    EXPECT_GT(passes, 0);
    EXPECT_LT(passes, 256) << "the render finished before the signal: make it longer";
    EXPECT_EQ(part.spec.get_int_attribute("arbor:spp"), 4 * passes);
    EXPECT_NE(slurp(dir + "/err.txt").find("continue with --resume"), std::string::npos);

    const CliRun resumed =
        run_arbor("render " + scene + " -o " + dir + "/out.exr --png " + dir + "/out.png --resume");
    ASSERT_EQ(resumed.code, 0) << resumed.err;
    EXPECT_FALSE(exists(dir + "/out.exr.state"));
    const Exr done = read_exr(dir + "/out.exr");
    EXPECT_TRUE(same_pixels(done, reference))
        << "the resumed render differs from the uninterrupted one";
    EXPECT_EQ(done.spec.get_int_attribute("arbor:incomplete", 0), 0);
    EXPECT_EQ(done.spec.get_int_attribute("arbor:spp"), 1024);
    // Resuming a finished render does nothing and says so.
    const CliRun again = run_arbor("render " + scene + " -o " + dir + "/out.exr --resume");
    EXPECT_EQ(again.code, 0) << again.err;
    EXPECT_NE(again.err.find("already finished"), std::string::npos) << again.err;
  }
}

// --resume refuses a film state of other settings, and a render with nothing to resume.
TEST(LongRender, ResumeRefusesOtherSettings) {
  const std::string dir = fresh_folder("refuse");
  const std::string scene = scene_file(dir, 64);
  const CliRun part = run_arbor("render " + scene + " -o " + dir + "/out.exr --passes 0:4");
  ASSERT_EQ(part.code, 0) << part.err;
  ASSERT_TRUE(exists(dir + "/out.exr.state"));
  const CliRun seed =
      run_arbor("render " + scene + " -o " + dir + "/out.exr --passes 0:4 --seed 6 --resume");
  EXPECT_EQ(seed.code, 2) << seed.err;
  EXPECT_NE(seed.err.find("other settings or inputs (seed 5 in the state, 6 in this command)"),
            std::string::npos)
      << seed.err;
  // A changed input is named too.
  std::ofstream(scene, std::ios::app) << "# a comment changes the scene's bytes\n";
  const CliRun edited =
      run_arbor("render " + scene + " -o " + dir + "/out.exr --passes 0:4 --resume");
  EXPECT_EQ(edited.code, 2) << edited.err;
  EXPECT_NE(edited.err.find("(the scene file has other contents)"), std::string::npos)
      << edited.err;
  const CliRun none = run_arbor("render " + scene + " -o " + dir + "/none.exr --resume");
  EXPECT_EQ(none.code, 2) << none.err;
  EXPECT_NE(none.err.find("no film state"), std::string::npos) << none.err;
  const CliRun range = run_arbor("render " + scene + " -o " + dir + "/out.exr --passes 0:17");
  EXPECT_EQ(range.code, 2) << range.err;
  EXPECT_NE(range.err.find("0 <= A < B <= 16"), std::string::npos) << range.err;
}

// --time-limit stops after the last pass that fits: a finished, valid file saying why it stopped;
// resumed, it is the uninterrupted image.
TEST(LongRender, TimeLimitStopsInTimeAndResumes) {
  const std::string dir = fresh_folder("time");
  const std::string scene = scene_file(dir, 16384);
  const CliRun limited = run_arbor("render " + scene + " -o " + dir + "/out.exr --time-limit 0.25");
  ASSERT_EQ(limited.code, 0) << limited.err;
  const Exr part = read_exr(dir + "/out.exr");
  EXPECT_EQ(part.spec.get_string_attribute("arbor:stopped"), "time limit");
  EXPECT_EQ(part.spec.get_int_attribute("arbor:incomplete", 0), 0);
  const int passes = part.spec.get_int_attribute("arbor:passes");
  EXPECT_GT(passes, 0);
  EXPECT_LT(passes, 4096);
  // How long it took is not asserted (a loaded machine may take any time; speed is bench/'s):
  // the file says it stopped for the limit, before its last pass, and resumes to the whole.
  const CliRun resumed =
      run_arbor("render " + scene + " -o " + dir + "/out.exr --resume --spp 16384");
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  const CliRun whole = run_arbor("render " + scene + " -o " + dir + "/whole.exr");
  ASSERT_EQ(whole.code, 0) << whole.err;
  EXPECT_TRUE(same_pixels(read_exr(dir + "/out.exr"), read_exr(dir + "/whole.exr")));
}

// A checkpointed render killed with SIGKILL keeps what it last wrote: a valid EXR and a film
// state that --resume finishes.
TEST(LongRender, CheckpointsSurviveKill9) {
  const std::string dir = fresh_folder("kill9");
  const std::string scene = scene_file(dir, 8192);
  const pid_t child =
      start_arbor(dir, {"render", scene, "-o", "out.exr", "--checkpoint-seconds", "0.1"});
  ASSERT_TRUE(wait_for(dir + "/out.exr.state"));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  const Exr part = read_exr(dir + "/out.exr");
  ASSERT_EQ(part.spec.get_int_attribute("arbor:incomplete"), 1);
  EXPECT_GT(part.spec.get_int_attribute("arbor:passes"), 0);
  // A kill during a checkpoint's write leaves that write's temporary (SIGKILL cannot be caught);
  // the next writer of the same file removes it.
  const CliRun resumed = run_arbor("render " + scene + " -o " + dir + "/out.exr --resume");
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  for (const std::string& f : files_in(dir)) EXPECT_EQ(f.find(".tmp"), std::string::npos) << f;
  const CliRun whole = run_arbor("render " + scene + " -o " + dir + "/whole.exr");
  ASSERT_EQ(whole.code, 0) << whole.err;
  EXPECT_TRUE(same_pixels(read_exr(dir + "/out.exr"), read_exr(dir + "/whole.exr")));
}

// Work units: pass ranges and crops, merged in any order, give the single render bit for bit;
// parts of another render, overlaps and gaps are refused naming the part and the pixel.
TEST(LongRender, PassRangesAndCropsMergeToTheSingleRender) {
  const std::string dir = fresh_folder("merge");
  const std::string scene = scene_file(dir, 64);  // 16 passes
  auto render = [&](const std::string& out, const std::string& opts) {
    const CliRun r = run_arbor("render " + scene + " -o " + dir + "/" + out + " " + opts);
    EXPECT_EQ(r.code, 0) << opts << "\n" << r.err;
    EXPECT_TRUE(exists(dir + "/" + out + ".state")) << out;
    return dir + "/" + out;
  };
  const CliRun whole = run_arbor("render " + scene + " -o " + dir + "/whole.exr");
  ASSERT_EQ(whole.code, 0) << whole.err;
  const Exr reference = read_exr(dir + "/whole.exr");

  // Passes: three ranges, given out of order.
  const std::string p0 = render("p0.exr", "--passes 0:5"), p1 = render("p1.exr", "--passes 5:11"),
                    p2 = render("p2.exr", "--passes 11:16");
  const CliRun merged = run_arbor("merge -o " + dir + "/passes.exr --png " + dir + "/passes.png " +
                                  p2 + " " + p0 + " " + p1);
  ASSERT_EQ(merged.code, 0) << merged.err;
  EXPECT_NE(merged.err.find("(the whole render)"), std::string::npos) << merged.err;
  EXPECT_TRUE(same_pixels(read_exr(dir + "/passes.exr"), reference));
  EXPECT_FALSE(exists(dir + "/passes.exr.state"));
  EXPECT_TRUE(exists(dir + "/passes.png"));
  // Two later ranges are not the whole render: refused, unless asked for a part (--partial)
  // that still merges with the first.
  const CliRun later = run_arbor("merge -o " + dir + "/p12.exr " + p1 + " " + p2);
  EXPECT_EQ(later.code, 2) << later.err;
  EXPECT_NE(later.err.find("the 2 parts cover only passes 5 to 15 of the render's passes 0 to 15; "
                           "give the parts that are missing, or --partial"),
            std::string::npos)
      << later.err;
  EXPECT_FALSE(exists(dir + "/p12.exr"));
  ASSERT_EQ(run_arbor("merge --partial -o " + dir + "/p12.exr " + p1 + " " + p2).code, 0);
  EXPECT_TRUE(exists(dir + "/p12.exr.state"));
  ASSERT_EQ(run_arbor("merge -o " + dir + "/again.exr " + dir + "/p12.exr " + p0).code, 0);
  EXPECT_TRUE(same_pixels(read_exr(dir + "/again.exr"), reference));

  // Crops (one split into pass ranges too): stitched.
  const std::string left = render("left.exr", "--crop 0,0,13,24"),
                    right_a = render("right_a.exr", "--crop 13,0,32,24 --passes 0:7"),
                    right_b = render("right_b.exr", "--crop 13,0,32,24 --passes 7:16");
  const Exr crop = read_exr(left);
  EXPECT_EQ(crop.spec.width, 13);
  EXPECT_EQ(crop.spec.full_width, 32);
  EXPECT_EQ(crop.spec.get_string_attribute("arbor:crop"), "0,0,13,24");
  ASSERT_EQ(
      run_arbor("merge -o " + dir + "/crops.exr " + right_b + " " + left + " " + right_a).code, 0);
  EXPECT_TRUE(same_pixels(read_exr(dir + "/crops.exr"), reference));
  // A forgotten tile: refused with what the parts cover, nothing written.
  const CliRun forgotten = run_arbor("merge -o " + dir + "/half.exr " + left);
  EXPECT_EQ(forgotten.code, 2) << forgotten.err;
  EXPECT_NE(forgotten.err.find("the part covers only the window 0,0,13,24 of the 32x24 image;"),
            std::string::npos)
      << forgotten.err;
  EXPECT_FALSE(exists(dir + "/half.exr"));
  EXPECT_FALSE(exists(dir + "/half.exr.state"));

  // Refused: an overlap, a gap, a part of another render.
  const CliRun overlap =
      run_arbor("merge -o " + dir + "/bad.exr " + p0 + " " + render("p4.exr", "--passes 4:16"));
  EXPECT_EQ(overlap.code, 2) << overlap.err;
  EXPECT_NE(overlap.err.find("overlaps " + p0 + ": both hold pass 4 of pixel (0, 0)"),
            std::string::npos)
      << overlap.err;
  const CliRun gap = run_arbor("merge -o " + dir + "/bad.exr " + p0 + " " + p2);
  EXPECT_EQ(gap.code, 2) << gap.err;
  EXPECT_NE(gap.err.find("leaves a gap: no part holds passes 5 to 10 of pixel (0, 0)"),
            std::string::npos)
      << gap.err;
  const CliRun hole = run_arbor("merge -o " + dir + "/bad.exr " + left + " " +
                                render("r.exr", "--crop 14,0,32,24"));
  EXPECT_EQ(hole.code, 2) << hole.err;
  EXPECT_NE(hole.err.find("of pixel (13, 0), which lies in no part's window"), std::string::npos)
      << hole.err;
  const CliRun other = run_arbor("merge -o " + dir + "/bad.exr " + p0 + " " +
                                 render("seed.exr", "--passes 5:16 --seed 9"));
  EXPECT_EQ(other.code, 2) << other.err;
  EXPECT_NE(other.err.find("is not a part of the same render"), std::string::npos) << other.err;
  EXPECT_FALSE(exists(dir + "/bad.exr"));
  const CliRun missing = run_arbor("merge -o " + dir + "/bad.exr " + dir + "/whole.exr");
  EXPECT_EQ(missing.code, 2) << missing.err;
  EXPECT_NE(missing.err.find("whole.exr.state"), std::string::npos) << missing.err;
}

// [render] independent_passes: the EXR says how its variance was estimated, the image differs
// from the default's (passes of one sequence), and its work units merge to it exactly.
TEST(LongRender, IndependentPassesReachTheExrAndMergeExactly) {
  const std::string dir = fresh_folder("independent");
  const std::string sequence = scene_file(dir, 16);
  ASSERT_EQ(run_arbor("render " + sequence + " -o " + dir + "/sequence.exr").code, 0);
  const std::string scene = scene_file(dir, 16, "independent_passes = true\n");
  const CliRun whole = run_arbor("render " + scene + " -o " + dir + "/whole.exr");
  ASSERT_EQ(whole.code, 0) << whole.err;
  const Exr a = read_exr(dir + "/sequence.exr"), b = read_exr(dir + "/whole.exr");
  EXPECT_EQ(a.spec.get_int_attribute("arbor:independent_passes", -1), 0);
  EXPECT_NE(a.spec.get_string_attribute("arbor:variance").find("one sequence (an upper bound"),
            std::string::npos);
  EXPECT_EQ(b.spec.get_int_attribute("arbor:independent_passes", -1), 1);
  EXPECT_NE(b.spec.get_string_attribute("arbor:variance").find("across independent passes"),
            std::string::npos);
  EXPECT_FALSE(same_pixels(a, b));
  const CliRun p0 = run_arbor("render " + scene + " -o " + dir + "/p0.exr --passes 0:2");
  const CliRun p1 = run_arbor("render " + scene + " -o " + dir + "/p1.exr --passes 2:4");
  ASSERT_EQ(p0.code + p1.code, 0) << p0.err << p1.err;
  ASSERT_EQ(run_arbor("merge -o " + dir + "/merged.exr " + dir + "/p1.exr " + dir + "/p0.exr").code,
            0);
  EXPECT_TRUE(same_pixels(read_exr(dir + "/merged.exr"), b));
}

// A film state that is truncated, or not one, is refused naming it (exit 2), and the EXR beside
// it is left as it was.
TEST(LongRender, ABrokenFilmStateIsRefused) {
  const std::string dir = fresh_folder("broken");
  const std::string scene = scene_file(dir, 64);
  ASSERT_EQ(run_arbor("render " + scene + " -o " + dir + "/out.exr --passes 0:4").code, 0);
  const std::string state = dir + "/out.exr.state", bytes = slurp(state);
  const std::string exr = slurp(dir + "/out.exr");
  std::ofstream(state, std::ios::binary) << bytes.substr(0, bytes.size() - 100);
  const CliRun cut = run_arbor("render " + scene + " -o " + dir + "/out.exr --passes 0:4 --resume");
  EXPECT_EQ(cut.code, 2) << cut.err;
  EXPECT_NE(
      cut.err.find(state + ": error: is not a film state arbor can read: its size (" +
                   std::to_string(bytes.size() - 100) + " bytes) is not what its header describes"),
      std::string::npos)
      << cut.err;
  std::ofstream(state, std::ios::binary) << "arbor film state 1\nfingerprint x\nsize -3 4\nend\n";
  const CliRun bad = run_arbor("merge -o " + dir + "/m.exr " + dir + "/out.exr");
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_NE(bad.err.find(state + ": error: is not a film state arbor can read"), std::string::npos)
      << bad.err;
  EXPECT_EQ(slurp(dir + "/out.exr"), exr);
  EXPECT_FALSE(exists(dir + "/m.exr"));
}
