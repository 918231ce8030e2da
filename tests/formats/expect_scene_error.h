// A scene text refused by the reader at a line and column with a message holding `fragment`.
#pragma once

#include <string>

#include "expect_input_error.h"
#include "formats/scene_file.h"

namespace arbor::formats {

inline void expect_scene_error(const std::string& text, int line, int column,
                               const std::string& fragment) {
  testing::expect_input_error([&] { parse_scene(text, "s.toml"); }, "s.toml", line, column,
                              fragment);
}

}  // namespace arbor::formats
