// The one error type for bad input (carries file, line, column) and the invariant check macro.
#pragma once

#include <stdexcept>
#include <string>

namespace arbor {

// Where in an input file something is; line and column are 1-based, 0 when unknown.
struct SourceLocation {
  std::string path;
  int line = 0;
  int column = 0;
};

// Bad input: a malformed file, an out-of-range value, an unknown key. The app maps it to exit 2.
// what() is "path:line:col: error: message" (parts without a value are left out).
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& message);
  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

// Formats "path:line:col: error: message" the way every arbor diagnostic is printed.
std::string format_diagnostic(const SourceLocation& where, const std::string& severity,
                              const std::string& message);

// The work failed for a reason that is not the input's fault (I/O, limits). Exit code 1.
class RuntimeFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A broken internal invariant: a bug in arbor, never the user's input.
[[noreturn]] void check_failed(const char* expr, const char* file, int line);

}  // namespace arbor

// Checked in every build; use for cheap invariants.
#define ARBOR_CHECK(expr) ((expr) ? (void)0 : ::arbor::check_failed(#expr, __FILE__, __LINE__))
