// Reader of arbor's TOML species format (docs/species-format.md): paper parameter names, one
// table per level, [bark] and [leaf] looks. Unknown keys and bad values are errors with position.
#include <cmath>
#include <map>
#include <string>

#include <toml++/toml.h>

#include "formats/toml_reader.h"

#include "generator/species.h"
#include "formats/species_file.h"

namespace arbor::formats {

namespace {

namespace look_range = generator::look_range;

class TomlSpecies : TomlReader {
 public:
  explicit TomlSpecies(const std::string& path) : TomlReader(path) {}

  Rgb colour(const toml::node& node, std::string_view name) const {
    const toml::array* a = node.as_array();
    if (!a || a->size() != 3) {
      throw InputError(at(node.source()), std::string(name) + " must be an array of 3 numbers");
    }
    Rgb c{};
    for (size_t i = 0; i < 3; ++i) {
      c[i] = number(*a->get(i), name, look_range::kColour);
    }
    return c;
  }

  void param(generator::Species& sp, const generator::ParamInfo& info, int level,
             const toml::node& node, const std::string& paper_name) {
    if (info.integer && !node.is_integer()) {
      throw InputError(at(node.source()), paper_name + " must be a whole number");
    }
    const std::string problem =
        generator::set_param(sp.weber_penn(), info, level, number(node, paper_name));
    if (!problem.empty()) {
      throw InputError(
          at(node.source()),
          (level >= 0 && !info.real && !info.whole ? std::to_string(level) : "") + problem);
    }
    positions_[paper_name] = at(node.source());
  }

  void levels(generator::Species& sp, const toml::table& levels) {
    for (auto&& [key, node] : levels) {
      const std::string k(key.str());
      if (k.size() != 1 || k[0] < '0' || k[0] > '3') {
        throw InputError(at(key.source()), "unknown level '" + k +
                                               "': levels are 0 (trunk) to 3; deeper levels "
                                               "reuse level 3");
      }
      const int level = k[0] - '0';
      for (auto&& [pkey, pnode] : table(node, "level." + k)) {
        const std::string name(pkey.str());
        const generator::ParamInfo* info = generator::find_level_param(name);
        if (!info) {
          throw InputError(at(pkey.source()), "unknown key '" + name + "' in [level." + k + "]");
        }
        if (info->level0_only && level != 0) {
          throw InputError(at(pkey.source()), name + " is a trunk parameter: put it in [level.0]");
        }
        if (info->children_only && level == 0) {
          throw InputError(at(pkey.source()),
                           name + " has no meaning for the trunk (level 0): remove it");
        }
        param(sp, *info, level, pnode, k + name);
      }
    }
  }

  void bark(generator::Species& sp, const toml::table& t) {
    for (auto&& [key, node] : t) {
      const std::string k(key.str());
      if (k == "albedo") {
        sp.bark.albedo = colour(node, "bark.albedo");
      } else if (k == "bump_height") {
        sp.bark.bump_height = number(node, "bark.bump_height", look_range::kBumpHeight);
      } else if (k == "roughness") {
        sp.bark.roughness = number(node, "bark.roughness", look_range::kBarkRoughness);
      } else if (k == "furrow_albedo") {
        sp.bark.furrow_albedo = colour(node, "bark.furrow_albedo");
      } else if (k == "lenticels") {
        sp.bark.lenticels = number(node, "bark.lenticels", look_range::kLenticels);
      } else if (k == "lenticel_albedo") {
        sp.bark.lenticel_albedo = colour(node, "bark.lenticel_albedo");
      } else if (k == "scars") {
        sp.bark.scars = number(node, "bark.scars", look_range::kScars);
      } else if (k == "scar_albedo") {
        sp.bark.scar_albedo = colour(node, "bark.scar_albedo");
      } else if (k == "base_height") {
        sp.bark.base_height = number(node, "bark.base_height", look_range::kBaseHeight);
      } else if (k == "ramiform") {
        sp.bark.ramiform = boolean(node, "bark.ramiform");
      } else {
        throw InputError(at(key.source()), "unknown key '" + k + "' in [bark]");
      }
    }
  }

  void roots(generator::Species& sp, const toml::table& t) {
    for (auto&& [key, node] : t) {
      const std::string k(key.str());
      if (k != "buttresses" && k != "height" && k != "spread") {
        throw InputError(at(key.source()), "unknown key '" + k + "' in [roots]");
      }
      const double v = number(node, "roots." + k);
      if (k == "buttresses") {
        if (v != std::floor(v) || v < 0.0 || v > 16.0)
          throw InputError(at(node.source()), "roots.buttresses must be a whole number in [0, 16]");
        sp.roots.buttresses = static_cast<int>(v);
      } else if (k == "height") {
        if (!(v > 0.0 && v <= 50.0))
          throw InputError(at(node.source()), "roots.height must be in (0, 50] trunk radii");
        sp.roots.height = v;
      } else {
        if (!(v > 0.0 && v <= 20.0))
          throw InputError(at(node.source()), "roots.spread must be in (0, 20] trunk radii");
        sp.roots.spread = v;
      }
    }
  }

