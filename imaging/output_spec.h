// What an image output holds and how it is tagged: the one output specification that the scene
// reader fills, the film state keeps, and the EXR and PNG writers and merge read. Each value's
// names and default are stated here, once.
#pragma once

#include <array>
#include <bitset>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "common/error.h"

namespace arbor::imaging {

// The type of the colour channels (depth, variance, ids and the treemaker AOVs are always float).
enum class PixelType { Half, Float };
inline constexpr std::array<const char*, 2> kPixelTypeNames = {"half", "float"};
const char* name_of(PixelType type);
std::optional<PixelType> pixel_type_named(std::string_view name);

// The AOVs an EXR can carry besides RGBA (docs/outputs.md), in the order their channels are
// written.
enum class Aov {
  Albedo,
  Normal,
  Depth,
  Variance,
  Samples,
  ObjectId,
  MaterialId,
  CryptoObject,
  CryptoMaterial,
  Treemaker
};
inline constexpr std::size_t kAovCount = 10;
inline constexpr std::array<const char*, kAovCount> kAovNames = {
    "albedo",    "normal",      "depth",         "variance",        "samples",
    "object_id", "material_id", "crypto_object", "crypto_material", "treemaker"};
const char* name_of(Aov aov);
std::optional<Aov> aov_named(std::string_view name);

// A set of AOVs.
class AovSet {
 public:
  bool has(Aov a) const { return bits_.test(static_cast<std::size_t>(a)); }
  void add(Aov a) { bits_.set(static_cast<std::size_t>(a)); }
  bool empty() const { return bits_.none(); }
  // Whether any needs the compositing ids (object_id, material_id, crypto_*).
  bool wants_ids() const {
    return has(Aov::ObjectId) || has(Aov::MaterialId) || has(Aov::CryptoObject) ||
           has(Aov::CryptoMaterial);
  }
  // The names, space-separated, in channel order ("" for none).
  std::string text() const;
  bool operator==(const AovSet& o) const { return bits_ == o.bits_; }
  bool operator!=(const AovSet& o) const { return bits_ != o.bits_; }

 private:
  std::bitset<kAovCount> bits_;
};

struct OutputSpec {
  // Linear Rec.709 by default: what EXR readers assume of an untagged or unread file (Blender's
  // "Linear", Nuke's "linear", OIIO's "Linear"), so the EXR opens right without setting anything;
  // "ACEScg" on request (tagged, for ACES pipelines).
  std::string colorspace = "Linear Rec.709 (sRGB)";
  std::string display = "sRGB";             // the PNG's OCIO display
  std::string view = "ACES 1.0 SDR-video";  // and view
  PixelType pixel_type = PixelType::Half;
  AovSet aovs;
  bool transparent_sky = false;  // camera rays that escape add nothing: alpha 0, premultiplied
  bool wants_ids() const { return aovs.wants_ids(); }
};

// Where the output's names were given (scene keys), for errors found later by the OCIO config;
// empty: the command line.
struct OutputKeys {
  SourceLocation colorspace, display, view;
};

}  // namespace arbor::imaging
