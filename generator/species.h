// A species: which tree model grows it (a variant over the models' parameters), and its default
// bark and leaf looks.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "common/error.h"
#include "common/math.h"
#include "common/range.h"
#include "generator/geometry/leaf_margin.h"
#include "generator/models/fractal/fractal.h"
#include "generator/models/lsystem/lsystem.h"
#include "generator/skeleton.h"
#include "generator/models/treemaker/treemaker_template.h"
#include "generator/models/weber_penn/weber_penn_params.h"

namespace arbor::generator {

// The range of each look value, stated once: the species reader, the scene reader (a tree's
// overrides, a mesh's materials) and the scene builder all check against these.
namespace look_range {
inline constexpr Range kColour{0.0, 1.0, ""};  // albedo, reflectance, transmittance per channel
inline constexpr Range kBumpHeight{0.0, 1.0, "metres"};
inline constexpr Range kBumpTile{1e-3, 100.0, "metres"};
inline constexpr Range kBarkRoughness{0.0, 90.0, "degrees"};
inline constexpr Range kCuticleIor{1.0, 3.0, "(1: no cuticle)"};
inline constexpr Range kCuticleRoughness{0.0, 1.0, ""};
inline constexpr Range kHingeAngle{0.0, 90.0, "degrees"};
inline constexpr Range kLeafFold{0.0, 80.0, "degrees"};
inline constexpr Range kLeafCup{-90.0, 90.0, "degrees"};
inline constexpr Range kLeafCurl{-180.0, 180.0, "degrees"};
inline constexpr Range kLeafTwist{-180.0, 180.0, "degrees"};
inline constexpr Range kPetioleLength{0.0, 3.0, "(x the blade's length)"};
inline constexpr Range kPetioleWidth{0.0, 0.5, "(x the blade's width)"};
inline constexpr Range kToothDepth{0.0, 0.3, "(x the blade's width)"};
inline constexpr Range kLeafVariation{0.0, 1.0, "(spread of ln brightness or ln chlorophyll)"};
inline constexpr Range kCrownGradient{-2.0, 2.0, "(ln brightness, crown top less bottom)"};
inline constexpr Range kVeins{0.0, 2.0, "(strength of the paler veins and margin)"};
inline constexpr Range kLenticels{0.0, 20000.0, "per square metre of bark"};
inline constexpr Range kScars{0.0, 200.0, "per square metre of bark"};
inline constexpr Range kBaseHeight{0.0, 30.0, "metres"};
}  // namespace look_range

// A leaf creates no energy: front and back reflectance each plus the transmittance at most 1 in
// every channel. The one statement of the rule; readers and the builder call it.
inline bool leaf_conserves_energy(const Rgb& front, const Rgb& back, const Rgb& transmittance) {
  for (int i = 0; i < 3; ++i) {
    if (front[i] + transmittance[i] > 1.0 || back[i] + transmittance[i] > 1.0) return false;
  }
  return true;
}
inline constexpr const char* kLeafEnergyRule =
    "leaf reflectance + transmittance must be at most 1 in every channel (for the front and the "
    "back), or the leaf would create energy";

// Default bark of the species (scene files may override it).
struct BarkLook {
  Rgb albedo{0.30, 0.26, 0.22};
  double bump_height = 0.004;  // metres of relief
  double roughness = 0.0;      // degrees: Oren–Nayar slope deviation σ (0: Lambertian)
  // Its colour by its relief and marks (materials/bark_color.h): the furrows' albedo (none: the
  // bark's own everywhere), lenticels and scars per m² and their albedos, the height of the
  // trunk's darker, deeper-furrowed base.
  std::optional<Rgb> furrow_albedo;
  double lenticels = 0.0;
  Rgb lenticel_albedo{0.06, 0.05, 0.045};
  double scars = 0.0;
  Rgb scar_albedo{0.05, 0.045, 0.04};
  // Bloomenthal §6's ramiform at the forks of the trunk and main branches (docs/geometry.md):
  // a smooth collar where a limb leaves its parent instead of the crease of two tubes.
  bool ramiform = false;
  double base_height = 0.0;
};

// Default leaves of the species: front reflectance, the lighter back, diffuse transmittance, and
// the waxy cuticle on both faces (materials/cuticle.h; docs/species-format.md gives the sources of
// the defaults: cuticular wax has a refractive index near 1.45; 0.5 is a moderately glossy leaf).
// The season a tree's leaves show (docs/species-format.md, "Seasons"): summer is the leaf as
// given; spring lighter and yellower (less chlorophyll); autumn turns most leaves towards the
// species' autumn colour (evergreen species, without one, keep their leaves).
enum class Season { Summer, Spring, Autumn };
inline constexpr std::array<const char*, 3> kSeasonNames = {"summer", "spring", "autumn"};

struct LeafLook {
  // A broadleaf's, checked against measured leaves (bench/leaf_colours.py: a PROSPECT-5 leaf
  // calibrated on LOPEX93/ANGERS, linear Rec. 709 (0.087, 0.123, 0.038), and the ColorChecker's
  // foliage patch (0.095, 0.150, 0.056)): red about 0.6 of green, blue 0.3, green 0.10–0.15.
  Rgb reflectance{0.08, 0.13, 0.04};
  Rgb back_reflectance{0.10, 0.15, 0.055};
  Rgb transmittance{0.055, 0.09, 0.01};
  double cuticle_ior = 1.45;       // 1: no cuticle (a matte leaf)
  double cuticle_roughness = 0.5;  // [0, 1]; GGX α = roughness²
  double hinge_angle = 0.0;        // degrees; > 0: Bloomenthal's hinged three-polygon leaf (§10)
  // The shaped leaf (generator/geometry/leaf_bend.h), degrees: each half raised along the midrib,
  // turned further up towards the margin, the tip curled towards the back, twisted about the
  // midrib from base to tip. All 0: a flat card.
  double fold = 0.0, cup = 0.0, curl = 0.0, twist = 0.0;
  // The stalk: its length × the blade's length (0: none) and its width × the blade's width.
  double petiole_length = 0.0, petiole_width = 0.03;
  // The margin (generator/geometry/leaf_margin.h): its kind, teeth along each side of the blade
  // and their depth × the blade's width.
  LeafMarginSpec margin;
  // Each leaf's own tint (materials/leaf_variation.h): spread of ln brightness, spread along the
  // chlorophyll axis, ln brightness from the crown's bottom to its top. 0: every leaf alike.
  double variation = 0.0;
  double hue_variation = 0.0;
  double crown_gradient = 0.0;
  // The procedural texture over the leaf (materials/leaf_texture.h): strength (0: none) and
  // secondary vein pairs.
  double veins = 0.0;
  int vein_pairs = 8;
  Season season = Season::Summer;
  // The front reflectance the leaves turn to in autumn (absent: evergreen, no autumn colour).
  std::optional<Rgb> autumn;
};

// Root buttresses at the trunk's base (Bloomenthal 1985, "the base of a tree": planar blobby
// contours around the points where the roots cross each plane). 0 buttresses: none.
struct RootLook {
  int buttresses = 0;
  double height = 3.0;  // × the trunk's base radius: where the roots have merged into the trunk
  double spread =
      2.0;  // × the trunk's base radius: how far beyond the trunk they reach at the ground
};

// The models, in the order of ModelParams' alternatives.
enum class Model { WeberPenn, LSystem, SkeletonFile, Fractal, TreeMaker };

// Which model grows a species, with that model's parameters.
using ModelParams =
    std::variant<WeberPennParams, LSystem, Skeleton, FractalParams, TreeMakerTemplate>;

struct Species {
  std::string name;
  std::string path;
  ModelParams params;  // Weber & Penn unless a reader says otherwise