  void leaf(generator::Species& sp, const toml::table& t) {
    for (auto&& [key, node] : t) {
      const std::string k(key.str());
      if (k == "reflectance")
        sp.leaf.reflectance = colour(node, "leaf.reflectance");
      else if (k == "back_reflectance")
        sp.leaf.back_reflectance = colour(node, "leaf.back_reflectance");
      else if (k == "transmittance")
        sp.leaf.transmittance = colour(node, "leaf.transmittance");
      else if (k == "cuticle_ior") {
        sp.leaf.cuticle_ior = number(node, "leaf.cuticle_ior", look_range::kCuticleIor);
      } else if (k == "cuticle_roughness") {
        sp.leaf.cuticle_roughness =
            number(node, "leaf.cuticle_roughness", look_range::kCuticleRoughness);
      } else if (k == "hinge_angle") {
        sp.leaf.hinge_angle = number(node, "leaf.hinge_angle", look_range::kHingeAngle);
      } else if (k == "fold") {
        sp.leaf.fold = number(node, "leaf.fold", look_range::kLeafFold);
      } else if (k == "cup") {
        sp.leaf.cup = number(node, "leaf.cup", look_range::kLeafCup);
      } else if (k == "curl") {
        sp.leaf.curl = number(node, "leaf.curl", look_range::kLeafCurl);
      } else if (k == "twist") {
        sp.leaf.twist = number(node, "leaf.twist", look_range::kLeafTwist);
      } else if (k == "petiole_length") {
        sp.leaf.petiole_length = number(node, "leaf.petiole_length", look_range::kPetioleLength);
      } else if (k == "petiole_width") {
        sp.leaf.petiole_width = number(node, "leaf.petiole_width", look_range::kPetioleWidth);
      } else if (k == "margin") {
        sp.leaf.margin.kind = static_cast<generator::LeafMargin>(
            choice_index(node, "leaf.margin", generator::kLeafMarginNames));
      } else if (k == "teeth") {
        sp.leaf.margin.teeth = static_cast<int>(integer(node, "leaf.teeth", 1, 100));
      } else if (k == "tooth_depth") {
        sp.leaf.margin.depth = number(node, "leaf.tooth_depth", look_range::kToothDepth);
      } else if (k == "variation") {
        sp.leaf.variation = number(node, "leaf.variation", look_range::kLeafVariation);
      } else if (k == "hue_variation") {
        sp.leaf.hue_variation = number(node, "leaf.hue_variation", look_range::kLeafVariation);
      } else if (k == "crown_gradient") {
        sp.leaf.crown_gradient = number(node, "leaf.crown_gradient", look_range::kCrownGradient);
      } else if (k == "veins") {
        sp.leaf.veins = number(node, "leaf.veins", look_range::kVeins);
      } else if (k == "autumn") {
        sp.leaf.autumn = colour(node, "leaf.autumn");
      } else if (k == "season") {
        sp.leaf.season = static_cast<generator::Season>(
            choice_index(node, "leaf.season", generator::kSeasonNames));
      } else if (k == "vein_pairs") {
        const double n = number(node, "leaf.vein_pairs", {1.0, 30.0, "pairs"});
        if (n != std::floor(n))
          throw InputError(at(node.source()), "leaf.vein_pairs must be a whole number in [1, 30]");
        sp.leaf.vein_pairs = static_cast<int>(n);
      } else
        throw InputError(at(key.source()), "unknown key '" + k + "' in [leaf]");
    }
    const generator::LeafLook& l = sp.leaf;
    if (l.hinge_angle > 0.0 && (l.fold != 0.0 || l.cup != 0.0 || l.curl != 0.0 || l.twist != 0.0)) {
      throw InputError(at(t.source()),
                       "[leaf] hinge_angle (Bloomenthal's three panels) and fold, cup, curl or "
                       "twist (the shaped leaf) are two ways to bend a leaf: set one");
    }
    if (!generator::leaf_conserves_energy(sp.leaf.reflectance, sp.leaf.back_reflectance,
                                          sp.leaf.transmittance)) {
      throw InputError(at(t.source()), generator::kLeafEnergyRule);
    }
  }

