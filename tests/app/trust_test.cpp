// Nothing destroyed, nothing silently wrong, no crash or hang (issue 25), through the command line:
// outputs that are devices or FIFOs, inputs that are FIFOs, folders or too big, deep TOML keys,
// damaged or forged film states, work units without -o, the fingerprint of a path spelt two
// ways, a dead writer's temporary of the film state, and plans too large to list.
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "temp_files.h"
using arbor::testing::files_in;
using arbor::testing::fresh_folder;

#include "app/cli.h"

namespace {

// Every run here is bounded: a hang shows as exit 124 instead of stalling the suite.
CliRun bounded(const std::string& args) {
  return run_arbor_with("", args, "exec timeout -s KILL 60");
}

// A tiny scene of passes of 4 samples.
std::string tiny_scene(const std::string& dir, int spp, const std::string& tree = "") {
  const std::string path = dir + "/scene.toml";
  std::ofstream(path)
      << "[render]\nwidth = 16\nheight = 12\nspp = " << spp
      << "\npass_spp = 4\nseed = 5\nmax_depth = 3\n"
      << "[camera]\nposition = [10.0, -14.0, 3.0]\nlook_at = [0.0, 0.0, 4.0]\n"
      << (tree.empty() ? "[[tree]]\nspecies = \"" + std::string(ARBOR_SOURCE_DIR) +
                             "/species/lsystem_weed.lsys\"\n"
                       : tree)
      << "[output]\nexr = \"own.exr\"\naovs = [\"variance\"]\npixel_type = \"float\"\n";
  return path;
}

bool is_char_device(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}
bool is_fifo(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
}

// This machine's name as arbor puts it in temporaries (common/atomic_file.cpp).
std::string host_tag() {
  char buf[256] = {};
  ::gethostname(buf, sizeof buf - 1);
  std::string tag;
  for (const char* c = buf; *c && *c != '.'; ++c)
    tag += std::isalnum(static_cast<unsigned char>(*c)) || *c == '-' ? *c : '-';
  return tag.empty() ? "host" : tag;
}

}  // namespace

// An output whose final target is a device or a FIFO is refused, and the device stays a device
// (as root, a link to /dev/full once turned /dev/full into a file).
TEST(Trust, OutputsThatAreDevicesOrFifosAreRefused) {
  const std::string dir = fresh_folder("trust_devices");
  std::vector<std::string> targets;
  // A device of our own (as /dev/full is: char 1,7): only root may make one; CI runs as root.
  if (::mknod((dir + "/devfull").c_str(), S_IFCHR | 0644, makedev(1, 7)) == 0)
    targets.push_back("devfull");
  ASSERT_EQ(::mkfifo((dir + "/fifo").c_str(), 0644), 0);
  targets.push_back("fifo");
  const std::string scene = tiny_scene(dir, 4);
  const std::string a = write_exr("trust_a.exr", 4, 4, 0.5f, -1.0f),
                    b = write_exr("trust_b.exr", 4, 4, 0.25f, -1.0f);
  for (const std::string& target : targets) {
    for (const char* link : {"full.obj", "full.exr", "full.png"}) {
      std::remove((dir + "/" + link).c_str());
      ASSERT_EQ(::symlink(target.c_str(), (dir + "/" + link).c_str()), 0);
    }
    const CliRun grow =
        bounded("grow " + species("lsystem_weed.lsys") + " -o " + dir + "/full.obj");
    EXPECT_EQ(grow.code, 2) << grow.err;
    EXPECT_NE(grow.err.find("arbor: error: cannot write " + dir + "/full.obj: " + dir + "/" +
                            target + " is a "),
              std::string::npos)
        << grow.err;
    const CliRun render = bounded("render " + scene + " -o " + dir + "/full.exr");
    EXPECT_EQ(render.code, 2) << render.err;
    EXPECT_NE(render.err.find("an output must be a regular file"), std::string::npos) << render.err;
    const CliRun heat = bounded("compare " + a + " " + b + " --heatmap " + dir + "/full.png");
    EXPECT_EQ(heat.code, 2) << heat.err;
    EXPECT_NE(heat.err.find("an output must be a regular file"), std::string::npos) << heat.err;
  }
  if (targets.front() == "devfull") {
    EXPECT_TRUE(is_char_device(dir + "/devfull"));
  }
  EXPECT_TRUE(is_fifo(dir + "/fifo"));
  EXPECT_FALSE(exists(dir + "/own.exr"));
}

