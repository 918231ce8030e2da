// Formatting of diagnostics and the failure path of ARBOR_CHECK.
#include "common/error.h"

#include <cstdio>
#include <cstdlib>

namespace arbor {

std::string format_diagnostic(const SourceLocation& where, const std::string& severity,
                              const std::string& message) {
  std::string out;
  if (!where.path.empty()) {
    out += where.path;
    if (where.line > 0) {
      out += ":" + std::to_string(where.line);
      if (where.column > 0) out += ":" + std::to_string(where.column);
    }
    out += ": ";
  }
  out += severity + ": " + message;
  return out;
}

InputError::InputError(SourceLocation where, const std::string& message)
    : std::runtime_error(format_diagnostic(where, "error", message)),
      where_(std::move(where)),
      message_(message) {}

void check_failed(const char* expr, const char* file, int line) {
  std::fprintf(stderr, "arbor: internal error: check '%s' failed at %s:%d\n", expr, file, line);
  std::abort();
}

}  // namespace arbor