  // model = "fractal": Ünal's parameters (docs/fractal-format.md).
  void fractal_key(generator::Species& sp, const std::string& k, const toml::node& node,
                   const toml::key& key) {
    generator::FractalParams& f = sp.fractal();
    struct Real {
      const char* name;
      double lo, hi;
      double generator::FractalParams::*field;
    };
    struct Whole {
      const char* name;
      int lo, hi;
      int generator::FractalParams::*field;
    };
    static const Real reals[] = {
        {"cone_angle", 0, 180, &generator::FractalParams::cone_angle},
        {"size_ratio", 0.01, 1.5, &generator::FractalParams::size_ratio},
        {"taper", 0.01, 1, &generator::FractalParams::taper},
        {"length", 1e-3, 500, &generator::FractalParams::length},
        {"radius", 1e-5, 50, &generator::FractalParams::radius},
        {"twist", -360, 360, &generator::FractalParams::twist},
        {"prune", 0, 0.99, &generator::FractalParams::prune},
        {"length_variation", 0, 0.99, &generator::FractalParams::length_variation},
        {"angle_variation", 0, 0.99, &generator::FractalParams::angle_variation},
        {"wiggle", 0, 0.5, &generator::FractalParams::wiggle},
        {"radius_variation", 0, 0.5, &generator::FractalParams::radius_variation},
        {"years_per_level", 1e-3, 1e4, &generator::FractalParams::years_per_level},
        {"age", 0, 1e6, &generator::FractalParams::age},
        {"cone_widening", 0, 1, &generator::FractalParams::cone_widening},
        {"leaf_length", 1e-4, 10, &generator::FractalParams::leaf_length},
        {"leaf_width", 1e-4, 10, &generator::FractalParams::leaf_width}};
    static const Whole wholes[] = {{"depth", 1, 32, &generator::FractalParams::depth},
                                   {"branches", 1, 64, &generator::FractalParams::branches},
                                   {"discs", 2, 256, &generator::FractalParams::discs},
                                   {"leaves", 0, 1000, &generator::FractalParams::leaves},
                                   {"leaf_shape", 0, 5, &generator::FractalParams::leaf_shape}};
    for (const Real& r : reals) {
      if (k != r.name) continue;
      f.*r.field = number(node, k, Range{r.lo, r.hi, ""});
      return;
    }
    for (const Whole& w : wholes) {
      if (k != w.name) continue;
      if (!node.is_integer()) throw InputError(at(node.source()), k + " must be a whole number");
      f.*w.field = static_cast<int>(number(node, k, Range{double(w.lo), double(w.hi), ""}));
      return;
    }
    throw InputError(at(key.source()), "unknown key '" + k + "' for model = \"fractal\"");
  }

  generator::Species read(std::string_view source) {
    const toml::table root = parse(source);
    generator::Species sp;
    sp.path = path();
    bool has_model = false;
    if (const toml::node* m = root.get("model")) {
      const std::string model = text(*m, "model");
      if (model == "fractal")
        sp.params = generator::FractalParams{};
      else if (model != "weber-penn") {
        throw InputError(at(m->source()),
                         "model '" + model + "' is not known; known: weber-penn, fractal");
      }
    }
    for (auto&& [key, node] : root) {
      const std::string k(key.str());
      if (k == "model") {
        has_model = true;
      } else if (sp.model() == generator::Model::Fractal && k != "name" && k != "bark" &&
                 k != "leaf" && k != "roots") {
        fractal_key(sp, k, node, key);
      } else if (k == "name") {
        sp.name = text(node, "name");
      } else if (k == "level") {
        levels(sp, table(node, "level"));
      } else if (k == "bark") {
        bark(sp, table(node, "bark"));
      } else if (k == "leaf") {
        leaf(sp, table(node, "leaf"));
      } else if (k == "roots") {
        roots(sp, table(node, "roots"));
      } else if (const generator::ParamInfo* info = generator::find_tree_param(k)) {
        param(sp, *info, -1, node, k);
      } else if (generator::find_level_param(k)) {
        throw InputError(at(key.source()),
                         "'" + k + "' is a per-level parameter: put it in a [level.N] table");
      } else {
        throw InputError(at(key.source()), "unknown key '" + k + "'");
      }
    }
    if (!has_model) {
      throw InputError({path(), 1, 1}, "missing key 'model' (for example model = \"weber-penn\")");
    }
    generator::finish_species(sp, positions_);
    return sp;
  }

 private:
  std::map<std::string, SourceLocation> positions_;
};

}  // namespace

generator::Species parse_species_toml(std::string_view text, const std::string& path) {
  return TomlSpecies(path).read(text);
}

}  // namespace arbor::formats