// FIFOs as inputs are refused at once, naming them: no read ever blocks on one.
TEST(Trust, FifoInputsAreRefusedNotWaitedOn) {
  const std::string dir = fresh_folder("trust_fifos");
  for (const char* name : {"f.skel", "f.toml", "f.exr", "f.obj"})
    ASSERT_EQ(::mkfifo((dir + "/" + name).c_str(), 0644), 0);
  const CliRun grow = bounded("grow " + dir + "/f.skel --stats");
  EXPECT_EQ(grow.code, 2) << grow.err;
  EXPECT_NE(grow.err.find(dir + "/f.skel: error: species is a FIFO (named pipe), not a file"),
            std::string::npos)
      << grow.err;

  const CliRun scene = bounded("render " + dir + "/f.toml -o " + dir + "/o.exr");
  EXPECT_EQ(scene.code, 2) << scene.err;
  EXPECT_NE(scene.err.find(dir + "/f.toml: error: scene is a FIFO"), std::string::npos)
      << scene.err;

  // As the species and as the mesh of a scene: the error is at the key that names it.
  const std::string s1 = tiny_scene(dir, 4, "[[tree]]\nspecies = \"f.skel\"\n");
  const CliRun species_fifo = bounded("render " + s1 + " -o " + dir + "/o.exr");
  EXPECT_EQ(species_fifo.code, 2) << species_fifo.err;
  EXPECT_NE(species_fifo.err.find(s1 + ":12:11: error: tree.species " + dir + "/f.skel is a FIFO"),
            std::string::npos)
      << species_fifo.err;
  const std::string s2 = tiny_scene(dir, 4, "[[mesh]]\npath = \"f.obj\"\n");
  const CliRun mesh_fifo = bounded("render " + s2 + " -o " + dir + "/o.exr");
  EXPECT_EQ(mesh_fifo.code, 2) << mesh_fifo.err;
  EXPECT_NE(mesh_fifo.err.find(s2 + ":12:8: error: mesh.path " + dir + "/f.obj is a FIFO"),
            std::string::npos)
      << mesh_fifo.err;

  const std::string b = write_exr("trust_fifo_b.exr", 4, 4, 0.25f, -1.0f);
  const CliRun compare = bounded("compare " + dir + "/f.exr " + b);
  EXPECT_EQ(compare.code, 2) << compare.err;
  EXPECT_NE(compare.err.find(dir + "/f.exr: error: image is a FIFO"), std::string::npos)
      << compare.err;

  // A FIFO as the film state of a resume and of a merge part.
  const std::string scene3 = tiny_scene(dir, 8);
  ASSERT_EQ(bounded("render " + scene3 + " -o " + dir + "/part.exr --passes 0:1").code, 0);
  std::remove((dir + "/part.exr.state").c_str());
  ASSERT_EQ(::mkfifo((dir + "/part.exr.state").c_str(), 0644), 0);
  const CliRun resume =
      bounded("render " + scene3 + " -o " + dir + "/part.exr --passes 0:1 --resume");
  EXPECT_EQ(resume.code, 2) << resume.err;
  EXPECT_NE(resume.err.find(dir + "/part.exr.state: error: film state is a FIFO"),
            std::string::npos)
      << resume.err;
  const CliRun merge = bounded("merge -o " + dir + "/m.exr " + dir + "/part.exr");
  EXPECT_EQ(merge.code, 2) << merge.err;
  EXPECT_NE(merge.err.find("film state is a FIFO"), std::string::npos) << merge.err;
  EXPECT_FALSE(exists(dir + "/m.exr"));
}

