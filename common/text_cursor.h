// A read position in a text file that keeps the line and column (from 1) for diagnostics:
// the shared core of arbor's hand-written lexers (L-systems, TREE-MAKER templates).
#pragma once

#include <cstddef>
#include <string>

#include "common/error.h"

namespace arbor {

class TextCursor {
 public:
  // `text` must outlive the cursor.
  TextCursor(const std::string& text, std::string path) : text_(text), path_(std::move(path)) {}

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return text_[pos_]; }  // only when !at_end()
  SourceLocation here() const { return {path_, line_, column_}; }
  const std::string& path() const { return path_; }

  // Steps over one character, starting a new line after '\n'.
  void advance() {
    if (text_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++pos_;
  }

 private:
  const std::string& text_;
  std::string path_;
  std::size_t pos_ = 0;
  int line_ = 1, column_ = 1;
};

}  // namespace arbor
