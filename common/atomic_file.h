// Writes a file atomically: to a temporary beside the target, renamed over it only on commit.
#pragma once

#include <cstdio>
#include <string>

namespace arbor {

class AtomicFile {
 public:
  // Opens the temporary file; throws RuntimeFailure when it cannot be created.
  explicit AtomicFile(std::string path, bool binary = false);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::FILE* get() { return file_; }
  // Writes raw bytes; errors are detected at commit.
  void write(const void* data, size_t size) { std::fwrite(data, 1, size, file_); }
  void write(const std::string& s) { write(s.data(), s.size()); }
  // Flushes, closes and renames over the target; throws RuntimeFailure on any I/O error.
  void commit();

 private:
  std::string path_;
  std::string temp_;
  std::FILE* file_ = nullptr;
};

}  // namespace arbor
