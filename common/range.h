// A closed interval of allowed values and its unit, stated once where the value is defined
// (e.g. generator/species.h's look ranges) and checked by every reader of that value.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

namespace arbor {

// A number as a person writes it in a message: "0.5", "1048576", "1e+09", "-0.1" (whole numbers
// below 10⁷ in full, others by printf's %g).
inline std::string short_number(double v) {
  char buf[32];
  const bool whole = v > -1e7 && v < 1e7 && v == std::floor(v);
  std::snprintf(buf, sizeof buf, whole ? "%.0f" : "%g", v);
  return buf;
}

struct Range {
  double lo = 0.0, hi = 0.0;
  std::string_view unit;  // "" for a pure number

  constexpr bool contains(double v) const { return v >= lo && v <= hi; }  // false for NaN

  // "[0, 90] degrees": the bounds as short as they print exactly enough for a message.
  std::string text() const {
    const std::string bounds = "[" + short_number(lo) + ", " + short_number(hi) + "]";
    return unit.empty() ? bounds : bounds + " " + std::string(unit);
  }
};

}  // namespace arbor
