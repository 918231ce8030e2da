// The scene file contract (docs/scene-format.md) as plain data: what a scene asks for, before
// anything is built, and what the renderer reads. formats/ fills it from a file (formats/
// scene_file.h), scene/ builds the world from it, tracer/ reads its settings; it sits below all
// three so that none of them reaches another's code. Paths are already resolved relative to the
// scene file.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/error.h"
#include "common/math.h"
#include "generator/species.h"
#include "imaging/output_spec.h"

namespace arbor::spec {

using Vec3d = std::array<double, 3>;

enum class Integrator { Path, Treemaker };
inline constexpr std::array<const char*, 2> kIntegratorNames = {"path", "treemaker"};
const char* name_of(Integrator integrator);
std::optional<Integrator> integrator_named(std::string_view name);

enum class SkyModel { Preetham, Nishita, Constant, Envmap, None, Atmosphere };
inline constexpr std::array<const char*, 6> kSkyModelNames = {"preetham", "nishita", "constant",
                                                              "envmap",   "none",    "atmosphere"};
const char* name_of(SkyModel model);

struct RenderSettings {
  int width = 960, height = 640;
  int spp = 64;
  std::uint64_t seed = 1;
  Integrator integrator = Integrator::Path;
  int max_depth = 12;
  // Path regularisation (docs/rendering.md, "Regularisation"): after a non-specular bounce,
  // glossy coats are roughened by pbrt-v4's rule. Biased; off for references.
  bool regularize = false;
  // Level of detail at range (docs/rendering.md, "Level of detail"; Weber & Penn §5): each tree
  // keeps the paper's fraction of its limbs and leaves for its range from the camera, leaves
  // enlarged to keep the crown's leaf area. Approximate; off for references. lod_quality is the
  // paper's quality factor (larger: detail kept farther away).
  bool lod = false;
  double lod_quality = 1.0;
  int treemaker_spp = 4;  // samples per pixel of the treemaker integrator (anti-aliasing)
  int pass_spp = 16;      // samples a pixel takes per pass (a power of two keeps Sobol' balanced)
  bool independent_passes =
      false;  // each pass its own scramble (unbiased variance) instead of one sequence
  double noise_threshold = 0.0;  // adaptive sampling: relative standard error to stop at; 0: off
  int min_spp = 16;  // adaptive sampling: samples before a pixel may stop (and 2 passes)
  int threads = 0;   // 0: all cores (command line only)
  // The air between the camera and what it sees (the nishita and atmosphere skies' atmosphere,
  // the path integrator): off for references
  bool aerial_perspective = false;

