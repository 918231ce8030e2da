// Internal to formats/: the checked reading of TOML values that the species and scene readers
// share. Every failure is an InputError at the value's file, line and column.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>

#include <toml++/toml.h>

#include "common/error.h"
#include "common/range.h"

namespace arbor::formats {

class TomlReader {
 public:
  explicit TomlReader(std::string path) : path_(std::move(path)) {}

  const std::string& path() const { return path_; }

  // Keys of more dotted parts than this are refused before toml++ sees them: it builds a nested
  // table per part recursively, and 50,000 parts overflowed the stack. No arbor key has more
  // than four.
  static constexpr int kMaxKeyParts = 64;

  // The whole document; a syntax error is reported where toml++ found it.
  toml::table parse(std::string_view text) const {
    check_key_depth(text);
    try {
      return toml::parse(text, path_);
    } catch (const toml::parse_error& e) {
      throw InputError(at(e.source()), std::string(e.description()));
    }
  }

  // InputError at the first key (of a table header or a key/value line) with more than
  // kMaxKeyParts dotted parts. Quoted parts may hold dots; multi-line strings are skipped.
  void check_key_depth(std::string_view text) const {
    bool in_multiline = false;
    std::string_view delimiter;
    int line = 1;
    for (std::size_t start = 0; start < text.size(); ++line) {
      std::size_t end = text.find('\n', start);
      if (end == std::string_view::npos) end = text.size();
      const std::string_view l = text.substr(start, end - start);
      start = end + 1;
      if (in_multiline) {
        if (l.find(delimiter) != std::string_view::npos) in_multiline = false;
        continue;
      }
      std::size_t i = l.find_first_not_of(" \t");
      if (i == std::string_view::npos || l[i] == '#') continue;
      const bool header = l[i] == '[';
      int parts = 1;
      char quote = 0;
      std::size_t j = i;
      for (; j < l.size(); ++j) {
        const char c = l[j];
        if (quote) {
          if (c == '\\' && quote == '"')
            ++j;
          else if (c == quote)
            quote = 0;
        } else if (c == '"' || c == '\'') {
          quote = c;
        } else if (c == '.') {
          ++parts;
        } else if ((header && c == ']' && j > i + 1 && l[j - 1] != '[') || (!header && c == '=')) {
          break;
        }
        if (parts > kMaxKeyParts) {
          throw InputError({path_, line, static_cast<int>(i) + 1},
                           "a key of more than " + std::to_string(kMaxKeyParts) + " dotted parts");
        }
      }
      // A value that opens a multi-line string ends only at its closing delimiter.
      for (std::string_view d : {std::string_view("\"\"\""), std::string_view("'''")}) {
        const std::size_t open = l.find(d, j);
        if (open != std::string_view::npos && l.find(d, open + 3) == std::string_view::npos) {
          in_multiline = true;
          delimiter = d;
        }
      }
    }
  }