// A folder where a file is expected names the folder and the scene key that referenced it.
TEST(Trust, FoldersAsInputsNameTheKeyThatReferencedThem) {
  const std::string dir = fresh_folder("trust_folders");
  ASSERT_EQ(::mkdir((dir + "/tree.toml").c_str(), 0755), 0);
  ASSERT_EQ(::mkdir((dir + "/bump.png").c_str(), 0755), 0);
  const CliRun grow = bounded("grow " + dir + "/tree.toml --stats");
  EXPECT_EQ(grow.code, 2) << grow.err;
  EXPECT_NE(grow.err.find(dir + "/tree.toml: error: species is a folder, not a file"),
            std::string::npos)
      << grow.err;
  const std::string s = tiny_scene(dir, 4,
                                   "[[tree]]\nspecies = \"" + species("quaking_aspen.toml") +
                                       "\"\n[tree.bark]\nbump_map = \"bump.png\"\n");
  const CliRun render = bounded("render " + s + " -o " + dir + "/o.exr");
  EXPECT_EQ(render.code, 2) << render.err;
  EXPECT_NE(render.err.find(s + ":14:12: error: tree.bark.bump_map " + dir +
                            "/bump.png is a folder, not a file"),
            std::string::npos)
      << render.err;
  // A missing one likewise.
  const std::string m = tiny_scene(dir, 4, "[[tree]]\nspecies = \"nowhere.toml\"\n");
  const CliRun missing = bounded("render " + m + " -o " + dir + "/o.exr");
  EXPECT_EQ(missing.code, 2) << missing.err;
  EXPECT_NE(
      missing.err.find(m + ":12:11: error: tree.species " + dir + "/nowhere.toml does not exist"),
      std::string::npos)
      << missing.err;
  EXPECT_FALSE(exists(dir + "/o.exr"));
}

// A dotted key of 50,000 parts is refused at its position in scene and species files (it once
// overflowed the stack); a species file over the size bound is refused without being read.
TEST(Trust, DeepKeysAndHugeFilesAreRefused) {
  const std::string dir = fresh_folder("trust_keys");
  std::string key = "a";
  for (int i = 1; i < 50000; ++i) key += ".a";
  std::ofstream(dir + "/deep.toml") << "model = \"weber-penn\"\n[" << key << "]\n";
  const CliRun species_run = bounded("grow " + dir + "/deep.toml --stats");
  EXPECT_EQ(species_run.code, 2) << species_run.err;
  EXPECT_EQ(species_run.signal, 0);
  EXPECT_NE(species_run.err.find(dir + "/deep.toml:2:1: error: a key of more than 64 dotted parts"),
            std::string::npos)
      << species_run.err;
  std::ofstream(dir + "/scene.toml") << "[render]\nwidth = 8\n" << key << " = 1\n";
  const CliRun scene_run = bounded("render " + dir + "/scene.toml -o " + dir + "/o.exr");
  EXPECT_EQ(scene_run.code, 2) << scene_run.err;
  EXPECT_NE(scene_run.err.find(dir + "/scene.toml:3:1: error: a key of more than 64 dotted parts"),
            std::string::npos)
      << scene_run.err;
  // 64 parts is still read (and then refused as an unknown key, by the reader).
  std::string ok = "a";
  for (int i = 1; i < 64; ++i) ok += ".a";
  std::ofstream(dir + "/ok.toml") << "model = \"weber-penn\"\n[" << ok << "]\n";
  const CliRun ok_run = bounded("grow " + dir + "/ok.toml --stats");
  EXPECT_NE(ok_run.err.find("unknown key 'a'"), std::string::npos) << ok_run.err;

  {
    std::ofstream big(dir + "/big.toml");
    big << "model = \"weber-penn\"\n";
    const std::string comment = "# " + std::string(1021, 'x') + "\n";
    for (int i = 0; i < 17 * 1024; ++i) big << comment;
  }
  const CliRun big = bounded("grow " + dir + "/big.toml --stats");
  EXPECT_EQ(big.code, 2) << big.err;
  EXPECT_NE(
      big.err.find(
          dir + "/big.toml: error: species is 17825813 bytes; species files are limited to 16 MiB"),
      std::string::npos)
      << big.err;
  ASSERT_EQ(::symlink("/dev/zero", (dir + "/zero.toml").c_str()), 0);
  const CliRun zero = bounded("grow " + dir + "/zero.toml --stats");
  EXPECT_EQ(zero.code, 2) << zero.err;
  EXPECT_NE(zero.err.find(dir + "/zero.toml: error: species is a device, not a file"),
            std::string::npos)
      << zero.err;
}

