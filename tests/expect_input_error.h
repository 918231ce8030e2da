// Test helper: expects a parser to refuse input with an InputError at a path, line and column
// whose message contains a fragment.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "common/error.h"

namespace arbor::testing {

template <typename Parse>
void expect_input_error(Parse&& parse, const std::string& path, int line, int column,
                        const std::string& fragment) {
  try {
    parse();
    ADD_FAILURE() << "accepted input that should fail with: " << fragment;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().path, path);
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_EQ(e.where().column, column) << e.what();
    EXPECT_NE(e.message().find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace arbor::testing
