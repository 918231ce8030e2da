// Reading the L-system language (Borenszweig 2008) with arbor's directives into rules.
#include "formats/lsystem_file.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <map>

#include "common/text_cursor.h"

namespace arbor::formats {

namespace {

class Parser {
 public:
  Parser(const std::string& text, const std::string& path) : cursor_(text, path), path_(path) {}

  generator::LSystem parse() {
    generator::LSystem sys;
    sys.path = path_;
    std::map<std::string, SourceLocation> seen;
    for (skip_space(); !at_end(); skip_space()) {
      const char c = peek();
      if (c >= 'A' && c <= 'Z') {
        sys.rules.push_back(rule());
      } else if (c >= 'a' && c <= 'z') {
        const SourceLocation where = here();
        const std::string name = word();
        if (seen.count(name)) throw InputError(where, "'" + name + "' is set twice");
        seen[name] = where;
        directive(sys, name, where);
      } else {
        throw InputError(here(),
                         std::string("expected a rule (A-Z) or a setting, found '") + c + "'");
      }
    }
    if (sys.rules.empty()) throw InputError({path_, 1, 1}, "the L-system has no rules");
    // Every rule reference must name a rule.
    std::map<char, bool> defined;
    for (const generator::LRule& r : sys.rules) defined[r.name] = true;
    for (const generator::LRule& r : sys.rules) check_references(r.body, defined);
    return sys;
  }

 private:
  bool at_end() const { return cursor_.at_end(); }
  char peek() const { return cursor_.peek(); }
  SourceLocation here() const { return cursor_.here(); }
  void advance() { cursor_.advance(); }
  void skip_space() {
    while (!at_end()) {
      if (std::isspace(static_cast<unsigned char>(peek()))) {
        advance();
      } else if (peek() == '#') {
        while (!at_end() && peek() != '\n') advance();
      } else {
        break;
      }
    }
  }
  void expect(char c, const std::string& what) {
    skip_space();
    if (at_end()) throw InputError(here(), "the file ends where " + what + " was expected");
    if (peek() != c)
      throw InputError(here(), "expected " + what + ", found '" + std::string(1, peek()) + "'");
    advance();
  }
  std::string word() {
    std::string w;
    while (!at_end() && (std::islower(static_cast<unsigned char>(peek())) || peek() == '_')) {
      w += peek();
      advance();
    }
    return w;
  }
  double number() {
    skip_space();
    const SourceLocation where = here();
    std::string digits;
    while (!at_end() && (std::isdigit(static_cast<unsigned char>(peek())) || peek() == '.')) {
      digits += peek();
      advance();
    }
    if (digits.empty() || digits.front() == '.' || digits.back() == '.' ||
        digits.find('.') != digits.rfind('.')) {
      throw InputError(where, "expected a number such as 2 or 0.5");
    }
    double v = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(v)) {
      throw InputError(where, "the number " +
                                  (digits.size() > 24 ? digits.substr(0, 24) + "..." : digits) +
                                  " is too large");
    }
    return v;
  }
  double parenthesized() {
    expect('(', "'('");
    const double v = number();
    expect(')', "')'");
    return v;
  }

  void directive(generator::LSystem& sys, const std::string& name, const SourceLocation& where) {
    expect('=', "'=' after '" + name + "'");
    const SourceLocation value_at = (skip_space(), here());
    const double v = number();
    expect(';', "';' after the value of '" + name + "'");
    auto range = [&](double lo, double hi) {
      if (v < lo || v > hi) {
        char buf[128];
        std::snprintf(buf, sizeof buf, "%s = %g is out of range [%g, %g]", name.c_str(), v, lo, hi);
        throw InputError(value_at, buf);
      }
    };
    auto whole = [&]() {
      if (v != std::floor(v)) throw InputError(value_at, name + " must be a whole number");
    };
    if (name == "iterations") {
      range(0, 64);
      whole();
      sys.iterations = static_cast<int>(v);
    } else if (name == "step") {
      range(1e-4, 1000);
      sys.step = v;
    } else if (name == "angle") {
      range(0, 360);
      sys.angle = v;
    } else if (name == "radius") {
      range(1e-5, 100);
      sys.radius = v;
    } else if (name == "randomness") {
      range(0, 0.99);
      sys.randomness = v;
    } else if (name == "leaves") {
      range(0, 1000);
      whole();
      sys.leaves = static_cast<int>(v);
    } else if (name == "leaf_length") {
      range(1e-4, 10);
      sys.leaf_length = v;
    } else if (name == "leaf_width") {
      range(1e-4, 10);
      sys.leaf_width = v;
    } else if (name == "leaf_shape") {
      range(0, 5);
      whole();
      sys.leaf_shape = static_cast<int>(v);
    } else
      throw InputError(where, "unknown setting '" + name +
                                  "' (known: iterations, step, angle, radius, randomness, leaves, "
                                  "leaf_length, leaf_width, leaf_shape)");
  }