// Flipped bytes, a NaN or a forged size in the film state: resume and merge refuse it with exit
// 2 naming it, and write nothing.
TEST(Trust, DamagedOrForgedFilmStatesAreRefused) {
  const std::string dir = fresh_folder("trust_state");
  const std::string scene = tiny_scene(dir, 32);
  ASSERT_EQ(bounded("render " + scene + " -o " + dir + "/p.exr --passes 0:4").code, 0);
  const std::string state = dir + "/p.exr.state";
  const std::string good = slurp(state), exr = slurp(dir + "/p.exr");
  const std::size_t header_end = good.find("\nend\n") + 5;
  ASSERT_LT(header_end + 2000, good.size());

  auto expect_refused = [&](const std::string& bytes, const std::string& why) {
    std::ofstream(state, std::ios::binary) << bytes;
    const CliRun resume =
        bounded("render " + scene + " -o " + dir + "/p.exr --passes 0:4 --resume");
    EXPECT_EQ(resume.code, 2) << why << ": " << resume.err;
    EXPECT_NE(resume.err.find(state + ": error: is not a film state arbor can read"),
              std::string::npos)
        << resume.err;
    const CliRun merge = bounded("merge -o " + dir + "/m.exr " + dir + "/p.exr");
    EXPECT_EQ(merge.code, 2) << why << ": " << merge.err;
    EXPECT_NE(merge.err.find(state + ": error: is not a film state arbor can read"),
              std::string::npos)
        << merge.err;
    EXPECT_FALSE(exists(dir + "/m.exr"));
    EXPECT_EQ(slurp(dir + "/p.exr"), exr);
  };
  // 64 bytes of the sums, each with one bit flipped.
  std::string flipped = good;
  for (std::size_t i = 0; i < 64; ++i) flipped[header_end + 1000 + i] ^= 0x10;
  expect_refused(flipped, "flipped bytes");
  // One flipped bit anywhere in the arrays is enough.
  std::string one = good;
  one[good.size() - 100] ^= 0x01;
  expect_refused(one, "one flipped bit");
  // A forged size: 100000x100000 would be 10^10 pixels.
  std::string forged = good;
  const std::size_t size_at = forged.find("\nsize ");
  forged.replace(size_at, forged.find('\n', size_at + 1) - size_at, "\nsize 100000 100000");
  expect_refused(forged, "forged size");
  // Forged extras within the bound: its arrays would not fit the file.
  std::string extras = good;
  const std::size_t extras_at = extras.find("\nextras ");
  extras.replace(extras_at, extras.find('\n', extras_at + 1) - extras_at, "\nextras 64 1 1");
  expect_refused(extras, "forged extras");
  // The intact state still resumes.
  std::ofstream(state, std::ios::binary) << good;
  EXPECT_EQ(bounded("render " + scene + " -o " + dir + "/p.exr --passes 0:4 --resume").code, 0);
}

// A work unit needs its own -o: it never overwrites the scene's outputs; an empty --crop is
// refused.
TEST(Trust, WorkUnitsNeedTheirOwnOutput) {
  const std::string dir = fresh_folder("trust_units");
  const std::string scene = tiny_scene(dir, 8);
  for (const char* unit :
       {"--crop 0,0,8,8", "--passes 0:1", "--crop ''", "--passes ''", "--crop '' -o x.exr"}) {
    const CliRun r = bounded("render " + scene + " " + unit);
    EXPECT_EQ(r.code, 2) << unit << ": " << r.err;
    EXPECT_EQ(r.err.rfind("arbor: error: ", 0), 0u) << r.err;
  }
  EXPECT_FALSE(exists(dir + "/own.exr"));
}

