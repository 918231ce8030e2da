// TREE-MAKER template parser: sections of `name= value` pairs in braces, any spacing, ranges as
// `low to high`, vectors as `x,y,z`, branch triplets in parentheses (Figure 6).
#include "formats/treemaker_template.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>

#include "common/range.h"
#include "common/text_cursor.h"

namespace arbor::formats {

namespace {

struct Token {
  enum Kind { Word, Number, Symbol, End } kind = End;
  std::string text;
  double value = 0.0;
  SourceLocation where;
};

class Lexer {
 public:
  Lexer(const std::string& text, const std::string& path) : cursor_(text, path) {}

  Token next() {
    skip();
    Token t;
    t.where = cursor_.here();
    if (cursor_.at_end()) return t;
    const char c = cursor_.peek();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      t.kind = Token::Word;
      while (!cursor_.at_end() &&
             (std::isalnum(static_cast<unsigned char>(cursor_.peek())) || cursor_.peek() == '_')) {
        t.text += cursor_.peek();
        advance();
      }
      return t;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') {
      std::string s;
      while (!cursor_.at_end() &&
             (std::isdigit(static_cast<unsigned char>(cursor_.peek())) || cursor_.peek() == '.' ||
              ((cursor_.peek() == '-' || cursor_.peek() == '+') && s.empty()))) {
        s += cursor_.peek();
        advance();
      }
      const char* b = s.data() + (s[0] == '+' ? 1 : 0);
      const auto [end, ec] = std::from_chars(b, s.data() + s.size(), t.value);
      if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(t.value)) {
        throw InputError(t.where, "'" + s + "' is not a number");
      }
      t.kind = Token::Number;
      t.text = s;
      return t;
    }
    if (std::string("{}()=,:").find(c) != std::string::npos) {
      t.kind = Token::Symbol;
      t.text = std::string(1, c);
      advance();
      return t;
    }
    throw InputError(t.where, std::string("unexpected character '") + c + "'");
  }

 private:
  void advance() { cursor_.advance(); }
  void skip() {
    while (!cursor_.at_end()) {
      if (std::isspace(static_cast<unsigned char>(cursor_.peek())))
        advance();
      else if (cursor_.peek() == '#') {
        while (!cursor_.at_end() && cursor_.peek() != '\n') advance();
      } else
        break;
    }
  }
  TextCursor cursor_;
};

class Parser {
 public:
  Parser(const std::string& text, const std::string& path) : lex_(text, path), path_(path) {
    take();
  }

  generator::TreeMakerTemplate parse() {
    generator::TreeMakerTemplate t;
    t.path = path_;
    std::map<std::string, SourceLocation> once;
    while (tok_.kind != Token::End) {
      if (tok_.kind != Token::Word)
        fail("expected a section name (iterations, gravity, light, color, branch, particle, leaf)");
      const Token section = tok_;
      take();
      expect("{");
      const std::string& s = section.text;
      if (s == "iterations" || s == "gravity" || s == "light") {
        if (once.count(s)) throw InputError(section.where, "'" + s + "' is given twice");
        once[s] = section.where;
      }
      if (s == "iterations") {
        key("i");
        const double v = number();
        if (v != std::floor(v) || v < 1 || v > 1000)
          fail_at(last_, "iterations must be a whole number from 1 to 1000");
        t.iterations = static_cast<int>(v);
      } else if (s == "gravity") {
        key("g");
        t.gravity = number();
        if (std::fabs(t.gravity) > 100.0) fail_at(last_, "gravity must be within ±100");
      } else if (s == "light") {
        light(t.light);
      } else if (s == "color") {
        color(t);
      } else if (s == "branch") {
        if (!t.particles.empty())
          throw InputError(section.where,
                           "branching rules must come before the particles (Figure 6, note 4)");
        branch(t, section.where);
      } else if (s == "particle") {
        particle(t);
        t.particles.back().where = section.where;
      } else if (s == "leaf") {
        leaf(t, section.where);
      } else {
        throw InputError(section.where, "unknown section '" + s + "'");
      }
      expect("}");
    }
    check(t);
    return t;
  }

