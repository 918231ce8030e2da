// Tests of the diagnostic format shared by every input error.
#include "common/error.h"

#include <gtest/gtest.h>

namespace arbor {

TEST(InputError, FormatsPathLineColumn) {
  const InputError e({"tree.toml", 12, 5}, "unknown key 'Shap'");
  EXPECT_STREQ(e.what(), "tree.toml:12:5: error: unknown key 'Shap'");
  EXPECT_EQ(e.where().line, 12);
  EXPECT_EQ(e.message(), "unknown key 'Shap'");
}

TEST(InputError, LeavesOutUnknownParts) {
  EXPECT_STREQ(InputError({"tree.toml", 0, 0}, "cannot open").what(),
               "tree.toml: error: cannot open");
  EXPECT_STREQ(InputError({"a.xml", 3, 0}, "x").what(), "a.xml:3: error: x");
  EXPECT_STREQ(InputError({}, "bad option").what(), "error: bad option");
}

}  // namespace arbor
