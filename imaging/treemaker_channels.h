// The channels of the "treemaker" AOV (TREE-MAKER's five shading factors, Neighbors & Hodges
// 1990 §III, Figure 3): what the treemaker integrator writes and the weight fit reads.
#pragma once

#include <string>
#include <vector>

namespace arbor::imaging {

// The factors in Figure 3's order: 1, N·L, h/h0, r/r0, sin(q/2).
inline constexpr const char* kTreemakerTermNames[5] = {"ambient", "lambert", "height", "radius",
                                                       "angle"};

// EXR channel names of the "treemaker" AOV, in the order render writes them: the factors
// "term_ambient.X" … "term_angle.X", the contributions "tm_ambient.R" … "tm_angle.B",
// "tm_rest.R/G/B". Every name is PASS.CHANNEL with a one-letter channel, as Blender's multilayer
// reader and Nuke's layer.channel convention need.
inline std::vector<std::string> treemaker_channel_names() {
  std::vector<std::string> names;
  for (const char* t : kTreemakerTermNames) names.push_back(std::string("term_") + t + ".X");
  for (const char* t : kTreemakerTermNames) {
    for (const char* c : {".R", ".G", ".B"}) names.push_back(std::string("tm_") + t + c);
  }
  for (const char* c : {".R", ".G", ".B"}) names.push_back(std::string("tm_rest") + c);
  return names;
}

}  // namespace arbor::imaging
