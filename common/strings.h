// Small string helpers.
#pragma once

#include <string>
#include <string_view>

namespace arbor {

inline bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace arbor
