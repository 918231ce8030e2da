// Writes a file atomically: to a temporary beside the target, renamed over it only on commit.
// Symlinks are written through (the link's final target is replaced, the link stays); a
// temporary still open when SIGINT or SIGTERM arrives is removed before the process dies.
#pragma once

#include <atomic>
#include <cstdio>
#include <string>
#include <vector>

namespace arbor {

class AtomicFile {
 public:
  // Opens the temporary file; throws RuntimeFailure when it cannot be created.
  explicit AtomicFile(std::string path, bool binary = false);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Writes raw bytes; an error is kept and reported by commit.
  void write(const void* data, size_t size);
  void write(const std::string& s) { write(s.data(), s.size()); }
  // Flushes, syncs to disk, closes and renames over the target; throws RuntimeFailure on any
  // I/O error (a full disk, a file-size limit), leaving the old file as it was.
  void commit();

 private:
  std::string path_;    // as the user named it (for messages)
  std::string target_;  // where it lands: the final target of a symlink chain
  std::string temp_;
  int slot_ = -1;  // in the table of temporaries removed on a signal
  int error_ = 0;  // the first write's errno
  std::FILE* file_ = nullptr;
};

// Where writing `path` lands: `path` itself, or the final target of the symlink chain it names
// (relative link targets resolved against the link's folder). Throws RuntimeFailure on a loop.
std::string resolve_output_path(const std::string& path);

// Removes the temporaries of `path` (after symlinks) that writers on this machine left when they
// were killed (kill -9): every AtomicFile does this for its own target; call it for a file that
// is removed rather than written (a finished render's film state).
void remove_dead_temporaries(const std::string& path);

// True when both paths name the same file: the same device and inode when both exist, else the
// same absolute name after symlinks (a file yet to be written).
bool same_file(const std::string& a, const std::string& b);

// InputError when writing the output `out` (`what` names it in the message) would replace one of
// `inputs` or an earlier output (the same file after symlinks, not merely the same spelling).
void refuse_overwriting(const std::string& what, const std::string& out,
                        const std::vector<std::string>& inputs,
                        const std::vector<std::string>& outputs = {});

// InputError unless `path`, after symlinks, is a regular file or does not exist: writing over a
// device, FIFO, socket or folder (through a symlink, say) is refused, never replaced by a file.
void check_output_target(const std::string& path);

// Makes the folder `path` would be written in, with its parents, when it is missing (as mkdir -p);
// RuntimeFailure when it cannot be made, is not a folder, or is not writable; InputError when
// `path` itself is not a regular file (check_output_target).
void prepare_output_folder(const std::string& path);

// Installs SIGINT and SIGTERM handlers that remove every temporary an AtomicFile holds, then
// end the process by the same signal (exit status 128 + signal). A signal inherited as ignored
// stays ignored. Call once from main.
void remove_temporaries_on_signal();

// While on, the first SIGINT or SIGTERM does not end the process: it is stored in stop_signal()
// (with a note on stderr) for the work to stop at a safe point; a second one ends it as above.
void stop_gracefully_on_signal(bool on);
// 0, or the signal that asked the work to stop.
const std::atomic<int>& stop_signal();

}  // namespace arbor
