#include "common/parse.h"

#include <charconv>

#include "common/error.h"

namespace arbor {

std::vector<int> parse_integers(const std::string& text, char sep, std::size_t count,
                                const char* option, const char* form) {
  std::vector<int> v;
  const char* p = text.data();
  const char* end = text.data() + text.size();
  while (v.size() < count) {
    int x = 0;
    const auto [next, ec] = std::from_chars(p, end, x);
    if (ec != std::errc() || x < 0) break;
    v.push_back(x);
    p = next;
    if (v.size() < count) {
      if (p == end || *p != sep) break;
      ++p;
    }
  }
  if (v.size() != count || p != end) {
    throw InputError({}, std::string(option) + " '" + text + "' is not of the form " + form);
  }
  return v;
}

}  // namespace arbor