  Model model() const { return static_cast<Model>(params.index()); }
  // The parameters of the species' model; std::bad_variant_access for another model's.
  const WeberPennParams& weber_penn() const { return std::get<WeberPennParams>(params); }
  WeberPennParams& weber_penn() { return std::get<WeberPennParams>(params); }
  const LSystem& lsystem() const { return std::get<LSystem>(params); }
  const Skeleton& skeleton() const { return std::get<Skeleton>(params); }
  const FractalParams& fractal() const { return std::get<FractalParams>(params); }
  FractalParams& fractal() { return std::get<FractalParams>(params); }
  const TreeMakerTemplate& treemaker() const { return std::get<TreeMakerTemplate>(params); }

  BarkLook bark;
  LeafLook leaf;
  RootLook roots;
  // The TREE-MAKER shading weights the species states (a template's `light {}`); those it does
  // not state take arbor's defaults (materials/treemaker_weights.h) when the scene is built.
  TmLight treemaker_light;
  // Non-fatal notes from reading the file ("path:line:col: warning: …"), to show the user.
  std::vector<std::string> warnings;
};

// The last step of every reader: checks the rules that involve several parameters (pointing at the
// offending key's position, looked up in `positions` by paper name) and names an unnamed species
// after its file. Throws InputError.
void finish_species(Species& species, const std::map<std::string, SourceLocation>& positions);

}  // namespace arbor::generator
