// The smallest complete TREE-MAKER template's parts (one rule, one colour, one particle, one
// leaf), shared by the reader's tests (tests/formats) and the growth's (tests/generator).
#pragma once

#include <string>

namespace arbor::testing {

inline const std::string kTmRule =
    "branch { level= 1 number= 1 to 2 (p=1 angle= 30 to 40 dir= 0 to 360 factor= 0.5 to 0.6) }\n";
inline const std::string kTmColor = "color { green= 0,1,0 }\n";
inline const std::string kTmParticle =
    "particle { pos=0,0,0 mag= 10 to 12 dir= 0,0,1:5 growth= 0.2 color= green brightness= 0.5 to "
    "0.6 }\n";
inline const std::string kTmLeaf =
    "leaf { p= 1 coord= limb out= 10 up= 10 color= green brightness= 0.5 to 0.6 tri= 0,0,0 1,0,1 "
    "-1,0,1 }\n";

}  // namespace arbor::testing
