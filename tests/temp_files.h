// Files for tests: a fresh folder under the test temporary directory, and what a folder holds.
#pragma once

#include <dirent.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace arbor::testing {

// An empty folder of this name under the test temporary directory (emptied if it exists).
inline std::string fresh_folder(const std::string& name) {
  const std::string dir = ::testing::TempDir() + name;
  const int rc = std::system(("rm -rf '" + dir + "' && mkdir -p '" + dir + "'").c_str());
  EXPECT_EQ(rc, 0) << dir;
  return dir;
}

// The names in a folder, sorted, without "." and "..".
inline std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  if (DIR* d = opendir(dir.c_str())) {
    while (dirent* e = readdir(d)) {
      const std::string n = e->d_name;
      if (n != "." && n != "..") names.push_back(n);
    }
    closedir(d);
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace arbor::testing
