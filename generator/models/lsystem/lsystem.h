// L-systems in Borenszweig's language (docs/lsystem-format.md), interpreted by a 3D turtle into
// a Skeleton.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/error.h"
#include "generator/grow_options.h"
#include "generator/skeleton.h"

namespace arbor::generator {

// One action of a rule body.
struct LAction {
  enum Kind : char {
    Forward = 'f',
    TurnLeft = '+',
    TurnRight = '-',
    RollLeft = '<',
    RollRight = '>',
    PitchDown = 'v',
    PitchUp = '^',
    ScaleStep = 's',
    ScaleRoll = 'h',
    ScaleYaw = 'u',
    ScalePitch = 'l',
    ScaleRadius = 'r',
    Rule = 'R',
    Branch = '[',
  };
  Kind kind = Forward;
  bool has_number = false;
  double number = 0.0;
  char rule = 0;                // for Rule
  std::vector<LAction> branch;  // for Branch
  SourceLocation where;
};

struct LRule {
  char name = 0;
  double weight = 1.0;  // the optional number after the name: weight among same-named rules
  std::vector<LAction> body;
  SourceLocation where;
};

struct LSystem {
  std::string path;
  int iterations = 4;
  double step = 1.0;        // metres per f
  double angle = 25.0;      // degrees per turn
  double radius = 0.05;     // metres, at the start
  double randomness = 0.0;  // relative variation of every step and turn
  int leaves = 0;           // leaves at the tip of every stem that has no branches
  double leaf_length = 0.1, leaf_width = 0.05;  // metres
  int leaf_shape = 0;
  std::vector<LRule> rules;  // the first rule's name is the axiom
};

// Upper estimate of the number of f segments the system draws (for the size limit).
double estimate_segments(const LSystem& system);

// The L-system reads seed, force and max_stems (the most segments it may draw).
using LSystemOptions = GrowOptions;

// Interprets the system with a 3D turtle (heading +z, up +y at the start). Deterministic.
Skeleton grow_lsystem(const LSystem& system, const LSystemOptions& options);

}  // namespace arbor::generator
