// A species: which tree model grows it, its parameters, and its default bark and leaf looks.
#pragma once

#include <array>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "common/error.h"
#include "generator/fractal.h"
#include "generator/lsystem.h"
#include "generator/skeleton.h"
#include "generator/treemaker_template.h"
#include "generator/weber_penn_params.h"

namespace arbor::gen {

using Rgb = std::array<double, 3>;

// Default bark of the species (scene files may override it).
struct BarkLook {
  Rgb albedo{0.30, 0.26, 0.22};
  double bump_height = 0.004;  // metres of relief
  double roughness = 0.0;      // degrees: Oren–Nayar slope deviation σ (0: Lambertian)
};

// Default leaves of the species: front reflectance, the lighter back, diffuse transmittance.
struct LeafLook {
  Rgb reflectance{0.06, 0.20, 0.04};
  Rgb back_reflectance{0.10, 0.24, 0.07};
  Rgb transmittance{0.05, 0.18, 0.03};
  double hinge_angle = 0.0;  // degrees; > 0: Bloomenthal's hinged three-polygon leaf (§10)
};

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
  // Non-fatal notes from reading the file ("path:line:col: warning: …"), to show the user.
  std::vector<std::string> warnings;
};

// Reads a species file, choosing the format by extension: .toml (arbor's format, `model =`
// says which model) or .xml (an Arbaro Weber & Penn parameter file). Throws InputError with
// the position of the problem.
Species load_species(const std::string& path);

// The two readers, from text already in memory (path is used in messages).
Species parse_species_toml(std::string_view text, const std::string& path);
Species parse_arbaro_xml(std::string_view text, const std::string& path);

// The last step of every reader: checks the rules that involve several parameters (pointing at the
// offending key's position, looked up in `positions` by paper name) and names an unnamed species
// after its file. Throws InputError.
void finish_species(Species& species,
                    const std::map<std::string, SourceLocation>& positions);

// Reads a whole file; throws InputError when it cannot be read.
std::string read_text_file(const std::string& path);

}  // namespace arbor::gen
