// OpenColorIO: loading the config, checking the output's names, CPU processors.
#include "imaging/color.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <OpenColorIO/OpenColorIO.h>

#include "common/error.h"
#include "common/executable.h"

namespace OCIO = OCIO_NAMESPACE;

namespace arbor::imaging {

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

namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 m{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) m[i][j] += a[i][k] * b[k][j];
  return m;
}

Mat3 inverse(const Mat3& m) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  Mat3 r{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      // Cofactor of (j, i) over the determinant.
      const int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
      r[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det;
    }
  }
  return r;
}

std::array<double, 3> times(const Mat3& m, const std::array<double, 3>& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
          m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

std::array<double, 3> xy_to_xyz(double x, double y) { return {x / y, 1.0, (1.0 - x - y) / y}; }

// RGB → CIE XYZ of primaries and white (x, y pairs: r, g, b, w), then Bradford-adapted from
// that white to D65 (as OCIO's *_BFD built-ins adapt).
Mat3 rgb_to_xyz_d65(const double c[8]) {
  Mat3 p{};
  for (int k = 0; k < 3; ++k) {
    const std::array<double, 3> v = xy_to_xyz(c[2 * k], c[2 * k + 1]);
    for (int i = 0; i < 3; ++i) p[i][k] = v[i];
  }
  const std::array<double, 3> white = xy_to_xyz(c[6], c[7]);
  const std::array<double, 3> scale = times(inverse(p), white);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) p[i][k] *= scale[k];
  const Mat3 bradford{
      {{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
  const std::array<double, 3> from = times(bradford, white),
                              to = times(bradford, xy_to_xyz(0.3127, 0.3290));
  Mat3 cone{};
  for (int i = 0; i < 3; ++i) cone[i][i] = to[i] / from[i];
  return multiply(multiply(inverse(bradford), multiply(cone, bradford)), p);
}

struct KnownPrimaries {
  const char* names[7];
  double c[8];
  const char* interop_id;  // the Color Interop Forum's id (an EXR's colorInteropID)
};

// Linear spaces arbor recognises by name when a config offers no XYZ: the names configs give
// them (arbor's, the ACES configs', Blender's).
const KnownPrimaries kPrimaries[] = {
    {{"Linear Rec.709 (sRGB)", "lin_rec709", "Linear Rec.709", "lin_rec709_scene", "Linear",
      "Utility - Linear - sRGB", "lin_srgb"},
     {0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290},
     "lin_rec709_scene"},
    {{"ACEScg", "ACES - ACEScg", "lin_ap1", "lin_ap1_scene", "Linear ACEScg", nullptr, nullptr},
     {0.713, 0.293, 0.165, 0.830, 0.128, 0.044, 0.32168, 0.33767},
     "lin_ap1_scene"},
    {{"ACES2065-1", "ACES - ACES2065-1", "lin_ap0", "lin_ap0_scene", "Linear ACES", nullptr,
      nullptr},
     {0.7347, 0.2653, 0.0, 1.0, 0.0001, -0.077, 0.32168, 0.33767},
     "lin_ap0_scene"},
    {{"Linear Rec.2020", "lin_rec2020", "lin_rec2020_scene", "Utility - Linear - Rec.2020",
      "Linear Rec.2100", nullptr, nullptr},
     {0.708, 0.292, 0.170, 0.797, 0.131, 0.046, 0.3127, 0.3290},
     "lin_rec2020_scene"},
    {{"Linear P3-D65", "lin_p3d65", "lin_p3d65_scene", "Utility - Linear - P3-D65",
      "Linear Display P3", nullptr, nullptr},
     {0.680, 0.320, 0.265, 0.690, 0.150, 0.060, 0.3127, 0.3290},
     "lin_p3d65_scene"},
};

const KnownPrimaries* known_primaries(const std::vector<std::string>& names) {
  for (const KnownPrimaries& k : kPrimaries) {
    for (const char* n : k.names) {
      if (n && std::find(names.begin(), names.end(), n) != names.end()) return &k;
    }
  }
  return nullptr;
}

ColorTransform matrix_transform(const Mat3& m) {
  std::array<float, 9> f{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      f[static_cast<std::size_t>(3 * i + j)] = static_cast<float>(m[i][j]);
  return [f](float rgb[3]) {
    const float r = rgb[0], g = rgb[1], b = rgb[2];
    rgb[0] = f[0] * r + f[1] * g + f[2] * b;
    rgb[1] = f[3] * r + f[4] * g + f[5] * b;
    rgb[2] = f[6] * r + f[7] * g + f[8] * b;
  };
}

// Why `t` is not a linear map from XYZ (D65) to a scene-linear RGB with a D65-adapted white, or "".
std::string implausible_xyz(const ColorTransform& t) {
  float white[3] = {0.95047f, 1.0f, 1.08883f};
  float twice[3] = {2 * 0.95047f, 2.0f, 2 * 1.08883f};
  float tint[3] = {0.2f, 0.5f, 0.1f}, tint2[3] = {0.8f, 2.0f, 0.4f};
  t(white);
  t(twice);
  t(tint);
  t(tint2);
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(white[c]) ||
        std::fabs(twice[c] - 2 * white[c]) > 1e-3f * std::fabs(2 * white[c]) + 1e-5f ||
        std::fabs(tint2[c] - 4 * tint[c]) > 1e-3f * std::fabs(4 * tint[c]) + 1e-5f) {
      return "it is not linear (a tone curve or a display encoding)";
    }
  }
  const float mean = (white[0] + white[1] + white[2]) / 3.0f;
  for (int c = 0; c < 3; ++c) {
    if (!(mean > 0.0f) || std::fabs(white[c] - mean) > 0.02f * mean) {
      return "it does not take the D65 white to a neutral colour";
    }
  }
  return "";
}

}  // namespace

struct ColorPipeline::Impl {
  OCIO::ConstConfigRcPtr config;
  // xyz_to_scene_linear's way, found once.
  std::once_flag xyz_once;
  ColorTransform xyz;
  std::string xyz_route, xyz_failure;
  void find_xyz(const std::string& config_path);
};

void ColorPipeline::Impl::find_xyz(const std::string& config_path) {
  const OCIO::Config& c = *config;
  std::vector<std::string> tried;
  auto scene_space = [&](const char* name, std::string& why) -> OCIO::ConstColorSpaceRcPtr {
    OCIO::ConstColorSpaceRcPtr cs = c.getColorSpace(name);
    if (!cs) {
      why = "not in the config";
      return nullptr;
    }
    if (cs->getReferenceSpaceType() != OCIO::REFERENCE_SPACE_SCENE) {
      why = std::string("\"") + cs->getName() +
            "\" is display-referred (reaching it needs a view transform)";
      return nullptr;
    }
    return cs;
  };
  auto accept = [&](ColorTransform t, const std::string& route) {
    const std::string why = implausible_xyz(t);
    if (!why.empty()) {
      tried.push_back(route + ": " + why);
      return false;
    }
    xyz = std::move(t);
    xyz_route = route;
    return true;
  };
  // 1. An XYZ colour space, by name, alias or role.
  for (const char* name : {"Linear CIE-XYZ-D65", OCIO::ROLE_INTERCHANGE_DISPLAY, "XYZ",
                           "Linear CIE-XYZ D65", "lin_ciexyzd65_scene"}) {
    std::string why;
    const OCIO::ConstColorSpaceRcPtr cs = scene_space(name, why);
    const std::string label = std::string("colour space \"") + name + "\"";
    if (!cs) {
      tried.push_back(label + ": " + why);
      continue;
    }
    try {
      if (accept(
              apply(
                  c.getProcessor(cs->getName(), OCIO::ROLE_SCENE_LINEAR)->getDefaultCPUProcessor()),
              label + (name == std::string(cs->getName())
                           ? ""
                           : std::string(" (\"") + cs->getName() + "\")"))) {
        return;
      }
    } catch (const OCIO::Exception& e) {
      tried.push_back(label + ": " + e.what());
    }
  }
  // 2. ACES2065-1 through the aces_interchange role, with the ACES primaries.
  {
    std::string why;
    const OCIO::ConstColorSpaceRcPtr cs = scene_space(OCIO::ROLE_INTERCHANGE_SCENE, why);
    if (!cs) {
      tried.push_back("role aces_interchange: " + why);
    } else {
      try {
        const ColorTransform to_ap0 = matrix_transform(inverse(rgb_to_xyz_d65(kPrimaries[2].c)));
        const ColorTransform ap0_to_linear =
            apply(c.getProcessor(cs->getName(), OCIO::ROLE_SCENE_LINEAR)->getDefaultCPUProcessor());
        if (accept(
                [to_ap0, ap0_to_linear](float rgb[3]) {
                  to_ap0(rgb);
                  ap0_to_linear(rgb);
                },
                std::string("role aces_interchange (\"") + cs->getName() +
                    "\", ACES AP0 primaries)")) {
          return;
        }
      } catch (const OCIO::Exception& e) {
        tried.push_back(std::string("role aces_interchange: ") + e.what());
      }
    }
  }
  // 3. The scene_linear space's primaries, when arbor knows it by name.
  const OCIO::ConstColorSpaceRcPtr linear = c.getColorSpace(OCIO::ROLE_SCENE_LINEAR);
  if (!linear) {
    tried.push_back("the scene_linear role: not in the config");
  } else {
    std::vector<std::string> names{linear->getName()};
    for (std::size_t i = 0; i < linear->getNumAliases(); ++i)
      names.emplace_back(linear->getAlias(i));
    if (const KnownPrimaries* known = known_primaries(names)) {
      if (accept(matrix_transform(inverse(rgb_to_xyz_d65(known->c))),
                 std::string("the scene_linear space \"") + linear->getName() +
                     "\" by its primaries")) {
        return;
      }
    } else {
      tried.push_back(std::string("the scene_linear space \"") + linear->getName() +
                      "\": not a space arbor knows the primaries of");
    }
  }
  xyz_failure = "the OCIO config " + config_path +
                " offers no way to convert the sky's CIE XYZ (D65) to "
                "scene_linear; tried ";
  for (std::size_t i = 0; i < tried.size(); ++i) xyz_failure += (i ? "; " : "") + tried[i];
  xyz_failure +=
      ". Add a scene-referred colour space named \"Linear CIE-XYZ-D65\" (or the "
      "cie_xyz_d65_interchange role pointing at one)";
}

ColorPipeline::ColorPipeline(std::string config_path)
    : impl_(std::make_unique<Impl>()), config_path_(std::move(config_path)) {
  try {
    impl_->config = OCIO::Config::CreateFromFile(config_path_.c_str());
  } catch (const OCIO::Exception& e) {
    throw InputError({config_path_, 0, 0}, std::string("cannot use this OCIO config: ") + e.what());
  }
}

ColorPipeline::~ColorPipeline() = default;

void ColorPipeline::check(const OutputSpec& o, const OutputKeys& where) const {
  const OCIO::Config& c = *impl_->config;
  if (!c.getColorSpace(o.colorspace.c_str())) {
    std::vector<std::string> names;
    for (int i = 0; i < c.getNumColorSpaces(); ++i)
      names.emplace_back(c.getColorSpaceNameByIndex(i));
    throw InputError(where.colorspace, "output.colorspace \"" + o.colorspace +
                                           "\" is not in the OCIO config " + config_path_ +
                                           "; it has " + list_of(names));
  }
  check_display_view(o.display, o.view, where.display, where.view);
  (void)to_output(o.colorspace);  // a space OCIO cannot convert to fails here, not after the render
}

void ColorPipeline::check_display_view(const std::string& display, const std::string& view,
                                       const SourceLocation& display_where,
                                       const SourceLocation& view_where) const {
  const OCIO::Config& c = *impl_->config;
  // A key's position when there is one, else the option's name.
  const bool keyed = !display_where.path.empty();
  std::vector<std::string> displays;
  bool display_found = false;
  for (int i = 0; i < c.getNumDisplays(); ++i) {
    displays.emplace_back(c.getDisplay(i));
    display_found = display_found || displays.back() == display;
  }
  if (!display_found) {
    throw InputError(display_where, std::string(keyed ? "output.display" : "--display") + " \"" +
                                        display + "\" is not a display of the OCIO config " +
                                        config_path_ + "; it has " + list_of(displays));
  }
  std::vector<std::string> views;
  bool view_found = false;
  for (int i = 0; i < c.getNumViews(display.c_str()); ++i) {
    views.emplace_back(c.getView(display.c_str(), i));
    view_found = view_found || views.back() == view;
  }
  if (!view_found) {
    throw InputError(view_where, std::string(keyed ? "output.view" : "--view") + " \"" + view +
                                     "\" is not a view of display \"" + display +
                                     "\" in the OCIO config " + config_path_ + "; it has " +
                                     list_of(views));
  }
}

ColorTransform ColorPipeline::to_output(const std::string& colorspace) const {
  try {
    return apply(impl_->config->getProcessor(OCIO::ROLE_SCENE_LINEAR, colorspace.c_str())
                     ->getDefaultCPUProcessor());
  } catch (const OCIO::Exception& e) {
    throw InputError({config_path_, 0, 0},
                     "OCIO cannot convert to " + colorspace + ": " + e.what());
  }
}

ColorTransform ColorPipeline::to_display(const std::string& colorspace, const std::string& display,
                                         const std::string& view) const {
  try {
    OCIO::DisplayViewTransformRcPtr t = OCIO::DisplayViewTransform::Create();
    t->setSrc(colorspace.c_str());
    t->setDisplay(display.c_str());
    t->setView(view.c_str());
    return apply(impl_->config->getProcessor(t)->getDefaultCPUProcessor());
  } catch (const OCIO::Exception& e) {
    throw InputError({config_path_, 0, 0}, "OCIO cannot show " + colorspace + " on display \"" +
                                               display + "\", view \"" + view + "\": " + e.what());
  }
}

ColorTransform ColorPipeline::xyz_to_scene_linear() const {
  std::call_once(impl_->xyz_once, [&] { impl_->find_xyz(config_path_); });
  if (!impl_->xyz) throw InputError({config_path_, 0, 0}, impl_->xyz_failure);
  return impl_->xyz;
}

std::string ColorPipeline::xyz_route() const {
  (void)xyz_to_scene_linear();
  return impl_->xyz_route;
}

bool ColorPipeline::has_colorspace(const std::string& colorspace) const {
  return impl_->config->getColorSpace(colorspace.c_str()) != nullptr;
}

std::vector<std::string> ColorPipeline::names_of(const std::string& colorspace) const {
  const OCIO::ConstColorSpaceRcPtr cs = impl_->config->getColorSpace(colorspace.c_str());
  if (!cs) return {colorspace};
  std::vector<std::string> names{cs->getName()};
  for (std::size_t i = 0; i < cs->getNumAliases(); ++i) names.emplace_back(cs->getAlias(i));
  return names;
}

std::string ColorPipeline::interop_id(const std::string& colorspace) const {
  const KnownPrimaries* known = known_primaries(names_of(colorspace));
  return known ? known->interop_id : "";
}

ColorTransform rgb_to_rgb(const std::vector<float>& from, const std::vector<float>& to) {
  if (from.size() != 8 || to.size() != 8)
    throw std::invalid_argument("rgb_to_rgb: 8 chromaticities each");
  double a[8], b[8];
  for (int i = 0; i < 8; ++i) {
    a[i] = from[static_cast<std::size_t>(i)];
    b[i] = to[static_cast<std::size_t>(i)];
  }
  return matrix_transform(multiply(inverse(rgb_to_xyz_d65(b)), rgb_to_xyz_d65(a)));
}

std::vector<float> ColorPipeline::chromaticities(const std::string& colorspace) const {
  if (const KnownPrimaries* known = known_primaries(names_of(colorspace))) {
    return std::vector<float>(known->c, known->c + 8);
  }
  std::call_once(impl_->xyz_once, [&] { impl_->find_xyz(config_path_); });
  if (!impl_->xyz) return {};
  ColorTransform to_space;
  try {
    to_space = to_output(colorspace);
  } catch (const InputError&) {
    return {};
  }
  // XYZ → the space, column by column; linear, or no chromaticities.
  Mat3 m{};
  for (int k = 0; k < 3; ++k) {
    float v[3] = {0.0f, 0.0f, 0.0f}, w[3] = {0.0f, 0.0f, 0.0f};
    v[k] = 1.0f;
    w[k] = 3.0f;
    impl_->xyz(v);
    to_space(v);
    impl_->xyz(w);
    to_space(w);
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(v[i]) ||
          std::fabs(w[i] - 3.0f * v[i]) > 1e-3f * std::fabs(3.0f * v[i]) + 1e-5f)
        return {};
      m[i][k] = v[i];
    }
  }
  const Mat3 to_xyz = inverse(m);
  std::vector<float> c;
  std::array<double, 3> white{0.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k) {
    const std::array<double, 3> p{to_xyz[0][k], to_xyz[1][k], to_xyz[2][k]};
    const double sum = p[0] + p[1] + p[2];
    if (!(std::fabs(sum) > 1e-9)) return {};
    c.push_back(static_cast<float>(p[0] / sum));
    c.push_back(static_cast<float>(p[1] / sum));
    for (int i = 0; i < 3; ++i)
      white[static_cast<std::size_t>(i)] += p[static_cast<std::size_t>(i)];
  }
  const double sum = white[0] + white[1] + white[2];
  c.push_back(static_cast<float>(white[0] / sum));
  c.push_back(static_cast<float>(white[1] / sum));
  return c;
}

}  // namespace arbor::imaging
