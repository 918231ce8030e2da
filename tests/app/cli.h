// Runs the arbor binary for end-to-end tests and captures its exit code and output.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

namespace {

struct CliRun {
  int code = -1;   // the exit code; -1 when the process died
  int signal = 0;  // the signal that ended it, if one did
  std::string out, err;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `arbor ARGS` through /bin/sh, after `shell_prefix` (e.g. "ulimit -f 8;"), started by
// `launcher` (e.g. "exec timeout 60" to bound it).
inline CliRun run_arbor_with(const std::string& shell_prefix, const std::string& args,
                             const std::string& launcher = "exec") {
  // ctest runs tests as parallel processes: name the capture files after the test.
  const std::string stem = ::testing::TempDir() + "cli_" +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const std::string out = stem + ".out", err = stem + ".err";
  const std::string cmd = shell_prefix + " " + launcher + " " + std::string(ARBOR_BINARY) + " " +
                          args + " >" + out + " 2>" + err;
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

inline CliRun run_arbor(const std::string& args) { return run_arbor_with("", args); }

inline std::string species(const char* name) {
  return std::string(ARBOR_SOURCE_DIR) + "/species/" + name;
}

inline std::string write_temp(const char* name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// Writes a w x h EXR of constant RGB, optionally with variance channels.
inline std::string write_exr(const char* name, int w, int h, float value, float variance) {
  const std::string path = ::testing::TempDir() + name;
  const int nch = variance >= 0 ? 6 : 3;
  OIIO::ImageSpec spec(w, h, nch, OIIO::TypeDesc::FLOAT);
  if (nch == 6) spec.channelnames = {"R", "G", "B", "variance.R", "variance.G", "variance.B"};
  OIIO::ImageBuf buf(spec);
  const float px[6] = {value, value, value, variance, variance, variance};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) buf.setpixel(x, y, px);
  EXPECT_TRUE(buf.write(path));
  return path;
}

inline bool exists(const std::string& path) { return std::ifstream(path).good(); }

}  // namespace
