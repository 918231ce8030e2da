// A species: which tree model grows it (a variant over the models' parameters), and its default
// bark and leaf looks.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "common/error.h"
#include "materials/looks.h"
#include "generator/models/fractal/fractal.h"
#include "generator/models/lsystem/lsystem.h"
#include "generator/skeleton.h"
#include "generator/models/treemaker/treemaker_template.h"
#include "generator/models/weber_penn/weber_penn_params.h"

namespace arbor::gen {

// The species' default looks (materials/looks.h).
using mat::BarkLook;
using mat::LeafLook;

// The models, in the order of ModelParams' alternatives.
enum class Model { WeberPenn, LSystem, SkeletonFile, Fractal, TreeMaker };

// Which model grows a species, with that model's parameters.
using ModelParams = std::variant<WeberPennParams, LSystem, Skeleton, FractalParams, TreeMakerTemplate>;

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
  // The species' own TREE-MAKER shading weights (a template's `light {}`); unset: arbor's defaults.
  std::optional<mat::TreemakerWeights> treemaker_weights;
  // Non-fatal notes from reading the file ("path:line:col: warning: …"), to show the user.
  std::vector<std::string> warnings;
};

// The last step of every reader: checks the rules that involve several parameters (pointing at the
// offending key's position, looked up in `positions` by paper name) and names an unnamed species
// after its file. Throws InputError.
void finish_species(Species& species,
                    const std::map<std::string, SourceLocation>& positions);

}  // namespace arbor::gen
