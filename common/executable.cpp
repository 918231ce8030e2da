// The executable's own path, from the kernel's /proc/self/exe link.
#include "common/executable.h"

#include <climits>
#include <unistd.h>

namespace arbor {

std::string executable_path() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return {};
  return std::string(buf, static_cast<std::size_t>(n));
}

std::string installed_data_path(const std::string& relative) {
  const std::string exe = executable_path();
  const auto slash = exe.find_last_of('/');
  if (slash == std::string::npos) return relative;
  return exe.substr(0, slash) + "/../share/arbor/" + relative;
}

}  // namespace arbor