  generator::LRule rule() {
    generator::LRule r;
    r.where = here();
    r.name = peek();
    advance();
    skip_space();
    if (!at_end() && peek() == '(') {
      const SourceLocation at = here();
      r.weight = parenthesized();
      if (r.weight <= 0.0) throw InputError(at, "a rule's weight must be above 0");
    }
    expect(':', "':' after the rule name");
    r.body = actions(false);
    expect(';', std::string("';' to end rule ") + r.name);
    if (r.body.empty()) throw InputError(r.where, std::string("rule ") + r.name + " is empty");
    return r;
  }

  std::vector<generator::LAction> actions(bool in_branch) {
    std::vector<generator::LAction> out;
    for (;;) {
      skip_space();
      if (at_end()) {
        if (in_branch) throw InputError(here(), "the file ends inside a branch: a ']' is missing");
        return out;
      }
      const char c = peek();
      if (c == ';') {
        if (in_branch) throw InputError(here(), "';' inside a branch: a ']' is missing");
        return out;
      }
      if (c == ']') {
        if (!in_branch) throw InputError(here(), "']' without a matching '['");
        return out;
      }
      generator::LAction a;
      a.where = here();
      advance();
      switch (c) {
        case 'f':
        case '+':
        case '-':
        case '<':
        case '>':
        case 'v':
        case '^':
          a.kind = static_cast<generator::LAction::Kind>(c);
          skip_space();
          if (!at_end() && peek() == '(') {
            a.has_number = true;
            a.number = parenthesized();
          }
          break;
        case 's':
        case 'h':
        case 'u':
        case 'l':
        case 'r':
          a.kind = static_cast<generator::LAction::Kind>(c);
          a.has_number = true;
          a.number = parenthesized();
          if (c == 'r' && (a.number <= 0.0 || a.number > 1.0)) {
            throw InputError(a.where,
                             "r(n) needs 0 < n ≤ 1: limbs do not thicken toward their tips");
          }
          if (c == 's' && a.number <= 0.0) throw InputError(a.where, "s(n) needs n > 0");
          break;
        case '[':
          // Parsing, interpreting and estimating recurse per bracket: a bound on the nesting
          // keeps the stack bounded (64 iterations of rules nested this deep still fit).
          if (++branch_depth_ > kMaxBranchDepth) {
            throw InputError(a.where, "branches are nested more than " +
                                          std::to_string(kMaxBranchDepth) + " deep in one rule");
          }
          a.kind = generator::LAction::Branch;
          a.branch = actions(true);
          expect(']', "']'");
          --branch_depth_;
          break;
        default:
          if (c >= 'A' && c <= 'Z') {
            a.kind = generator::LAction::Rule;
            a.rule = c;
          } else {
            throw InputError(a.where, std::string("unknown action '") + c + "'");
          }
      }
      out.push_back(std::move(a));
    }
  }

  void check_references(const std::vector<generator::LAction>& body,
                        const std::map<char, bool>& defined) {
    for (const generator::LAction& a : body) {
      if (a.kind == generator::LAction::Rule && !defined.count(a.rule)) {
        throw InputError(a.where, std::string("rule ") + a.rule + " is used but never defined");
      }
      if (a.kind == generator::LAction::Branch) check_references(a.branch, defined);
    }
  }

  static constexpr int kMaxBranchDepth = 100;
  TextCursor cursor_;
  std::string path_;
  int branch_depth_ = 0;
};

}  // namespace

generator::LSystem parse_lsystem(const std::string& text, const std::string& path) {
  return Parser(text, path).parse();
}

}  // namespace arbor::formats