// The fingerprint does not depend on how the scene's path is spelt: a render of scene.toml
// resumes as ./scene.toml, and its parts merge.
TEST(Trust, TheFingerprintIgnoresHowAPathIsSpelt) {
  const std::string dir = fresh_folder("trust_spelling");
  tiny_scene(dir, 32);
  const CliRun first =
      run_arbor_with("cd " + dir + " &&", "render scene.toml -o out.exr --time-limit 1e-9");
  ASSERT_EQ(first.code, 0) << first.err;
  ASSERT_TRUE(exists(dir + "/out.exr.state"));
  const CliRun resume =
      run_arbor_with("cd " + dir + " &&", "render ./scene.toml -o out.exr --resume");
  EXPECT_EQ(resume.code, 0) << resume.err;
  EXPECT_FALSE(exists(dir + "/out.exr.state"));
  ASSERT_EQ(run_arbor_with("cd " + dir + " &&", "render scene.toml -o a.exr --passes 0:4").code, 0);
  ASSERT_EQ(run_arbor_with("cd " + dir + " &&", "render ./scene.toml -o b.exr --passes 4:8").code,
            0);
  ASSERT_EQ(run_arbor_with("cd /tmp &&", "render " + dir + "/../" + dir.substr(dir.rfind('/') + 1) +
                                             "/scene.toml -o " + dir + "/c.exr --passes 0:4")
                .code,
            0);
  const CliRun merge = run_arbor_with("cd " + dir + " &&", "merge -o m.exr a.exr b.exr");
  EXPECT_EQ(merge.code, 0) << merge.err;
  const CliRun merge2 = run_arbor_with("cd " + dir + " &&", "merge -o m2.exr c.exr b.exr");
  EXPECT_EQ(merge2.code, 0) << merge2.err;
}

// A temporary of the film state left by a writer killed with -9 is removed when the render
// finishes (it never writes the state again), not left beside the finished image.
TEST(Trust, AFinishedRenderRemovesDeadTemporariesOfItsState) {
  const std::string dir = fresh_folder("trust_temporaries");
  const std::string scene = tiny_scene(dir, 16);
  ASSERT_EQ(bounded("render " + scene + " -o " + dir + "/out.exr --time-limit 1e-9").code, 0);
  // pid 999999999 is beyond any pid_max: its process is dead.
  const std::string dead = dir + "/.out.exr.state.tmp-" + host_tag() + "-999999999.state";
  std::ofstream(dead) << "half a state";
  ASSERT_TRUE(exists(dead));
  ASSERT_EQ(bounded("render " + scene + " -o " + dir + "/out.exr --resume").code, 0);
  EXPECT_EQ(files_in(dir), (std::vector<std::string>{"out.exr", "scene.toml"}));
}

// A plan too large to list is refused before it is made.
TEST(Trust, HugePlansAreRefused) {
  const std::string dir = fresh_folder("trust_plan");
  const std::string scene = tiny_scene(dir, 64);
  const CliRun r = bounded("plan " + scene +
                           " --tiles 4096x4096 --width 16384 --height 16384 --pass-groups 16 -o " +
                           dir + "/x.exr");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("a plan has at most 100000 units and 4096 parts per merge"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(
      bounded("plan " + scene + " --tiles 64x64 --width 64 --height 64 -o " + dir + "/x.exr").code,
      0);
}

// A forest of more variants than memory holds is refused once its first variant is grown (each
// variant's geometry counts), not grown for minutes into "out of memory".
TEST(Trust, AForestOfTooManyVariantsIsRefusedUpFront) {
  const std::string dir = fresh_folder("trust_variants");
  const std::string scene = tiny_scene(dir, 4,
                                       "[[forest]]\nspecies = \"" + species("quaking_aspen.toml") +
                                           "\"\ncount = 20000\nvariants = 10000\n");
  const CliRun r =
      run_arbor_with("ulimit -v 16000000;", "render " + scene + " -o " + dir + "/o.exr",
                     "exec timeout -s KILL 60");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(scene + ":11:1: error: the forest's 10000 variants would need about"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(exists(dir + "/o.exr"));
}
