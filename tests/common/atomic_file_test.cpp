// AtomicFile: the old file survives a failed write, links are written through, temporaries do
// not outlive a signal, and same_file sees through spellings and links.
#include "common/atomic_file.h"

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <filesystem>
#include <gtest/gtest.h>

#include "common/error.h"
#include "temp_files.h"

namespace arbor {
namespace {

std::string fresh_folder(const std::string& name) {
  return testing::fresh_folder("atomic_" + name);
}
using testing::files_in;

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_plain(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(AtomicFile, CommitReplacesTheFileAndKeepsItsMode) {
  const std::string dir = fresh_folder("commit");
  const std::string path = dir + "/out.txt";
  write_plain(path, "old");
  ASSERT_EQ(chmod(path.c_str(), 0640), 0);
  AtomicFile f(path);
  f.write(std::string("new"));
  f.commit();
  EXPECT_EQ(read(path), "new");
  struct stat st;
  ASSERT_EQ(stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"out.txt"});
}

TEST(AtomicFile, AbandonedWriteLeavesTheOldFileAndNoTemporary) {
  const std::string dir = fresh_folder("abandon");
  const std::string path = dir + "/out.txt";
  write_plain(path, "old");
  {
    AtomicFile f(path);
    f.write(std::string("half"));
  }
  EXPECT_EQ(read(path), "old");
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"out.txt"});
}

// A write that the operating system refuses part-way (here a file-size limit, as a full disk
// would) is reported by commit, and the old file stays as it was.
TEST(AtomicFile, FailedWriteIsReportedAndTheOldFileKept) {
  const std::string dir = fresh_folder("limit");
  const std::string path = dir + "/out.bin";
  write_plain(path, "old");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{4096, 4096};
    setrlimit(RLIMIT_FSIZE, &limit);
    const std::string big(100000, 'x');
    AtomicFile f(path, true);
    f.write(big);
    try {
      f.commit();
    } catch (const RuntimeFailure& e) {
      _exit(std::string(e.what()).find("cannot write " + path) == 0 ? 42 : 1);
    }
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 42) << "the failed write was not reported";
  EXPECT_EQ(read(path), "old");
  EXPECT_EQ(files_in(dir), std::vector<std::string>{"out.bin"});
}

TEST(AtomicFile, TemporariesOfKilledWritersAreRemovedByTheNextWriter) {
  const std::string dir = fresh_folder("stale");
  char host[256] = {};
  ASSERT_EQ(gethostname(host, sizeof host - 1), 0);
  std::string tag;
  for (const char* c = host; *c && *c != '.'; ++c)
    tag += std::isalnum(static_cast<unsigned char>(*c)) || *c == '-' ? *c : '-';
  // A process that has ended (its pid is free), one that lives (our parent), and a writer on
  // another machine sharing the folder.
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);
  const std::string dead = dir + "/.out.exr.tmp-" + tag + "-" + std::to_string(child) + ".exr";
  const std::string alive = dir + "/.out.exr.tmp-" + tag + "-" + std::to_string(getppid()) + ".exr";
  const std::string elsewhere = dir + "/.out.exr.tmp-otherhost-" + std::to_string(child) + ".exr";
  const std::string other_file =
      dir + "/.other.exr.tmp-" + tag + "-" + std::to_string(child) + ".exr";
  for (const std::string& f : {dead, alive, elsewhere, other_file}) std::ofstream(f) << "partial";
  AtomicFile file(dir + "/out.exr");
  file.write("whole");
  file.commit();
  EXPECT_FALSE(std::filesystem::exists(dead));
  EXPECT_TRUE(std::filesystem::exists(alive));
  EXPECT_TRUE(std::filesystem::exists(elsewhere));
  EXPECT_TRUE(std::filesystem::exists(other_file));  // another target's: its own writer's to clean
  EXPECT_EQ(read(dir + "/out.exr"), "whole");
}