 private:
  void take() {
    last_ = tok_;
    tok_ = lex_.next();
  }
  [[noreturn]] void fail(const std::string& m) const { throw InputError(tok_.where, m); }
  [[noreturn]] void fail_at(const Token& t, const std::string& m) const {
    throw InputError(t.where, m);
  }
  bool is(const char* sym) const { return tok_.kind == Token::Symbol && tok_.text == sym; }
  void expect(const char* sym) {
    if (!is(sym))
      fail(std::string("expected '") + sym + "'" +
           (tok_.kind == Token::End ? " before the end of the file"
                                    : ", found '" + tok_.text + "'"));
    take();
  }
  // `name=`: the next key must be this one.
  void key(const char* name) {
    if (tok_.kind != Token::Word || tok_.text != name)
      fail(std::string("expected '") + name + "='");
    take();
    expect("=");
  }
  std::string word() {
    if (tok_.kind != Token::Word) fail("expected a name");
    const std::string w = tok_.text;
    take();
    return w;
  }
  double number() {
    if (tok_.kind != Token::Number)
      fail("expected a number" + (tok_.kind == Token::End
                                      ? std::string(" before the end of the file")
                                      : ", found '" + tok_.text + "'"));
    const double v = tok_.value;
    // Template numbers are centimetres, degrees, factors: past a million they only overflow.
    if (!(std::fabs(v) <= 1e6)) fail("the number " + tok_.text + " is out of range [-1e6, 1e6]");
    take();
    return v;
  }
  generator::TmRange range() {
    const Token first = tok_;
    generator::TmRange r;
    r.lo = r.hi = number();
    if (tok_.kind == Token::Word && tok_.text == "to") {
      take();
      r.hi = number();
    }
    if (r.lo > r.hi) fail_at(first, "a range's low end must not exceed its high end");
    return r;
  }
  glm::dvec3 vec3() {
    glm::dvec3 v;
    v.x = number();
    expect(",");
    v.y = number();
    expect(",");
    v.z = number();
    return v;
  }

  void light(generator::TmLight& l) {
    while (tok_.kind == Token::Word) {
      const Token k = tok_;
      take();
      expect("=");
      const double v = number();
      if (v < 0.0 || v > 10.0) fail_at(last_, "light weights must be in [0, 10]");
      if (k.text == "ambient")
        l.ambient = v;
      else if (k.text == "lambert")
        l.lambert = v;
      else if (k.text == "height")
        l.height = v;
      else if (k.text == "radius")
        l.radius = v;
      else if (k.text == "angle")
        l.angle = v;
      else
        fail_at(k,
                "unknown light weight '" + k.text + "' (ambient, lambert, height, radius, angle)");
    }
  }

  void color(generator::TreeMakerTemplate& t) {
    const Token name = tok_;
    generator::TmColor c;
    c.name = word();
    expect("=");
    c.rgb = vec3();
    if (c.rgb.x < 0 || c.rgb.y < 0 || c.rgb.z < 0 || std::max({c.rgb.x, c.rgb.y, c.rgb.z}) <= 0.0) {
      fail_at(name, "a colour needs non-negative weights, not all zero");
    }
    if (t.color(c.name)) fail_at(name, "colour '" + c.name + "' is defined twice");
    t.colors.push_back(c);
  }

  void branch(generator::TreeMakerTemplate& t, const SourceLocation& where) {
    generator::TmBranchRule r;
    r.where = where;
    key("level");
    const double level = number();
    if (level != std::floor(level) || level < 1 || level > 1000)
      fail_at(last_, "level must be a whole number ≥ 1");
    r.level = static_cast<int>(level);
    key("number");
    r.number = range();
    if (r.number.lo < 0.0 || r.number.hi > 100.0)
      fail_at(last_, "the number of branches must be in [0, 100]");
    while (is("(")) {
      take();
      generator::TmBranchChoice c;
      key("p");
      c.p = number();
      if (c.p < 0.0 || c.p > 1.0) fail_at(last_, "a probability must be in [0, 1]");
      key("angle");
      c.angle = range();
      key("dir");
      c.dir = range();
      key("factor");
      c.factor = range();
      if (c.factor.lo < 0.0) fail_at(last_, "a growth factor must not be negative");
      expect(")");
      r.choices.push_back(c);
    }
    if (r.choices.empty())
      throw InputError(where, "a branching rule needs at least one (p angle dir factor) triplet");
    double sum = 0.0;
    for (const generator::TmBranchChoice& c : r.choices) sum += c.p;
    if (std::fabs(sum - 1.0) > 1e-6)
      throw InputError(where, "the probabilities of this branching rule add up to " +
                                  short_number(sum) + ", not 1 (Figure 6, note 5)");
    for (const generator::TmBranchRule& other : t.branches) {
      if (other.level == r.level)
        throw InputError(where,
                         "level " + std::to_string(r.level) + " already has a branching rule");
    }
    t.branches.push_back(r);
    std::sort(t.branches.begin(), t.branches.end(),
              [](const generator::TmBranchRule& a, const generator::TmBranchRule& b) {
                return a.level < b.level;
              });
  }

