// Atomic file output: nothing half-written is ever left at the target path, nor beside it.
#include "common/atomic_file.h"

#include <atomic>
#include <cctype>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <system_error>
#include <sys/stat.h>
#include <unistd.h>

#include "common/error.h"
#include "common/input_file.h"

namespace arbor {

namespace {

// Temporaries open right now, for the signal handler: fixed storage, so removing them needs
// nothing but unlink(), which is async-signal-safe.
// A slot is claimed by one writer, then marked ready once its path is complete: the handler
// only ever unlinks complete paths.
constexpr int kSlots = 32;
char g_temp_paths[kSlots][PATH_MAX];
std::atomic<bool> g_temp_claimed[kSlots];
std::atomic<bool> g_temp_ready[kSlots];

int register_temporary(const std::string& path) {
  if (path.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (g_temp_claimed[i].compare_exchange_strong(expected, true)) {
      std::memcpy(g_temp_paths[i], path.c_str(), path.size() + 1);
      g_temp_ready[i].store(true);
      return i;
    }
  }
  return -1;
}

void release_temporary(int slot) {
  if (slot < 0) return;
  g_temp_ready[slot].store(false);
  g_temp_claimed[slot].store(false);
}

std::atomic<int> g_stop_signal{0};
std::atomic<bool> g_graceful{false};

extern "C" void remove_temporaries_and_die(int sig) {
  // The first signal of a graceful stop only asks; the work stops at its next safe point.
  int none = 0;
  if (g_graceful.load() && g_stop_signal.compare_exchange_strong(none, sig)) {
    static const char msg[] =
        "\narbor: stopping after the running pass (a second Ctrl-C stops at once)\n";
    ssize_t ignored = ::write(2, msg, sizeof msg - 1);
    (void)ignored;
    return;
  }
  for (int i = 0; i < kSlots; ++i) {
    if (g_temp_ready[i].load()) ::unlink(g_temp_paths[i]);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// This machine's name as it goes into temporaries' names ([A-Za-z0-9-] only).
std::string host_tag() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0 || buf[0] == '\0') return "host";
  std::string tag;
  for (const char* c = buf; *c && *c != '.'; ++c)
    tag += std::isalnum(static_cast<unsigned char>(*c)) || *c == '-' ? *c : '-';
  return tag.empty() ? "host" : tag;
}

// A hidden temporary beside `target` that keeps its extension (image writers choose the format
// by it): dir/.NAME.tmp-HOST-PID.EXT. The host and process name the writer, so a later writer of
// the same target can tell a temporary left by a killed process (SIGKILL cannot be caught) from
// one being written now, even on a folder that other machines share.
struct TempName {
  std::string dir, prefix, ext;  // dir/ + prefix + PID + ext
};
TempName temp_name(const std::string& target, const std::string& host) {
  const auto slash = target.find_last_of('/');
  const std::string name = slash == std::string::npos ? target : target.substr(slash + 1);
  const auto dot = name.find_last_of('.');
  return {slash == std::string::npos ? "" : target.substr(0, slash + 1),
          "." + name + ".tmp-" + host + "-",
          dot == std::string::npos || dot == 0 ? "" : name.substr(dot)};
}

std::string temporary_for(const std::string& target) {
  const TempName t = temp_name(target, host_tag());
  return t.dir + t.prefix + std::to_string(::getpid()) + t.ext;
}

// Removes the temporaries of `target` that processes of this machine left when they were killed:
// those whose process no longer exists. Another machine's are left alone.
void remove_stale_temporaries(const std::string& target) {
  const TempName t = temp_name(target, host_tag());
  std::error_code ec;
  for (std::filesystem::directory_iterator it(folder_of(target), ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= t.prefix.size() + t.ext.size() ||
        name.compare(0, t.prefix.size(), t.prefix) != 0 ||
        name.compare(name.size() - t.ext.size(), t.ext.size(), t.ext) != 0) {
      continue;
    }
    const std::string digits =
        name.substr(t.prefix.size(), name.size() - t.prefix.size() - t.ext.size());
    if (digits.empty() || digits.size() > 9 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      continue;
    const long pid = std::stol(digits);
    if (pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) ::unlink(it->path().c_str());
  }
}

[[noreturn]] void fail(const std::string& path, int err) {
  throw RuntimeFailure("cannot write " + path + ": " + std::strerror(err));
}

// The absolute name a path that may not exist yet would have: its folder's real path and its
// own name, after symlinks.
std::string canonical_name(const std::string& path) {
  const std::string target = resolve_output_path(path);
  const auto slash = target.find_last_of('/');
  const std::string name = slash == std::string::npos ? target : target.substr(slash + 1);
  char buf[PATH_MAX];
  if (!::realpath(folder_of(target).c_str(), buf)) return target;
  return std::string(buf) + "/" + name;
}

}  // namespace

std::string resolve_output_path(const std::string& path) {
  std::string at = path;
  for (int hops = 0; hops < 40; ++hops) {
    struct stat st;
    if (::lstat(at.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return at;
    char buf[PATH_MAX];
    const ssize_t n = ::readlink(at.c_str(), buf, sizeof buf - 1);
    if (n < 0) return at;
    buf[n] = '\0';
    const std::string link(buf);
    at = link.front() == '/' ? link : folder_of(at) + "/" + link;
  }
  throw RuntimeFailure("cannot write " + path + ": too many levels of symbolic links");
}

void remove_dead_temporaries(const std::string& path) {
  remove_stale_temporaries(resolve_output_path(path));
}

bool same_file(const std::string& a, const std::string& b) {
  if (a.empty() || b.empty()) return false;
  struct stat sa, sb;
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0) {
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  }
  return canonical_name(a) == canonical_name(b);
}

void check_output_target(const std::string& path) {
  const std::string target = resolve_output_path(path);
  struct stat st;
  if (::stat(target.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return;
  throw InputError({}, "cannot write " + path + ": " + (target == path ? "it" : target) + " is " +
                           file_kind(st.st_mode) +
                           "; an output must be a regular file or not exist yet");
}

void prepare_output_folder(const std::string& path) {
  check_output_target(path);
  const std::string dir = folder_of(resolve_output_path(path));
  struct stat st;
  if (::stat(dir.c_str(), &st) != 0) {
    // A missing folder is made, with its missing parents (as mkdir -p), before anything renders.
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) {
      throw RuntimeFailure("cannot write " + path + ": cannot create its folder " + dir + ": " +
                           error.message());
    }
  } else if (!S_ISDIR(st.st_mode)) {
    throw RuntimeFailure("cannot write " + path + ": " + dir + " is not a folder");
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    throw RuntimeFailure("cannot write " + path + ": its folder " + dir + " is not writable");
  }
}

void stop_gracefully_on_signal(bool on) { g_graceful.store(on); }

const std::atomic<int>& stop_signal() { return g_stop_signal; }

void remove_temporaries_on_signal() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = remove_temporaries_and_die;
  sigemptyset(&sa.sa_mask);
  for (const int sig : {SIGINT, SIGTERM}) {
    // A signal the parent set to be ignored (nohup, a background job) stays ignored.
    struct sigaction old;
    if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaction(sig, &sa, nullptr);
  }
}

AtomicFile::AtomicFile(std::string path, bool binary)
    : path_(std::move(path)), target_(resolve_output_path(path_)) {
  check_output_target(path_);
  remove_stale_temporaries(target_);
  temp_ = temporary_for(target_);
  slot_ = register_temporary(temp_);
  file_ = std::fopen(temp_.c_str(), binary ? "wb" : "w");
  if (!file_) {
    const int err = errno;
    release_temporary(slot_);
    fail(path_, err);
  }
  // Replacing a file keeps its permissions.
  struct stat st;
  if (::stat(target_.c_str(), &st) == 0) ::fchmod(::fileno(file_), st.st_mode & 07777);
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(temp_.c_str());
  }
  release_temporary(slot_);
}

void AtomicFile::write(const void* data, size_t size) {
  if (error_ == 0 && size > 0 && std::fwrite(data, 1, size, file_) != size)
    error_ = errno ? errno : EIO;
}

void AtomicFile::commit() {
  int err = error_;
  if (err == 0 && (std::fflush(file_) != 0 || std::ferror(file_) != 0)) err = errno ? errno : EIO;
  if (err == 0 && ::fsync(::fileno(file_)) != 0) err = errno;
  if (std::fclose(file_) != 0 && err == 0) err = errno;
  file_ = nullptr;
  if (err == 0 && std::rename(temp_.c_str(), target_.c_str()) != 0) err = errno;
  if (err != 0) {
    std::remove(temp_.c_str());
    release_temporary(slot_);
    slot_ = -1;
    fail(path_, err);
  }
  release_temporary(slot_);
  slot_ = -1;
}

void refuse_overwriting(const std::string& what, const std::string& out,
                        const std::vector<std::string>& inputs,
                        const std::vector<std::string>& outputs) {
  for (const std::string& in : inputs) {
    if (same_file(out, in))
      throw InputError({}, what + " " + out + " would overwrite the input " + in);
  }
  for (const std::string& other : outputs) {
    if (same_file(out, other))
      throw InputError({}, what + " " + out + " is also written as " + other);
  }
}

}  // namespace arbor
