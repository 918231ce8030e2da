// Input files: regular files only, text bounded in size, each read once.
#include "common/input_file.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <map>
#include <mutex>
#include <sys/stat.h>
#include <unistd.h>

#include "common/error.h"

namespace arbor {

std::string file_kind(unsigned mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& what, const std::string& why) {
  throw InputError({path, 0, 0}, what + " " + why);
}

using FileId = std::pair<dev_t, ino_t>;

// Opens `path` for reading without blocking (a FIFO with no writer would block open()), and
// refuses anything but a regular file. Returns the descriptor, its size and its identity.
int open_regular(const std::string& path, const std::string& what, std::uint64_t& size,
                 FileId& id) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    struct stat st;
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
      refuse(path, what, "is " + file_kind(st.st_mode) + ", not a file");
    }
    refuse(path, what,
           err == ENOENT ? std::string("does not exist")
                         : std::string("cannot be opened for reading: ") + std::strerror(err));
  }
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    const mode_t mode = st.st_mode;
    ::close(fd);
    refuse(path, what, "is " + file_kind(mode) + ", not a file");
  }
  // Regular files never block; reads may now wait as usual.
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  size = static_cast<std::uint64_t>(st.st_size);
  id = {st.st_dev, st.st_ino};
  return fd;
}

std::string read_all(int fd, const std::string& path, const std::string& what, std::uint64_t size) {
  std::string text(static_cast<std::size_t>(size), '\0');
  std::size_t got = 0;
  while (got < text.size()) {
    const ssize_t n = ::read(fd, &text[got], text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      refuse(path, what, std::string("cannot be read: ") + std::strerror(err));
    }
    if (n == 0) break;  // shrank while read
    got += static_cast<std::size_t>(n);
  }
  text.resize(got);
  ::close(fd);
  return text;
}

// Digests of the files read in this run by (device, inode), and the bytes of those that
// input_digest read before anything parsed them (small ones only), so that the parser gets the
// very bytes that were fingerprinted and no file is read twice.
constexpr std::uint64_t kKeptBytes = 64ull << 20;
struct Digests {
  std::mutex mutex;
  std::map<FileId, std::uint64_t> by_inode;
  std::map<FileId, std::string> kept;
} g_digests;

bool identity(const std::string& path, FileId& id) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return false;
  id = {st.st_dev, st.st_ino};
  return true;
}

}  // namespace

std::uint64_t fnv1a_bytes(const void* data, std::size_t size, std::uint64_t hash) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= p[i];
    hash *= 0x100000001b3ull;
  }
  return hash;
}

std::string input_file_problem(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    return errno == ENOENT ? "does not exist"
                           : std::string("cannot be opened for reading: ") + std::strerror(errno);
  }
  if (!S_ISREG(st.st_mode)) return "is " + file_kind(st.st_mode) + ", not a file";
  if (::access(path.c_str(), R_OK) != 0)
    return std::string("cannot be opened for reading: ") + std::strerror(errno);
  return "";
}

void check_input_file(const std::string& path, const std::string& what) {
  const std::string problem = input_file_problem(path);
  if (!problem.empty()) refuse(path, what, problem);
}

std::string read_text_input(const std::string& path, const std::string& what,
                            std::uint64_t max_bytes) {
  FileId id;
  if (identity(path, id)) {
    std::lock_guard<std::mutex> lock(g_digests.mutex);
    const auto it = g_digests.kept.find(id);
    if (it != g_digests.kept.end() && it->second.size() <= max_bytes) {
      std::string text = std::move(it->second);
      g_digests.kept.erase(it);
      return text;
    }
  }
  std::uint64_t size = 0;
  const int fd = open_regular(path, what, size, id);
  if (size > max_bytes) {
    ::close(fd);
    refuse(path, what,
           "is " + std::to_string(size) + " bytes; " + what + " files are limited to " +
               std::to_string(max_bytes >> 20) + " MiB");
  }
  std::string text = read_all(fd, path, what, size);
  std::lock_guard<std::mutex> lock(g_digests.mutex);
  g_digests.by_inode[id] = fnv1a_bytes(text.data(), text.size());
  return text;
}

std::uint64_t input_digest(const std::string& path, const std::string& what) {
  FileId id;
  if (identity(path, id)) {
    std::lock_guard<std::mutex> lock(g_digests.mutex);
    const auto it = g_digests.by_inode.find(id);
    if (it != g_digests.by_inode.end()) return it->second;
  }
  std::uint64_t size = 0;
  const int fd = open_regular(path, what, size, id);
  if (size <= kKeptBytes) {
    std::string text = read_all(fd, path, what, size);
    const std::uint64_t hash = fnv1a_bytes(text.data(), text.size());
    std::lock_guard<std::mutex> lock(g_digests.mutex);
    g_digests.by_inode[id] = hash;
    g_digests.kept[id] = std::move(text);
    return hash;
  }
  std::uint64_t hash = 0xcbf29ce484222325ull;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      refuse(path, what, std::string("cannot be read: ") + std::strerror(err));
    }
    if (n == 0) break;
    hash = fnv1a_bytes(buf, static_cast<std::size_t>(n), hash);
  }
  ::close(fd);
  return hash;
}

}  // namespace arbor
