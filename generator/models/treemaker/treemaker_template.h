// TREE-MAKER tree templates (Neighbors & Hodges, Figure 6): the language as plain data.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "common/error.h"

namespace arbor::generator {

struct TmRange {
  double lo = 0.0, hi = 0.0;
};

// The five weights of the approximate shading formula (§III).
// The shading weights a template's `light {}` section sets (§III); unset ones keep arbor's
// defaults, applied where the scene is built.
struct TmLight {
  std::optional<double> ambient, lambert, height, radius, angle;
};

struct TmColor {
  std::string name;
  glm::dvec3 rgb{1.0};
};

// One (p angle dir factor) triplet of a branching rule.
struct TmBranchChoice {
  double p = 1.0;
  TmRange angle, dir, factor;
};

struct TmBranchRule {
  int level = 1;
  TmRange number;
  std::vector<TmBranchChoice> choices;
  SourceLocation where;
};

struct TmParticle {
  glm::dvec3 pos{0.0};
  TmRange mag{1.0, 1.0};
  glm::dvec3 dir{0.0, 0.0, 1.0};
  double max_deviation = 0.0;  // degrees
  double acc = 0.0;            // added to both ends of the magnitude range each iteration
  double growth = 0.0;         // width added to every stored position each iteration
  double age = 0.0;            // added to growth each iteration
  std::string color;
  TmRange brightness{1.0, 1.0};
  SourceLocation where;
};

// A triangle (three points) or a line (two) in leaf coordinates, with its colour.
struct TmElement {
  bool line = false;
  std::array<glm::dvec3, 3> v{};
  std::string color;
  TmRange brightness{1.0, 1.0};
};

struct TmLeaf {
  double p = 1.0;
  bool limb_coords = false;    // coord= limb (else leaf)
  double out = 0.0, up = 0.0;  // degrees of deviation
  std::vector<TmElement> elements;
  SourceLocation where;
};

struct TreeMakerTemplate {
  std::string path;
  int iterations = 10;
  double gravity = 0.0;
  TmLight light;
  std::vector<TmColor> colors;
  std::vector<TmBranchRule> branches;  // by level, ascending
  std::vector<TmParticle> particles;
  std::vector<TmLeaf> leaves;

  const TmColor* color(const std::string& name) const;
  // The rule for a level: its own, or the nearest lower level's (§IV).
  const TmBranchRule* rule_for(int level) const;
};

}  // namespace arbor::generator