  // The sample count of the integrator in use.
  int samples() const { return integrator == Integrator::Treemaker ? treemaker_spp : spp; }
};

struct CameraDesc {
  Vec3d position{14.0, -20.0, 3.0};
  Vec3d look_at{0.0, 0.0, 6.0};
  Vec3d up{0.0, 0.0, 1.0};
  double fov = 45.0;             // vertical, degrees
  double aperture_radius = 0.0;  // metres
  double focus_distance = 0.0;   // metres; 0: distance to look_at
  double exposure = 0.0;         // stops
  bool auto_exposure = false;    // exposure = "auto": metered (tracer/exposure.h)
  // With a terrain: the eye stands this many metres above the terrain under position (x, y),
  // whose z is then ignored.
  std::optional<double> above_ground;
  SourceLocation above_ground_where;
  SourceLocation look_at_where, up_where;  // the keys' positions, for errors (else the file's)
};

// InputError at the key when the camera cannot form an image (look_at at the position, up along
// the view or zero).
void check_camera(const CameraDesc& camera);

struct SunDesc {
  bool enabled = true;
  double elevation = 40.0, azimuth = 135.0;  // degrees; azimuth counter-clockwise from +x
  double irradiance = 3.0;                   // scene-linear, on a plane facing the sun
  double angular_diameter = 0.53;            // degrees
};

struct SkyDesc {
  SkyModel model = SkyModel::Preetham;
  double turbidity = 3.0;  // preetham: Preetham's; atmosphere: Linke's (docs/rendering.md)
  // nishita, atmosphere: multipliers of the standard atmosphere's profiles, the observer's altitude
  // (m)
  double air_density = 1.0, dust_density = 1.0, ozone_density = 1.0, altitude = 0.0;
  // atmosphere: the aerosols by one of turbidity, visibility (km; 0: not given) or dust_density
  // (the one given; turbidity 3 when none is); the ground's albedo under the whole sky (negative:
  // the luminance of [ground]'s albedo, the reader fills it in)
  double visibility = 0.0;
  bool turbidity_given = false, dust_given = false;
  double ground_albedo = -1.0;
  Rgb color{1.0, 1.0, 1.0};
  std::string path;       // envmap
  double rotation = 0.0;  // envmap, degrees about z
  double scale = 1.0;     // envmap
};

struct GroundDesc {
  bool enabled = true;
  Rgb albedo{0.16, 0.14, 0.10};
  // Patches of a second albedo (grass on soil, say) by smooth procedural noise: patch_cover of
  // the ground (0: none), blobs about patch_scale metres across.
  Rgb patch_albedo{0.06, 0.11, 0.035};
  double patch_cover = 0.0, patch_scale = 3.0;
  // Detail at finer scales (materials/ground.h): its strength, small stones per m² of soil, the
  // fraction under leaf litter; all 0 by default (the ground as before).
  double detail = 0.0, stones = 0.0, litter = 0.0;
  Rgb stone_albedo{0.32, 0.31, 0.29};
  Rgb litter_albedo{0.20, 0.13, 0.07};
};

// A [terrain] (docs/landscape.md): a height field over a square centred on the origin, from a
// procedural model (fractional Brownian motion hills, ridged mountains) or from an image (a
// digital elevation model). Heights run from 0 (the lowest) to `relief`; the ground plane, if
// on, continues the terrain's lowest level beyond its edges. Its material is the [ground]'s,
// with soil and rock by slope and curvature.
enum class TerrainKind { Hills, Mountains, Image };
inline constexpr std::array<const char*, 3> kTerrainKindNames = {"hills", "mountains", "image"};
struct TerrainDesc {
  bool enabled = false;  // a [terrain] table is in the scene
  TerrainKind kind = TerrainKind::Hills;
  double size = 1000.0;     // metres: the square's side (image: pixels × metres_per_pixel)
  double relief = 100.0;    // metres from the lowest to the highest point
  std::uint64_t seed = 1;   // of the procedural models
  double resolution = 2.0;  // metres between height samples (procedural models)
  std::string path;         // kind = "image": a 16-bit PNG or an EXR, one height per pixel
  double metres_per_pixel = 1.0;
  double height_scale = 1.0;  // metres per unit of the image's value (a PNG's 0…65535 → 0…1)
  double rock_slope = 35.0;   // degrees: rock on faces steeper than this (soil a band below)
  double surround = 4.0;      // sides the model continues beyond the square, coarser (0: none)
  Rgb rock_albedo{0.30, 0.29, 0.26};
  Rgb soil_albedo{0.19, 0.15, 0.11};
  SourceLocation where, path_where;  // the table's and the path's positions, for errors found later
};

// The metres between a terrain's height samples: the image's metres_per_pixel, or the size
// divided into whole steps no longer than the resolution.
inline double terrain_spacing(const TerrainDesc& t) {
  if (t.kind == TerrainKind::Image) return t.metres_per_pixel;
  return t.size / std::ceil(t.size / t.resolution - 1e-9);
}

// A meadow of grass blades (scene/meadow.h): `density` blades per m² (0: none) over `area`
// (x0, y0, x1, y1, rounded out to whole tiles), each a thin two-sided translucent ribbon.
struct MeadowDesc {
  double density = 0.0;
  std::array<double, 4> area{-10.0, -10.0, 10.0, 10.0};
  double height = 0.25;         // metres, the blades' median height
  double height_spread = 0.3;   // σ of ln height
  double width = 0.004;         // metres, a blade's width at its base
  double clumping = 0.5;        // the share of blades in tufts
  double lean = 20.0;           // degrees, the blades' typical lean from upright
  double bend = 0.5;            // how far gravity bends a leaning blade over, [0, 1]
  double dry = 0.05;            // the share of dead, straw-coloured blades
  double wind = 0.0;            // m/s, bending the blades downwind (and swaying in [animation])
  double wind_direction = 0.0;  // degrees about z: the direction the wind blows towards
  double tile = 1.0;            // metres, the side of a tile of blades
  int tiles = 4;                // distinct tiles the meadow repeats, turned and shuffled
  std::uint64_t seed = 1;
  // A grass blade's, by the leaves' measured ratios (docs/species-format.md, "Leaf colours").
  Rgb reflectance{0.07, 0.12, 0.035}, back_reflectance{0.08, 0.13, 0.04};
  Rgb transmittance{0.045, 0.08, 0.01};
  Rgb dry_reflectance{0.30, 0.24, 0.12};
  SourceLocation where;
};

// The cells of a meadow's tile grid its area touches, at most (the area rounded out to whole
// tiles, plus one per axis for an area off the grid): what its instances cost.
inline double meadow_cells(const MeadowDesc& m) {
  return std::ceil((m.area[2] - m.area[0]) / m.tile + 1.0) *
         std::ceil((m.area[3] - m.area[1]) / m.tile + 1.0);
}

// The ground's albedo as one number, what the atmosphere's sky sees: the luminance (Rec. 709) of
// its albedo and its patches' by the share each covers.
inline double mean_albedo(const GroundDesc& g) {
  auto y = [](const Rgb& c) { return luminance(c[0], c[1], c[2]); };
  // Stones cover about stones × 8.2 cm² of soil (their mean area, soft edges included).
  const double stones = std::min(1.0, g.stones * 8.2e-4) * (1.0 - g.patch_cover);
  const double plain = (1.0 - g.patch_cover - stones) * y(g.albedo) +
                       g.patch_cover * y(g.patch_albedo) + stones * y(g.stone_albedo);
  return (1.0 - g.litter) * plain + g.litter * y(g.litter_albedo);
}

// The ground's albedo under the atmosphere sky: the one stated (the reader fills in [ground]'s),
// or, for a description made in code (negative), the default ground's.
inline double ground_albedo_under(const SkyDesc& s) {
  return s.ground_albedo >= 0.0 ? s.ground_albedo : mean_albedo(GroundDesc{});
}

// Linke's turbidity of an atmosphere without aerosols (and 1.5 cm of precipitable water), rounded
// up: the smallest sky.turbidity of the atmosphere model (tracer/lights/nishita.h,
// dust_for_turbidity; docs/rendering.md, "Sky").
inline constexpr double kClearestLinkeTurbidity = 2.21;

// Overrides of a species' bark and leaves; unset fields keep the species' values.
struct BarkOverride {
  std::optional<Rgb> albedo;
  std::string bump_map;  // image path; empty: procedural bark
  std::optional<double> bump_height;
  double bump_tile = 0.25;  // metres along and around the limb per repeat of bump_map, albedo_map
  std::string albedo_map;   // image multiplying the albedo; empty: none
  std::optional<double> roughness;  // degrees, Oren–Nayar σ
};
struct LeafOverride {
  std::optional<Rgb> reflectance, back_reflectance, transmittance;
  std::optional<double> cuticle_ior, cuticle_roughness;            // 1: no cuticle; [0, 1]
  std::optional<double> variation, hue_variation, crown_gradient;  // each leaf's own tint
  std::optional<double> veins;  // the procedural texture's strength
  std::optional<generator::Season> season;
  std::string albedo_map;  // image over the leaf's uv multiplying R, back R and T; empty: none
};

// Overrides of the five TREE-MAKER shading weights (§III); unset ones keep the template's
// `light {}` values, or arbor's defaults for trees of other models.
struct TreemakerOverride {
  std::optional<double> ambient, lambert, height, radius, angle;
};

struct Placement {
  Vec3d position{0.0, 0.0, 0.0};
  double rotation = 0.0;  // degrees about z
  double scale = 1.0;
};

struct TreeDesc {
  std::string species;  // resolved path
  SourceLocation where;
  std::uint64_t seed = 1;
  Placement placement;
  double time = 0.0;
  BarkOverride bark;
  LeafOverride leaf;
  TreemakerOverride treemaker;
};

struct ForestDesc {
  std::string species;
  SourceLocation where;
  int count = 1;
  int variants = 1;
  std::array<double, 4> area{-10.0, -10.0, 10.0, 10.0};  // x0, y0, x1, y1
  std::uint64_t seed = 1;
  BarkOverride bark;
  LeafOverride leaf;
  TreemakerOverride treemaker;
};

// One species of a plant community (scene/community.h; docs/landscape.md, "Plant communities"):
// how it establishes, grows, competes and where it can live.
struct CommunitySpecies {
  std::string species;  // the species file
  SourceLocation where;
  int variants = 16;             // distinct trees grown; every plant is one of them, scaled
  double sown = 0.0;             // established per m² in the first year (an even-aged stand)
  double seedlings = 1e-3;       // established per m² per year where the habitat is ideal
  double seeds = 2.0;            // seeds a year from a plant past half its maturity
  double dispersal = 10.0;       // metres: the mean distance of a seed from its parent
  double radius = 4.0;           // metres: the circle of influence at maturity (the crown)
  double maturity = 40.0;        // years to 95 % of the full radius
  double lifespan = 200.0;       // years; older plants die at 10 % a year
  double shade_tolerance = 0.0;  // a dominated plant's chance to live another year, [0, 1)
  double altitude_min = -1e5;    // metres above the terrain's lowest point
  double altitude_max = 1e5;
  double slope_max = 45.0;         // degrees
  double aspect = 180.0;           // degrees from north, clockwise: the way its slopes face
  double aspect_preference = 0.0;  // 0: any aspect, 1: only slopes facing `aspect`
  double moisture_min = 0.0;       // the terrain's flow moisture, [0, 1]
  double moisture_max = 1.0;
  BarkOverride bark;
  LeafOverride leaf;
  TreemakerOverride treemaker;
};

// A plant community (scene/community.h): its species simulated together over `years` on `area`
// as circles of influence (Lane & Prusinkiewicz 2002).
struct CommunityDesc {
  bool enabled = false;
  std::array<double, 4> area{-50.0, -50.0, 50.0, 50.0};
  double years = 100.0;
  std::uint64_t seed = 1;
  std::vector<CommunitySpecies> species;
  SourceLocation where;
};

// Rocks (scene/rocks.h; docs/landscape.md, "Rocks"): boulders and stones of a few noise-displaced
// shapes, instanced, their sizes from a power law, placed on rock faces and scree and partly
// buried.
struct RocksDesc {
  bool enabled = false;
  SourceLocation where;
  double density = 0.02;                  // rocks per m² where the ground is all rock
  double size_min = 0.3, size_max = 3.0;  // metres: a rock's diameter
  double exponent = 2.5;                  // the sizes' density falls as size^-exponent
  double buried = 0.3;                    // the share of a rock's height below the ground
  int variants = 8;                       // distinct shapes
  std::uint64_t seed = 1;
  std::optional<std::array<double, 4>> area;  // x0, y0, x1, y1; none: the terrain's square
  Rgb albedo{0.30, 0.29, 0.26};
};

struct MeshMaterialDesc {
  std::string kind = "diffuse";  // "bark" | "leaf" | "diffuse"
  Rgb albedo{0.5, 0.5, 0.5};     // bark, diffuse
  // leaf: a species leaf's defaults (generator/species.h LeafLook), stated there once
  Rgb reflectance = generator::LeafLook{}.reflectance;
  Rgb back_reflectance = generator::LeafLook{}.back_reflectance;
  Rgb transmittance = generator::LeafLook{}.transmittance;
  double cuticle_ior = generator::LeafLook{}.cuticle_ior;
  double cuticle_roughness = generator::LeafLook{}.cuticle_roughness;
};

struct MeshDesc {
  std::string path;
  SourceLocation where;
  std::string up = "z";
  Placement placement;
  std::map<std::string, MeshMaterialDesc> materials;  // by OBJ group or material name
};

// The [output] table: the files, and the output specification they are written by
// (imaging/output_spec.h: colour space, display and view, pixel type, AOVs, transparent sky).
struct OutputDesc : imaging::OutputSpec {
  std::string exr;  // resolved; empty: none
  std::string png;
  double checkpoint_seconds = 0.0;     // rewrite the outputs this often as passes finish; 0: never
  SourceLocation treemaker_aov_where;  // where "treemaker" is listed (only that integrator has it)
  // The keys' positions, for errors found later (by the OCIO config); the file's when unset.
  imaging::OutputKeys where;
};

// An animation (docs/farm.md): frame N is rendered at clock N / fps seconds. Trees of models that
// sway in the wind (Weber & Penn, §4.7) get the clock added to their `time` (seconds of wind);
// trees of growth models (the fractal model, whose `time` is the tree's age in years) grow by
// years_per_second × the clock (0: they stand still). The sample seed is varied per frame
// (derive_key(seed, N)) unless pin_seed.
struct AnimationDesc {
  int frames = 0;  // 0: no [animation] table
  double fps = 24.0;
  double years_per_second = 0.0;
  bool pin_seed = false;
  SourceLocation where;  // the table's position, for errors found later
};

// A file the scene names, where it names it (for errors about the file itself).
struct FileRef {
  std::string path;  // resolved against the scene's folder
  SourceLocation where;
  std::string key;  // "tree.species", "forest.bark.bump_map", …
};

struct SceneDesc {
  std::string path;
  std::vector<FileRef> files;  // every file key, in the order of the scene's text
  RenderSettings render;
  CameraDesc camera;
  SunDesc sun;
  SkyDesc sky;
  GroundDesc ground;
  TerrainDesc terrain;
  MeadowDesc meadow;
  std::vector<TreeDesc> trees;
  std::vector<ForestDesc> forests;
  CommunityDesc community;
  RocksDesc rocks;
  std::vector<MeshDesc> meshes;
  OutputDesc output;
  AnimationDesc animation;
  double clock = 0.0;  // seconds into the animation of this render (render --frame N: N / fps)
};

// The frame's path: the first run of '#' in `path` replaced by `frame`, zero-padded to the run's
// length ("out/wind.####.exr", 7 → "out/wind.0007.exr"); `path` when it has no '#'.
std::string frame_path(const std::string& path, int frame);

// Every file the scene reads: the scene itself, species, textures, the environment map, meshes.
std::vector<std::string> scene_inputs(const SceneDesc& scene);

}  // namespace arbor::spec