  void particle(generator::TreeMakerTemplate& t) {
    generator::TmParticle p;
    while (tok_.kind == Token::Word) {
      const Token k = tok_;
      take();
      expect("=");
      if (k.text == "pos")
        p.pos = vec3();
      else if (k.text == "mag") {
        p.mag = range();
        if (p.mag.lo < 0.0) fail_at(k, "mag must not be negative");
      } else if (k.text == "dir") {
        p.dir = vec3();
        if (p.dir.x == 0.0 && p.dir.y == 0.0 && p.dir.z == 0.0)
          fail_at(k, "dir must not be the zero vector");
        expect(":");
        p.max_deviation = number();
        if (p.max_deviation < 0.0 || p.max_deviation > 180.0)
          fail_at(last_, "the deviation must be in [0, 180] degrees");
      } else if (k.text == "acc")
        p.acc = number();
      else if (k.text == "growth") {
        p.growth = number();
        if (p.growth < 0.0) fail_at(last_, "growth must not be negative");
      } else if (k.text == "age")
        p.age = number();
      else if (k.text == "color") {
        const Token c = tok_;
        p.color = word();
        if (!t.color(p.color))
          fail_at(c,
                  "colour '" + p.color + "' is not defined (define it in a color section before)");
      } else if (k.text == "brightness")
        p.brightness = brightness();
      else
        fail_at(k, "unknown particle key '" + k.text +
                       "' (pos, mag, dir, acc, growth, age, color, brightness)");
    }
    t.particles.push_back(p);
  }

  generator::TmRange brightness() {
    const Token at = tok_;
    const generator::TmRange b = range();
    if (b.lo < 0.0 || b.hi > 1.0) fail_at(at, "brightness must be in [0, 1]");
    return b;
  }

  void leaf(generator::TreeMakerTemplate& t, const SourceLocation& where) {
    generator::TmLeaf l;
    l.where = where;
    std::string color;
    generator::TmRange bright{1.0, 1.0};
    while (tok_.kind == Token::Word) {
      const Token k = tok_;
      take();
      expect("=");
      if (k.text == "p") {
        l.p = number();
        if (l.p < 0.0 || l.p > 1.0) fail_at(last_, "a probability must be in [0, 1]");
      } else if (k.text == "coord") {
        const Token c = tok_;
        const std::string w = word();
        if (w != "limb" && w != "leaf") fail_at(c, "coord must be 'limb' or 'leaf'");
        l.limb_coords = w == "limb";
      } else if (k.text == "out")
        l.out = number();
      else if (k.text == "up")
        l.up = number();
      else if (k.text == "color") {
        const Token c = tok_;
        color = word();
        if (!t.color(color)) fail_at(c, "colour '" + color + "' is not defined");
      } else if (k.text == "brightness")
        bright = brightness();
      else if (k.text == "tri" || k.text == "ln") {
        if (color.empty()) fail_at(k, "give the element's color= before its tri= or ln=");
        generator::TmElement e;
        e.line = k.text == "ln";
        e.color = color;
        e.brightness = bright;
        const int n = e.line ? 2 : 3;
        for (int i = 0; i < n; ++i) e.v[static_cast<size_t>(i)] = vec3();
        l.elements.push_back(e);
      } else
        fail_at(
            k, "unknown leaf key '" + k.text + "' (p, coord, out, up, color, brightness, tri, ln)");
    }
    if (l.elements.empty())
      throw InputError(where, "a leaf needs at least one tri= or ln= element");
    t.leaves.push_back(l);
  }

  void check(const generator::TreeMakerTemplate& t) const {
    const SourceLocation end{path_, 1, 1};
    if (t.branches.empty()) throw InputError(end, "a template needs at least one branching rule");
    if (t.particles.empty()) throw InputError(end, "a template needs at least one particle");
    if (t.leaves.empty()) throw InputError(end, "a template needs at least one leaf definition");
    double sum = 0.0;
    for (const generator::TmLeaf& l : t.leaves) sum += l.p;
    if (std::fabs(sum - 1.0) > 1e-6) {
      throw InputError(t.leaves.back().where, "the leaf probabilities add up to " +
                                                  short_number(sum) + ", not 1 (Figure 6, note 5)");
    }
  }

  Lexer lex_;
  std::string path_;
  Token tok_, last_;
};

}  // namespace

generator::TreeMakerTemplate parse_treemaker_template(const std::string& text,
                                                      const std::string& path) {
  return Parser(text, path).parse();
}

}  // namespace arbor::formats
