// Reading back what the pbrt-v4 exporter writes, for its tests: the export itself, a tokenizer of
// pbrt's syntax (directives, typed parameters, lists) that fails the test on anything pbrt would
// refuse, and lookups in what it read.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "imaging/color.h"
#include "formats/scene_file.h"
#include "scene/scene.h"
#include "tracer/pbrt_scene.h"
#include "tracer/test_world.h"

namespace arbor::tracer::pbrt_reading {

// `arbor export`'s library part: the scene built, then written as pbrt-v4 sees it.
inline void export_scene(const std::string& scene_path, const std::string& out,
                         int sky_resolution) {
  const spec::SceneDesc desc = formats::load_scene(scene_path);
  write_pbrt_scene(*scene::build_scene(desc, kOcioConfig), scene::render_input(desc),
                   imaging::ColorPipeline(kOcioConfig), out, sky_resolution);
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A pbrt-v4 file as statements: a directive and its arguments (quoted strings, numbers, or
// bracketed lists); comments dropped. Fails the test on anything pbrt's tokenizer would refuse.
struct Statement {
  std::string directive;
  std::vector<std::string> args;  // strings without their quotes; a list as "[", items, "]"
};
inline std::vector<Statement> parse_pbrt(const std::string& text) {
  std::vector<std::string> tokens;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '#') {
      i = text.find('\n', i);
      if (i == std::string::npos) break;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '"') {
      const std::size_t end = text.find('"', i + 1);
      EXPECT_NE(end, std::string::npos) << "unterminated string at " << i;
      if (end == std::string::npos) break;
      tokens.push_back("\"" + text.substr(i + 1, end - i - 1));
      i = end + 1;
    } else if (c == '[' || c == ']') {
      tokens.emplace_back(1, c);
      ++i;
    } else {
      std::size_t end = i;
      while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])) &&
             text[end] != '[' && text[end] != ']' && text[end] != '"')
        ++end;
      tokens.push_back(text.substr(i, end - i));
      i = end;
    }
  }
  std::vector<Statement> out;
  int depth = 0;
  for (const std::string& t : tokens) {
    const bool word = std::isalpha(static_cast<unsigned char>(t[0])) && t != "true" && t != "false";
    if (word && depth == 0) {
      out.push_back({t, {}});
      continue;
    }
    EXPECT_FALSE(out.empty()) << "argument before any directive: " << t;
    if (out.empty()) continue;
    if (t == "[") ++depth;
    if (t == "]") --depth;
    EXPECT_GE(depth, 0);
    EXPECT_LE(depth, 1) << "nested list";
    if (t[0] != '"' && t != "[" && t != "]") {
      char* end = nullptr;
      std::strtod(t.c_str(), &end);
      EXPECT_EQ(*end, '\0') << "not a number: " << t << " in " << out.back().directive;
    }
    out.back().args.push_back(t[0] == '"' ? t.substr(1) : t);
  }
  EXPECT_EQ(depth, 0);
  const std::set<std::string> known = {"ColorSpace",
                                       "Scale",
                                       "LookAt",
                                       "Camera",
                                       "Film",
                                       "PixelFilter",
                                       "Sampler",
                                       "Integrator",
                                       "WorldBegin",
                                       "LightSource",
                                       "MakeNamedMaterial",
                                       "NamedMaterial",
                                       "Material",
                                       "ObjectBegin",
                                       "ObjectEnd",
                                       "ObjectInstance",
                                       "AttributeBegin",
                                       "AttributeEnd",
                                       "Shape",
                                       "Transform",
                                       "Texture"};
  const std::set<std::string> types = {"float", "integer", "point3", "point2", "normal",
                                       "rgb",   "string",  "bool",   "texture"};
  for (const Statement& s : out) {
    EXPECT_TRUE(known.count(s.directive)) << s.directive;
    // Parameter lists: "type name" then one value or a bracketed list.
    std::size_t i = 0;
    if (s.directive == "Camera" || s.directive == "Film" || s.directive == "PixelFilter" ||
        s.directive == "Sampler" || s.directive == "Integrator" || s.directive == "LightSource" ||
        s.directive == "Shape" || s.directive == "MakeNamedMaterial" || s.directive == "Material" ||
        s.directive == "Texture") {
      i = s.directive == "Texture" ? 3 : 1;  // Texture "name" "type" "class" params
      while (i < s.args.size()) {
        const std::string& decl = s.args[i];
        const std::size_t space = decl.find(' ');
        EXPECT_NE(space, std::string::npos)
            << s.directive << ": parameter without a type: " << decl;
        if (space == std::string::npos) break;
        EXPECT_TRUE(types.count(decl.substr(0, space))) << s.directive << ": type of " << decl;
        ++i;
        if (i < s.args.size() && s.args[i] == "[") {
          while (i < s.args.size() && s.args[i] != "]") ++i;
        }
        ++i;
      }
    }
  }
  return out;
}

inline std::vector<double> numbers(const Statement& s, const std::string& param) {
  std::vector<double> v;
  for (std::size_t i = 0; i < s.args.size(); ++i) {
    if (s.args[i] != param) continue;
    ++i;
    const bool list = s.args[i] == "[";
    for (i += list ? 1 : 0; i < s.args.size() && s.args[i] != "]"; ++i) {
      v.push_back(std::stod(s.args[i]));
      if (!list) break;
    }
    break;
  }
  return v;
}

inline const Statement* find(const std::vector<Statement>& all, const std::string& directive,
                             const std::string& first = "") {
  for (const Statement& s : all) {
    if (s.directive == directive && (first.empty() || (!s.args.empty() && s.args[0] == first)))
      return &s;
  }
  return nullptr;
}

inline std::size_t count(const std::vector<Statement>& all, const std::string& directive) {
  std::size_t n = 0;
  for (const Statement& s : all) n += s.directive == directive;
  return n;
}

}  // namespace arbor::tracer::pbrt_reading
