#include "imaging/output_spec.h"

namespace arbor::imaging {

const char* name_of(PixelType type) { return kPixelTypeNames[static_cast<std::size_t>(type)]; }

std::optional<PixelType> pixel_type_named(std::string_view name) {
  for (std::size_t i = 0; i < kPixelTypeNames.size(); ++i) {
    if (name == kPixelTypeNames[i]) return static_cast<PixelType>(i);
  }
  return std::nullopt;
}

const char* name_of(Aov aov) { return kAovNames[static_cast<std::size_t>(aov)]; }

std::optional<Aov> aov_named(std::string_view name) {
  for (std::size_t i = 0; i < kAovNames.size(); ++i) {
    if (name == kAovNames[i]) return static_cast<Aov>(i);
  }
  return std::nullopt;
}

std::string AovSet::text() const {
  std::string s;
  for (std::size_t i = 0; i < kAovCount; ++i) {
    if (bits_.test(i)) s += (s.empty() ? "" : " ") + std::string(kAovNames[i]);
  }
  return s;
}

}  // namespace arbor::imaging