  SourceLocation at(const toml::source_region& r) const {
    return {path_, static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
  }
  [[noreturn]] void fail(const toml::node& n, const std::string& message) const {
    throw InputError(at(n.source()), message);
  }

  // A finite number (an integer is accepted).
  double number(const toml::node& n, std::string_view name) const {
    std::optional<double> v;
    if (n.is_floating_point() || n.is_integer()) v = n.value<double>();
    if (!v) fail(n, std::string(name) + " must be a number");
    if (!std::isfinite(*v)) fail(n, std::string(name) + " must be a finite number");
    return *v;
  }
  // A finite number in [lo, hi].
  double number(const toml::node& n, std::string_view name, double lo, double hi) const {
    return number(n, name, Range{lo, hi, ""});
  }
  // A finite number in a value's stated range (common/range.h).
  double number(const toml::node& n, std::string_view name, const Range& range) const {
    const double v = number(n, name);
    if (!range.contains(v)) {
      fail(n, std::string(name) + " = " + short_number(v) + " is out of range " + range.text());
    }
    return v;
  }
  std::int64_t integer(const toml::node& n, std::string_view name, std::int64_t lo,
                       std::int64_t hi) const {
    if (!n.is_integer()) fail(n, std::string(name) + " must be a whole number");
    const std::int64_t v = *n.value<std::int64_t>();
    if (v < lo || v > hi) {
      fail(n, std::string(name) + " = " + std::to_string(v) + " is out of range [" +
                  std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
    return v;
  }
  std::string text(const toml::node& n, std::string_view name) const {
    if (!n.is_string()) fail(n, std::string(name) + " must be a string");
    return *n.value<std::string>();
  }
  // One of `options`; the message lists them.
  std::string choice(const toml::node& n, std::string_view name,
                     std::initializer_list<const char*> options) const {
    return options.begin()[choice_index(n, name, options.begin(), options.size())];
  }
  // The index of the one of `options` (a type's table of names) that `n` names.
  template <std::size_t N>
  std::size_t choice_index(const toml::node& n, std::string_view name,
                           const std::array<const char*, N>& options) const {
    return choice_index(n, name, options.data(), N);
  }
  std::size_t choice_index(const toml::node& n, std::string_view name, const char* const* options,
                           std::size_t count) const {
    const std::string v = text(n, name);
    std::string list;
    for (std::size_t i = 0; i < count; ++i) {
      if (v == options[i]) return i;
      list += std::string(list.empty() ? "" : ", ") + "\"" + options[i] + "\"";
    }
    fail(n, std::string(name) + " must be one of " + list + ", not \"" + v + "\"");
  }
  bool boolean(const toml::node& n, std::string_view name) const {
    if (!n.is_boolean()) fail(n, std::string(name) + " must be true or false");
    return *n.value<bool>();
  }
  const toml::table& table(const toml::node& n, std::string_view name) const {
    if (const toml::table* t = n.as_table()) return *t;
    fail(n, "'" + std::string(name) + "' must be a table");
  }

  // Three numbers, each in the range.
  std::array<double, 3> triple(const toml::node& n, const std::string& name,
                               const Range& range) const {
    const toml::array* a = n.as_array();
    if (!a || a->size() != 3) fail(n, name + " must be an array of 3 numbers");
    return {number(*a->get(0), name, range), number(*a->get(1), name, range),
            number(*a->get(2), name, range)};
  }
  std::array<double, 3> triple(const toml::node& n, const std::string& name, double lo,
                               double hi) const {
    const toml::array* a = n.as_array();
    if (!a || a->size() != 3) fail(n, name + " must be an array of 3 numbers");
    return {number(*a->get(0), name, lo, hi), number(*a->get(1), name, lo, hi),
            number(*a->get(2), name, lo, hi)};
  }
  // An axis-aligned rectangle [[x0, y0], [x1, y1]] of the ground, as {x0, y0, x1, y1}.
  std::array<double, 4> area(const toml::node& n, const std::string& name) const {
    const toml::array* a = n.as_array();
    if (!a || a->size() != 2 || !a->get(0)->is_array() || !a->get(1)->is_array() ||
        a->get(0)->as_array()->size() != 2 || a->get(1)->as_array()->size() != 2) {
      fail(n, name + " must be [[x0, y0], [x1, y1]]");
    }
    const toml::array& lo = *a->get(0)->as_array();
    const toml::array& hi = *a->get(1)->as_array();
    const std::array<double, 4> r = {
        number(*lo.get(0), name, -1e7, 1e7), number(*lo.get(1), name, -1e7, 1e7),
        number(*hi.get(0), name, -1e7, 1e7), number(*hi.get(1), name, -1e7, 1e7)};
    if (!(r[2] > r[0] && r[3] > r[1]))
      fail(n, name + " must go from the smaller corner to the larger one");
    return r;
  }

 private:
  std::string path_;
};

}  // namespace arbor::formats
