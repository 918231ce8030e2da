// Colour management: one OpenColorIO config per run, the conversions the renderer needs from it,
// and where arbor finds its config.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "imaging/output_spec.h"

namespace arbor::imaging {

// Converts a colour in place (thread-safe).
using ColorTransform = std::function<void(float rgb[3])>;

class ColorPipeline {
 public:
  // Loads the config; InputError naming the file when OCIO cannot use it.
  explicit ColorPipeline(std::string config_path);
  ~ColorPipeline();
  ColorPipeline(const ColorPipeline&) = delete;
  ColorPipeline& operator=(const ColorPipeline&) = delete;

  const std::string& config_path() const { return config_path_; }

  // InputError at the scene key when the output's colour space, display or view is not in the
  // config, listing what the config has.
  void check(const OutputSpec& output, const OutputKeys& where = {}) const;
  // scene_linear → `colorspace`, per pixel.
  ColorTransform to_output(const std::string& colorspace) const;
  // `colorspace` → a display's view (display-referred, as the PNG is written), per pixel.
  ColorTransform to_display(const std::string& colorspace, const std::string& display,
                            const std::string& view) const;
  // InputError unless `display` is a display of the config and `view` one of its views, listing
  // what the config has; `display_where`/`view_where` locate the names (a scene key, or none).
  void check_display_view(const std::string& display, const std::string& view,
                          const SourceLocation& display_where,
                          const SourceLocation& view_where) const;
  // CIE XYZ (D65) → scene_linear, for the sky models. Found, in this order: a scene-referred
  // colour space named or aliased "Linear CIE-XYZ-D65" (arbor's), the cie_xyz_d65_interchange
  // role, "XYZ" (Blender's role and space), "Linear CIE-XYZ D65" or "lin_ciexyzd65_scene"; the
  // aces_interchange role, reached from XYZ by the ACES primaries (Bradford-adapted); the
  // scene_linear space's chromaticities when it is a space arbor knows (Rec.709, ACEScg,
  // ACES2065-1, Rec.2020, Display P3 linear). Each way is checked (linear, D65 white to neutral);
  // InputError naming every way tried and why it failed when none works.
  ColorTransform xyz_to_scene_linear() const;
  // Which way xyz_to_scene_linear() went, for messages and tests.
  std::string xyz_route() const;
  // Whether the config has a colour space of this name (or alias, or role).
  bool has_colorspace(const std::string& colorspace) const;
  // The colour space's name and aliases (just `colorspace` when the config lacks it).
  std::vector<std::string> names_of(const std::string& colorspace) const;
  // The space's CIE xy chromaticities (red, green, blue, white: 8 numbers): the published ones
  // for a space arbor knows by name or alias (those of xyz_to_scene_linear's third way), else
  // measured through the config (D65-adapted primaries and a D65 white); empty when the space is
  // not linear in XYZ.
  std::vector<float> chromaticities(const std::string& colorspace) const;
  // The Color Interop Forum's id of a space arbor knows ("lin_ap1_scene", …), else "".
  std::string interop_id(const std::string& colorspace) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string config_path_;
};

// The linear map between two RGB spaces given by their chromaticities (8 numbers each: red,
// green, blue and white xy, as ColorPipeline::chromaticities gives them), the whites
// Bradford-adapted through D65 (exact, and no adaptation at all, when both whites agree).
ColorTransform rgb_to_rgb(const std::vector<float>& from, const std::vector<float>& to);

// The config a run of arbor uses: $OCIO when it is set and not empty, else the config.ocio
// installed with the executable (`<prefix>/share/arbor/ocio/config.ocio` for `<prefix>/bin/arbor`;
// the build tree has the same layout). Read once, by the program, and passed on.
std::string default_ocio_config();

}  // namespace arbor::imaging
