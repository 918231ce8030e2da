// OpenColorIO: loading the config, checking the output's names, CPU processors.
#include "imaging/color.h"

#include <cstdlib>
#include <vector>

#include <OpenColorIO/OpenColorIO.h>

#include "common/error.h"
#include "common/executable.h"

namespace OCIO = OCIO_NAMESPACE;

namespace arbor::trace {

namespace {

std::string list_of(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "\"" : ", \"") + n + "\"";
  return out;
}

ColorTransform apply(OCIO::ConstCPUProcessorRcPtr cpu) {
  return [cpu](float rgb[3]) { cpu->applyRGB(rgb); };
}

}  // namespace

std::string default_ocio_config() {
  const char* env = std::getenv("OCIO");
  if (env && *env) return env;
  return installed_data_path("ocio/config.ocio");
}

struct ColorPipeline::Impl {
  OCIO::ConstConfigRcPtr config;
};

ColorPipeline::ColorPipeline(std::string config_path)
    : impl_(std::make_unique<Impl>()), config_path_(std::move(config_path)) {
  try {
    impl_->config = OCIO::Config::CreateFromFile(config_path_.c_str());
  } catch (const OCIO::Exception& e) {
    throw InputError({config_path_, 0, 0}, std::string("cannot use this OCIO config: ") + e.what());
  }
}

ColorPipeline::~ColorPipeline() = default;

void ColorPipeline::check(const OutputDesc& o) const {
  const OCIO::Config& c = *impl_->config;
  if (!c.getColorSpace(o.colorspace.c_str())) {
    std::vector<std::string> names;
    for (int i = 0; i < c.getNumColorSpaces(); ++i) names.emplace_back(c.getColorSpaceNameByIndex(i));
    throw InputError(o.colorspace_where, "output.colorspace \"" + o.colorspace + "\" is not in the OCIO config " +
                             config_path_ + "; it has " + list_of(names));
  }
  std::vector<std::string> displays;
  bool display_found = false;
  for (int i = 0; i < c.getNumDisplays(); ++i) {
    displays.emplace_back(c.getDisplay(i));
    display_found = display_found || displays.back() == o.display;
  }
  if (!display_found) {
    throw InputError(o.display_where, "output.display \"" + o.display + "\" is not in the OCIO config; it has " +
                             list_of(displays));
  }
  std::vector<std::string> views;
  bool view_found = false;
  for (int i = 0; i < c.getNumViews(o.display.c_str()); ++i) {
    views.emplace_back(c.getView(o.display.c_str(), i));
    view_found = view_found || views.back() == o.view;
  }
  if (!view_found) {
    throw InputError(o.view_where, "output.view \"" + o.view + "\" is not a view of display \"" + o.display +
                             "\"; it has " + list_of(views));
  }
  (void)to_output(o.colorspace);  // a space OCIO cannot convert to fails here, not after the render
}

ColorTransform ColorPipeline::to_output(const std::string& colorspace) const {
  try {
    return apply(impl_->config->getProcessor(OCIO::ROLE_SCENE_LINEAR, colorspace.c_str())
                     ->getDefaultCPUProcessor());
  } catch (const OCIO::Exception& e) {
    throw InputError({config_path_, 0, 0}, "OCIO cannot convert to " + colorspace + ": " + e.what());
  }
}

ColorTransform ColorPipeline::xyz_to_scene_linear() const {
  try {
    return apply(impl_->config->getProcessor("Linear CIE-XYZ-D65", OCIO::ROLE_SCENE_LINEAR)
                     ->getDefaultCPUProcessor());
  } catch (const OCIO::Exception& e) {
    throw InputError({config_path_, 0, 0}, std::string("the OCIO config cannot convert the sky's CIE XYZ "
                                                       "(it needs \"Linear CIE-XYZ-D65\"): ") + e.what());
  }
}

}  // namespace arbor::trace
