// Atomic file output: nothing half-written is ever left at the target path.
#include "common/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <unistd.h>

#include "common/error.h"

namespace arbor {

AtomicFile::AtomicFile(std::string path, bool binary) : path_(std::move(path)) {
  temp_ = path_ + ".tmp-" + std::to_string(::getpid());
  file_ = std::fopen(temp_.c_str(), binary ? "wb" : "w");
  if (!file_) {
    throw RuntimeFailure("cannot write " + path_ + ": " + std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(temp_.c_str());
  }
}

void AtomicFile::commit() {
  const bool write_failed = std::ferror(file_) != 0;
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (write_failed || close_failed) {
    const int err = errno;
    std::remove(temp_.c_str());
    throw RuntimeFailure("cannot write " + path_ + ": " + std::strerror(err));
  }
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    std::remove(temp_.c_str());
    throw RuntimeFailure("cannot write " + path_ + ": " + std::strerror(err));
  }
}

}  // namespace arbor
