// The scene file's keys of what stands on the ground: [[tree]], [[forest]] and their [.bark],
// [.leaf] and [.treemaker] overrides, [[mesh]] and its materials, [meadow] (scene_keys.h).
#include <array>

#include "formats/scene_keys.h"

namespace arbor::formats {

using keys::custom;
using keys::file;
using keys::value;
namespace look_range = generator::look_range;

namespace {

constexpr Range kAnySeed{0, 0x1p63, ""};
constexpr Range kUnit{0, 1, ""};
constexpr std::array<const char*, 2> kUpNames = {"z", "y"};
constexpr std::array<const char*, 3> kMaterialKinds = {"bark", "leaf", "diffuse"};

// position, rotation and scale of a [[tree]] or a [[mesh]].
template <class D>
void add_placement(std::vector<Key<D>>& table) {
  table.push_back(custom<D>("position", KeyKind::Triple, "where its origin stands",
                            [](const KeyValue& v, D& d) { d.placement.position = v.triple(); })
                      .within(Range{-1e7, 1e7, "metres"})
                      .shows("[0, 0, 0]"));
  table.push_back(custom<D>("rotation", KeyKind::Number, "turned about z",
                            [](const KeyValue& v, D& d) { d.placement.rotation = v.number(); })
                      .within(Range{-360, 360, "degrees"})
                      .shows("0"));
  table.push_back(custom<D>("scale", KeyKind::Number, "scaled by, about its origin",
                            [](const KeyValue& v, D& d) { d.placement.scale = v.number(); })
                      .within(Range{1e-6, 1e6, ""})
                      .shows("1"));
}

// bark, leaf and treemaker: the species' looks and weights overridden, of a [[tree]] or a
// [[forest]].
template <class D>
void add_overrides(std::vector<Key<D>>& table) {
  table.push_back(custom<D>("bark", KeyKind::Table, "overrides of the species' bark ([.bark])",
                            [](const KeyValue& v, D& d) {
                              read_keys(v.reader, v.table(), v.name, "[" + v.name + "]",
                                        bark_keys(), d.bark);
                            }));
  table.push_back(custom<D>("leaf", KeyKind::Table, "overrides of the species' leaves ([.leaf])",
                            [](const KeyValue& v, D& d) {
                              read_keys(v.reader, v.table(), v.name, "[" + v.name + "]",
                                        leaf_keys(), d.leaf);
                            }));
  table.push_back(custom<D>(
      "treemaker", KeyKind::Table, "the TREE-MAKER shading weights ([.treemaker])",
      [](const KeyValue& v, D& d) {
        read_keys(v.reader, v.table(), v.name, "[" + v.name + "]", treemaker_keys(), d.treemaker);
      }));
}

}  // namespace

const std::vector<Key<spec::TreeDesc>>& tree_keys() {
  using T = spec::TreeDesc;
  static const std::vector<Key<T>> table = [] {
    std::vector<Key<T>> t = {
        file("species", &T::species,
             "the species file: TOML, Arbaro XML, L-system, TREE-MAKER template or skeleton")
            .shows("required"),
        value("seed", &T::seed, kAnySeed, "the tree's seed"),
        value("time", &T::time, Range{-1e6, 1e6, ""},
              "seconds of wind for swaying models; years of age for the fractal model"),
    };
    add_placement(t);
    add_overrides(t);
    return t;
  }();
  return table;
}

const std::vector<Key<spec::ForestDesc>>& forest_keys() {
  using F = spec::ForestDesc;
  static const std::vector<Key<F>> table = [] {
    std::vector<Key<F>> t = {
        file("species", &F::species, "the species file, as [[tree]]'s").shows("required"),
        value("count", &F::count, Range{1, 1e7, "trees"}, "trees scattered over the area"),
        value("variants", &F::variants, Range{1, 1e4, "trees"},
              "distinct trees grown (at most count); the others are instances of them"),
        value("seed", &F::seed, kAnySeed, "the seed of the variants and their places"),
        value("area", &F::area, Range{}, "[[x0, y0], [x1, y1]]: the rectangle they stand in"),
    };
    add_overrides(t);
    return t;
  }();
  return table;
}

const std::vector<Key<spec::CommunitySpecies>>& community_species_keys() {
  using C = spec::CommunitySpecies;
  static const std::vector<Key<C>> table = [] {
    std::vector<Key<C>> t = {
        file("species", &C::species, "the species file, as [[tree]]'s").shows("required"),
        value("variants", &C::variants, Range{1, 1024, "trees"},
              "distinct trees grown; every plant is one of them, scaled to its size"),
        value("sown", &C::sown, Range{0, 10, "per m²"},
              "established in the first year, where the habitat is ideal (an even-aged stand)"),
        value("seedlings", &C::seedlings, Range{0, 10, "per m² per year"},
              "established anywhere, where the habitat is ideal"),
        value("seeds", &C::seeds, Range{0, 1000, "per year"},
              "seeds a plant past half its maturity disperses"),
        value("dispersal", &C::dispersal, Range{0.1, 10000, "metres"},
              "the mean distance of a seed from its parent"),
        value("radius", &C::radius, Range{0.05, 100, "metres"},
              "the circle of influence at maturity (about the crown's)"),
        value("maturity", &C::maturity, Range{1, 10000, "years"},
              "years to 95 % of the full radius"),
        value("lifespan", &C::lifespan, Range{1, 10000, "years"},
              "older plants die at 10 % a year"),
        value("shade_tolerance", &C::shade_tolerance, Range{0, 0.999, ""},
              "a plant overtopped by a taller species' chance to live another year (by its own "
              "kind, it dies)"),
        value("altitude_min", &C::altitude_min, Range{-1e5, 1e5, "metres"},
              "above the terrain's lowest point")
            .shows("no limit"),
        value("altitude_max", &C::altitude_max, Range{-1e5, 1e5, "metres"},
              "above the terrain's lowest point")
            .shows("no limit"),
        value("slope_max", &C::slope_max, Range{0, 90, "degrees"}, "the steepest it grows on"),
        value("aspect", &C::aspect, Range{0, 360, "degrees"},
              "the way its favourite slopes face, clockwise from north (180: south)"),
        value("aspect_preference", &C::aspect_preference, Range{0, 1, ""},
              "0: any aspect; 1: only slopes facing `aspect`"),
        value("moisture_min", &C::moisture_min, Range{0, 1, ""},
              "the terrain's flow moisture (0: ridges, 1: the valley's floor)"),
        value("moisture_max", &C::moisture_max, Range{0, 1, ""}, "as moisture_min"),
    };
    add_overrides(t);
    return t;
  }();
  return table;
}

const std::vector<Key<spec::BarkOverride>>& bark_keys() {
  using B = spec::BarkOverride;
  static const std::vector<Key<B>> table = {
      value("albedo", &B::albedo, look_range::kColour, "the bark's albedo").shows("the species'"),
      file("bump_map", &B::bump_map, "a height image for the relief").shows("none: procedural"),
      value("bump_height", &B::bump_height, look_range::kBumpHeight, "the relief's depth")
          .shows("the species'"),
      value("bump_tile", &B::bump_tile, look_range::kBumpTile,
            "along and around the limb per repeat of bump_map and albedo_map"),
      value("roughness", &B::roughness, look_range::kBarkRoughness, "Oren–Nayar's σ")
          .shows("the species'"),
      file("albedo_map", &B::albedo_map, "an image multiplying the albedo"),
  };
  return table;
}

const std::vector<Key<spec::LeafOverride>>& leaf_keys() {
  using L = spec::LeafOverride;
  static const std::vector<Key<L>> table = {
      value("reflectance", &L::reflectance, look_range::kColour, "the upper side's")
          .shows("the species'"),
      value("back_reflectance", &L::back_reflectance, look_range::kColour, "the lower side's")
          .shows("the species'"),
      value("transmittance", &L::transmittance, look_range::kColour, "through the leaf")
          .shows("the species'"),
      file("albedo_map", &L::albedo_map, "an image over the leaf multiplying all three"),
      value("cuticle_ior", &L::cuticle_ior, look_range::kCuticleIor, "the waxy coat's")
          .shows("the species'"),
      value("cuticle_roughness", &L::cuticle_roughness, look_range::kCuticleRoughness,
            "the coat's GGX roughness")
          .shows("the species'"),
      value("variation", &L::variation, look_range::kLeafVariation, "each leaf's own brightness")
          .shows("the species'"),
      value("hue_variation", &L::hue_variation, look_range::kLeafVariation,
            "each leaf's own chlorophyll")
          .shows("the species'"),
      value("crown_gradient", &L::crown_gradient, look_range::kCrownGradient,
            "sun leaves above, shade leaves below")
          .shows("the species'"),
      value("veins", &L::veins, look_range::kVeins, "the procedural texture's strength")
          .shows("the species'"),
      custom<L>(
          "season", KeyKind::Choice, "the leaves' colours of the season",
          [](const KeyValue& v, L& l) { l.season = static_cast<generator::Season>(v.choice()); })
          .of(choices_of(generator::kSeasonNames))
          .shows("the species'"),
  };
  return table;
}

const std::vector<Key<spec::TreemakerOverride>>& treemaker_keys() {
  using W = spec::TreemakerOverride;
  // The template language's own range for these weights (treemaker-format.md).
  constexpr Range kWeight{0, 10, ""};
  static const std::vector<Key<W>> table = {
      value("ambient", &W::ambient, kWeight, "§III's ambient weight").shows("the template's"),
      value("lambert", &W::lambert, kWeight, "§III's Lambert weight").shows("the template's"),
      value("height", &W::height, kWeight, "§III's height weight").shows("the template's"),
      value("radius", &W::radius, kWeight, "§III's radius weight").shows("the template's"),
      value("angle", &W::angle, kWeight, "§III's angle weight").shows("the template's"),
  };
  return table;
}

const std::vector<Key<spec::MeshMaterialDesc>>& mesh_material_keys() {
  using M = spec::MeshMaterialDesc;
  static const std::vector<Key<M>> table = {
      custom<M>(
          "kind", KeyKind::Choice, "\"bark\" and \"diffuse\" are Lambertian; \"leaf\" two-sided",
          [](const KeyValue& v, M& m) { m.kind = kMaterialKinds[v.choice()]; },
          [](const M& m) { return m.kind; })
          .of(choices_of(kMaterialKinds))
          .shows("\"diffuse\""),
      value("albedo", &M::albedo, look_range::kColour, "bark, diffuse: the albedo"),
      value("reflectance", &M::reflectance, look_range::kColour, "leaf: the upper side's"),
      value("back_reflectance", &M::back_reflectance, look_range::kColour,
            "leaf: the lower side's"),
      value("transmittance", &M::transmittance, look_range::kColour, "leaf: through it"),
      value("cuticle_ior", &M::cuticle_ior, look_range::kCuticleIor, "leaf: the coat's"),
      value("cuticle_roughness", &M::cuticle_roughness, look_range::kCuticleRoughness,
            "leaf: the coat's GGX roughness"),
  };
  return table;
}

const std::vector<Key<spec::MeshDesc>>& mesh_keys() {
  using M = spec::MeshDesc;
  static const std::vector<Key<M>> table = [] {
    std::vector<Key<M>> t = {
        file("path", &M::path, "the Wavefront OBJ").shows("required"),
        custom<M>(
            "up", KeyKind::Choice, "the file's up axis (\"y\": turned to z up)",
            [](const KeyValue& v, M& m) { m.up = kUpNames[v.choice()]; },
            [](const M& m) { return m.up; })
            .of(choices_of(kUpNames))
            .shows("\"z\""),
        custom<M>("material", KeyKind::Table,
                  "[mesh.material.NAME]: the material of the faces of OBJ group or material NAME",
                  [](const KeyValue& v, M& m) {
                    for (auto&& [key, node] : v.table()) {
                      const std::string name(key.str());
                      const std::string owner = v.name + "." + name;
                      spec::MeshMaterialDesc& d = m.materials[name];
                      read_keys(v.reader, v.reader.table(node, owner), owner, owner,
                                mesh_material_keys(), d);
                      if (d.kind == "leaf" &&
                          !generator::leaf_conserves_energy(d.reflectance, d.back_reflectance,
                                                            d.transmittance)) {
                        throw InputError(v.reader.at(node.source()),
                                         owner + ": " + generator::kLeafEnergyRule);
                      }
                    }
                  }),
    };
    add_placement(t);
    return t;
  }();
  return table;
}

const std::vector<Key<spec::MeadowDesc>>& meadow_keys() {
  using M = spec::MeadowDesc;
  static const std::vector<Key<M>> table = {
      value("density", &M::density, Range{0, 50000, "blades per square metre"},
            "grass blades; 0: no meadow"),
      value("area", &M::area, Range{}, "[[x0, y0], [x1, y1]], rounded out to whole tiles"),
      value("height", &M::height, Range{0.01, 3, "metres"}, "the blades' median height"),
      value("height_spread", &M::height_spread, kUnit, "σ of ln height"),
      value("width", &M::width, Range{0.0005, 0.05, "metres"}, "a blade's width at its base"),
      value("clumping", &M::clumping, kUnit, "the share of blades in tufts"),
      value("lean", &M::lean, Range{0, 80, "degrees"}, "the blades' typical lean from upright"),
      value("bend", &M::bend, kUnit, "how far gravity bends a leaning blade over"),
      value("dry", &M::dry, kUnit, "the share of dead, straw-coloured blades"),
      value("wind", &M::wind, Range{0, 30, "m/s"},
            "bends the blades downwind (and sways them in [animation])"),
      value("wind_direction", &M::wind_direction, Range{-360, 360, "degrees"},
            "the direction the wind blows towards, about z"),
      value("tile", &M::tile, Range{0.1, 10, "metres"}, "the side of a tile of blades"),
      value("tiles", &M::tiles, Range{1, 64, "tiles"}, "distinct tiles, turned and shuffled"),
      value("seed", &M::seed, kAnySeed, "the meadow's seed"),
      value("reflectance", &M::reflectance, kUnit, "a blade's upper side"),
      value("back_reflectance", &M::back_reflectance, kUnit, "a blade's lower side"),
      value("transmittance", &M::transmittance, kUnit, "through a blade"),
      value("dry_reflectance", &M::dry_reflectance, kUnit, "a dead blade's"),
  };
  return table;
}

}  // namespace arbor::formats