TEST(AtomicFile, WritesThroughSymlinks) {
  const std::string dir = fresh_folder("link");
  ASSERT_EQ(mkdir((dir + "/real").c_str(), 0755), 0);
  write_plain(dir + "/real/target.txt", "old");
  ASSERT_EQ(symlink("real/target.txt", (dir + "/link.txt").c_str()), 0);
  ASSERT_EQ(symlink("link.txt", (dir + "/link2.txt").c_str()), 0);
  AtomicFile f(dir + "/link2.txt");
  f.write(std::string("new"));
  f.commit();
  struct stat st;
  ASSERT_EQ(lstat((dir + "/link2.txt").c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode)) << "the link was replaced by a file";
  ASSERT_EQ(lstat((dir + "/link.txt").c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  EXPECT_EQ(read(dir + "/real/target.txt"), "new");
  EXPECT_EQ(files_in(dir + "/real"), std::vector<std::string>{"target.txt"});
  // A dangling link creates its target.
  ASSERT_EQ(symlink("real/new.txt", (dir + "/dangling.txt").c_str()), 0);
  AtomicFile g(dir + "/dangling.txt");
  g.write(std::string("made"));
  g.commit();
  EXPECT_EQ(read(dir + "/real/new.txt"), "made");
  // A loop of links is refused.
  ASSERT_EQ(symlink("loop_b", (dir + "/loop_a").c_str()), 0);
  ASSERT_EQ(symlink("loop_a", (dir + "/loop_b").c_str()), 0);
  EXPECT_THROW(AtomicFile(dir + "/loop_a"), RuntimeFailure);
}

TEST(AtomicFile, SignalRemovesTheTemporary) {
  for (const int sig : {SIGINT, SIGTERM}) {
    const std::string dir = fresh_folder("signal" + std::to_string(sig));
    const std::string path = dir + "/out.exr";
    write_plain(path, "old");
    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      remove_temporaries_on_signal();
      AtomicFile f(path, true);
      f.write(std::string(1000, 'x'));
      std::fflush(nullptr);
      const char c = 'r';
      (void)!::write(ready[1], &c, 1);
      for (;;) pause();
    }
    char c = 0;
    ASSERT_EQ(::read(ready[0], &c, 1), 1);
    EXPECT_EQ(files_in(dir).size(), 2u) << "the temporary should exist while writing";
    kill(child, sig);
    int status = 0;
    waitpid(child, &status, 0);
    close(ready[0]);
    close(ready[1]);
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"out.exr"});
    EXPECT_EQ(read(path), "old");
  }
}

TEST(AtomicFile, SameFileSeesThroughSpellingsAndLinks) {
  const std::string dir = fresh_folder("same");
  write_plain(dir + "/a.exr", "a");
  write_plain(dir + "/b.exr", "b");
  ASSERT_EQ(symlink("a.exr", (dir + "/l.exr").c_str()), 0);
  ASSERT_EQ(link((dir + "/a.exr").c_str(), (dir + "/hard.exr").c_str()), 0);
  EXPECT_TRUE(same_file(dir + "/a.exr", dir + "/./a.exr"));
  EXPECT_TRUE(same_file(dir + "/a.exr", dir + "/../atomic_same/a.exr"));
  EXPECT_TRUE(same_file(dir + "/l.exr", dir + "/a.exr"));
  EXPECT_TRUE(same_file(dir + "/hard.exr", dir + "/a.exr"));
  EXPECT_FALSE(same_file(dir + "/a.exr", dir + "/b.exr"));
  // Files yet to be written: the same when their absolute names are.
  EXPECT_TRUE(same_file(dir + "/new.png", dir + "/./new.png"));
  EXPECT_FALSE(same_file(dir + "/new.png", dir + "/other.png"));
  EXPECT_FALSE(same_file("", dir + "/a.exr"));
}

TEST(AtomicFile, MissingOutputFoldersAreMadeAndFilesInTheWayAreErrors) {
  // Issue 15: `render -o out/x.exr` in a fresh clone, where out/ does not exist yet.
  const std::string dir = ::testing::TempDir() + "arbor_folders_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  EXPECT_NO_THROW(prepare_output_folder(dir + "/a/b/out.png"));
  EXPECT_TRUE(std::filesystem::is_directory(dir + "/a/b"));
  // A file where a folder should be: no folder can be made there.
  { std::ofstream(dir + "/file") << "x"; }
  EXPECT_THROW(prepare_output_folder(dir + "/file/out.png"), RuntimeFailure);
  EXPECT_THROW(prepare_output_folder(dir + "/file/deeper/out.png"), RuntimeFailure);
  EXPECT_NO_THROW(prepare_output_folder(::testing::TempDir() + "out.png"));
  EXPECT_NO_THROW(prepare_output_folder("relative.png"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace arbor
