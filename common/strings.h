// Small string helpers.
#pragma once

#include <string>
#include <string_view>

namespace arbor {

inline bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The last component of a path ("a/b/c.obj" → "c.obj").
inline std::string file_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// "species/quaking_aspen.toml" → "quaking_aspen": what the compositing ids call a file's things.
inline std::string file_stem(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find_last_of('.');
  if (dot != std::string::npos && dot > 0) name.erase(dot);
  for (char& c : name) {
    if (static_cast<unsigned char>(c) < 0x20) c = '_';  // names travel one to a line, tab-separated
  }
  return name;
}

}  // namespace arbor
