// A species: which tree model grows it, its parameters, and its default bark and leaf looks.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
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

enum class Model { WeberPenn, LSystem, SkeletonFile, Fractal, TreeMaker };

struct Species {
  std::string name;
  std::string path;
  Model model = Model::WeberPenn;
  WeberPennParams weber_penn;  // for Model::WeberPenn
  LSystem lsystem;             // for Model::LSystem
  Skeleton skeleton;           // for Model::SkeletonFile
  FractalParams fractal;       // for Model::Fractal
  TreeMakerTemplate treemaker; // for Model::TreeMaker
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
