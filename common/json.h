// Writing JSON by hand: the body of a JSON string (quotes and backslashes escaped, control
// characters dropped).
#pragma once

#include <string>

namespace arbor {

inline std::string json_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out;
}

}  // namespace arbor
