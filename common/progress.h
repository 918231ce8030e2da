// A progress bar with ETA on a terminal; silent when stderr is not a terminal (CI logs).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace arbor {

class Progress {
 public:
  // label: what is being done ("grow"); total: units of work expected (may be revised).
  Progress(std::string label, std::uint64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void set_total(std::uint64_t total) { total_ = total; }
  // Reports that `done` units are complete; redraws at most ~10 times a second.
  void update(std::uint64_t done);
  // Clears the bar (called by the destructor too).
  void finish();
  bool enabled() const { return enabled_; }

 private:
  std::string label_;
  std::uint64_t total_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace arbor
