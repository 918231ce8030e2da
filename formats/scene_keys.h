// Internal to formats/: the scene file's keys, each stated once — its name, where its value goes,
// its range and unit, its one-line meaning and the models it belongs to — in one table per
// scene table (scene_keys.cpp, scene_keys_trees.cpp). The reader reads by these tables, the
// fingerprint prints by them and docs/scene-format.md is generated from them
// (scene_key_reference, scene_desc.h).
//
// A new key is one line in its table (and its field in scene_desc.h); a key whose value is not a
// plain field (a choice, a sub-table, a value with a position kept for later) names its reader.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include <toml++/toml.h>

#include "common/range.h"
#include "spec/scene_desc.h"
#include "formats/toml_reader.h"

namespace arbor::formats {

// TomlReader's checked values, and the files the keys name: resolved against the scene's folder
// and listed, for load_scene's checks of each input where it is named.
class SceneKeyReader : public TomlReader {
 public:
  explicit SceneKeyReader(const std::string& path);

  std::string file(const toml::node& n, const std::string& name) const;
  const std::vector<spec::FileRef>& files() const { return files_; }

 private:
  std::string folder_;
  mutable std::vector<spec::FileRef> files_;
};

// A choice key's names (a type's name table, e.g. kSkyModelNames).
struct Choices {
  const char* const* names = nullptr;
  std::size_t count = 0;
};
template <std::size_t N>
Choices choices_of(const std::array<const char*, N>& names) {
  return {names.data(), N};
}

// What a key holds, as the reference names it.
enum class KeyKind { Flag, Whole, Number, Triple, Area, Text, File, Choice, Table, List };

// One value being read: the node, its full name ("sky.turbidity", "tree.leaf.veins"), its key's
// range and choices, and its checked forms.
struct KeyValue {
  const SceneKeyReader& reader;
  const toml::node& node;
  std::string name;
  Range range;
  Choices choices;

  SourceLocation where() const { return reader.at(node.source()); }
  double number() const { return reader.number(node, name, range); }
  std::int64_t whole() const {
    // 2⁶³ and above stand for "any": the largest whole number TOML holds.
    const std::int64_t hi = range.hi >= 0x1p63 ? INT64_MAX : static_cast<std::int64_t>(range.hi);
    return reader.integer(node, name, static_cast<std::int64_t>(range.lo), hi);
  }
  spec::Vec3d triple() const { return reader.triple(node, name, range); }
  std::array<double, 4> area() const { return reader.area(node, name); }
  bool flag() const { return reader.boolean(node, name); }
  std::string text() const { return reader.text(node, name); }
  std::string file() const { return reader.file(node, name); }
  std::size_t choice() const {
    return reader.choice_index(node, name, choices.names, choices.count);
  }
  const toml::table& table() const { return reader.table(node, name); }
};

template <class D>
using KeyField =
    std::variant<std::monostate, bool D::*, int D::*, std::uint64_t D::*, double D::*,
                 std::optional<double> D::*, spec::Vec3d D::*, std::optional<spec::Vec3d> D::*,
                 std::array<double, 4> D::*, std::string D::*>;

template <class D>
struct Key {
  std::string_view name;
  std::string_view meaning;  // one line, for the reference
  KeyKind kind = KeyKind::Number;
  KeyField<D> field;         // where a plain value goes; std::monostate: `read` stores it
  Range range{};             // numbers (each of a triple's): the allowed values and their unit
  std::string_view belongs;  // the models it belongs to, by name ("preetham atmosphere"); "": all
  Choices choices{};
  void (*read)(const KeyValue&, D&) = nullptr;
  std::string (*show)(const D&) = nullptr;  // a `read` key's value, for the fingerprint
  std::string_view shown;  // the default as the reference shows it, where the value cannot say

  Key& only_for(std::string_view models) {
    belongs = models;
    return *this;
  }
  Key& shows(std::string_view text) {
    shown = text;
    return *this;
  }
  Key& within(Range r) {
    range = r;
    return *this;
  }
  Key& of(Choices names) {
    choices = names;
    return *this;
  }
};

namespace keys {

template <class T>
constexpr KeyKind kind_of() {
  if constexpr (std::is_same_v<T, bool>) return KeyKind::Flag;
  if constexpr (std::is_same_v<T, int> || std::is_same_v<T, std::uint64_t>) return KeyKind::Whole;
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, std::optional<double>>)
    return KeyKind::Number;
  if constexpr (std::is_same_v<T, spec::Vec3d> || std::is_same_v<T, std::optional<spec::Vec3d>>)
    return KeyKind::Triple;
  if constexpr (std::is_same_v<T, std::array<double, 4>>) return KeyKind::Area;
  return KeyKind::Text;
}

// A plain value: a number, whole number, triple or area in `range`, or a flag.
template <class D, class T>
Key<D> value(std::string_view name, T D::*field, Range range, std::string_view meaning) {
  Key<D> k;
  k.name = name;
  k.meaning = meaning;
  k.kind = kind_of<T>();
  k.field = field;
  k.range = range;
  return k;
}
template <class D>
Key<D> flag(std::string_view name, bool D::*field, std::string_view meaning) {
  return value(name, field, Range{}, meaning);
}
// A file's path, resolved against the scene's folder and checked by load_scene.
template <class D>
Key<D> file(std::string_view name, std::string D::*field, std::string_view meaning) {
  Key<D> k = value(name, field, Range{}, meaning);
  k.kind = KeyKind::File;
  return k;
}
// A key with its own reader (and `show`, for a value the fingerprint holds): a choice, a
// sub-table, a value whose position is kept.
template <class D>
Key<D> custom(std::string_view name, KeyKind kind, std::string_view meaning,
              void (*read)(const KeyValue&, D&), std::string (*show)(const D&) = nullptr) {
  Key<D> k;
  k.name = name;
  k.meaning = meaning;
  k.kind = kind;
  k.read = read;
  k.show = show;
  return k;
}

template <class>
struct member;
template <class D, class T>
struct member<T D::*> {
  using type = T;
};

}  // namespace keys

// The model in use where keys belong to some models only: its key and its name
// ({"sky.model", "constant"}).
struct ModelInUse {
  std::string_view key, name;
};

// Whether `name` is one of the space-separated `models`.
bool belongs_to(std::string_view models, std::string_view name);

// Reads table `t` into `d` by `keys`: each key's full name is `prefix` "." key; a key not in
// `keys` is an error at it ("unknown key 'zoom' in [camera]", `shown_as` = "[camera]"; at the top
// level, `shown_as` = "": "unknown table or key 'lights'"), and so is
// a key that belongs to other models than `model`'s.
template <class D>
void read_keys(const SceneKeyReader& r, const toml::table& t, std::string_view prefix,
               std::string_view shown_as, const std::vector<Key<D>>& table, D& d,
               const ModelInUse* model = nullptr) {
  for (auto&& [name, node] : t) {
    const Key<D>* key = nullptr;
    for (const Key<D>& k : table) {
      if (k.name == name.str()) key = &k;
    }
    if (!key) {
      const std::string k(name.str());
      throw InputError(r.at(name.source()),
                       shown_as.empty() ? "unknown table or key '" + k + "'"
                                        : "unknown key '" + k + "' in " + std::string(shown_as));
    }
    const std::string full = prefix.empty() ? std::string(name.str())
                                            : std::string(prefix) + "." + std::string(name.str());
    if (model && !key->belongs.empty() && !belongs_to(key->belongs, model->name)) {
      std::string owners;
      std::string_view rest = key->belongs;
      while (!rest.empty()) {
        const std::size_t space = rest.find(' ');
        const std::string_view m = rest.substr(0, space);
        owners += std::string(owners.empty() ? "" : " or ") + "\"" + std::string(m) + "\"";
        rest = space == std::string_view::npos ? std::string_view() : rest.substr(space + 1);
      }
      r.fail(node, full + " belongs to " + std::string(model->key) + " = " + owners + ", not \"" +
                       std::string(model->name) + "\"");
    }
    const KeyValue v{r, node, full, key->range, key->choices};
    if (key->read) {
      key->read(v, d);
      continue;
    }
    std::visit(
        [&](auto field) {
          using F = decltype(field);
          if constexpr (!std::is_same_v<F, std::monostate>) {
            using T = typename keys::member<F>::type;
            if constexpr (std::is_same_v<T, bool>)
              d.*field = v.flag();
            else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, std::uint64_t>)
              d.*field = static_cast<T>(v.whole());
            else if constexpr (std::is_same_v<T, double> ||
                               std::is_same_v<T, std::optional<double>>)
              d.*field = v.number();
            else if constexpr (std::is_same_v<T, spec::Vec3d> ||
                               std::is_same_v<T, std::optional<spec::Vec3d>>)
              d.*field = v.triple();
            else if constexpr (std::is_same_v<T, std::array<double, 4>>)
              d.*field = v.area();
            else
              d.*field = key->kind == KeyKind::File ? v.file() : v.text();
          }
        },
        key->field);
  }
}

// A number exactly, as short as it reads back the same ("0.53", "1e-06"): std::to_chars.
std::string exact_number(double v);
std::string exact_triple(const spec::Vec3d& v);

// A key's value in `d` at full precision, as the fingerprint and the reference show it
// ("[0.16, 0.14, 0.1]", "true", "none", "unset"): the field's, or its `show`'s.
template <class D>
std::string value_text(const Key<D>& key, const D& d) {
  if (key.show) return key.show(d);
  return std::visit(
      [&](auto field) -> std::string {
        using F = decltype(field);
        if constexpr (std::is_same_v<F, std::monostate>) {
          return "";
        } else {
          using T = typename keys::member<F>::type;
          const T& v = d.*field;
          if constexpr (std::is_same_v<T, bool>) {
            return v ? "true" : "false";
          } else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, std::uint64_t>) {
            return std::to_string(v);
          } else if constexpr (std::is_same_v<T, double>) {
            return exact_number(v);
          } else if constexpr (std::is_same_v<T, std::optional<double>>) {
            return v ? exact_number(*v) : "unset";
          } else if constexpr (std::is_same_v<T, spec::Vec3d>) {
            return exact_triple(v);
          } else if constexpr (std::is_same_v<T, std::optional<spec::Vec3d>>) {
            return v ? exact_triple(*v) : "unset";
          } else if constexpr (std::is_same_v<T, std::array<double, 4>>) {
            return "[[" + exact_number(v[0]) + ", " + exact_number(v[1]) + "], [" +
                   exact_number(v[2]) + ", " + exact_number(v[3]) + "]]";
          } else {
            return v.empty() ? "none" : "\"" + v + "\"";
          }
        }
      },
      key.field);
}

// Every key of `table` with a value, "name value" items joined by "; " (the fingerprint's form).
template <class D>
std::string values_text(const std::vector<Key<D>>& table, const D& d) {
  std::string text;
  for (const Key<D>& k : table) {
    const std::string v = value_text(k, d);
    if (!v.empty()) text += (text.empty() ? "" : "; ") + std::string(k.name) + " " + v;
  }
  return text;
}

// One key as the reference lists it.
struct KeyDoc {
  std::string name, kind, range, default_value, meaning, belongs;
};
template <class D>
std::vector<KeyDoc> key_docs(const std::vector<Key<D>>& table, const D& defaults = D{}) {
  static constexpr const char* kKinds[] = {"boolean", "integer", "number", "[x, y, z]", "area",
                                           "string",  "file",    "string", "table",     "list"};
  std::vector<KeyDoc> docs;
  for (const Key<D>& k : table) {
    KeyDoc doc{std::string(k.name),
               kKinds[static_cast<int>(k.kind)],
               "",
               k.shown.empty() ? value_text(k, defaults) : std::string(k.shown),
               std::string(k.meaning),
               std::string(k.belongs)};
    if (k.kind == KeyKind::Whole || k.kind == KeyKind::Number || k.kind == KeyKind::Triple) {
      doc.range = k.range.hi >= 0x1p63 ? "≥ " + short_number(k.range.lo) : k.range.text();
    }
    for (std::size_t i = 0; i < k.choices.count; ++i)
      doc.range += std::string(i ? ", " : "") + "\"" + k.choices.names[i] + "\"";
    docs.push_back(doc);
  }
  return docs;
}

// The tables (scene_keys.cpp, scene_keys_trees.cpp).
const std::vector<Key<spec::SceneDesc>>& scene_keys();  // the top level: the tables
const std::vector<Key<spec::RenderSettings>>& render_keys();
const std::vector<Key<spec::CameraDesc>>& camera_keys();
const std::vector<Key<spec::SunDesc>>& sun_keys();
const std::vector<Key<spec::SkyDesc>>& sky_keys();
const std::vector<Key<spec::GroundDesc>>& ground_keys();
const std::vector<Key<spec::TerrainDesc>>& terrain_keys();  // scene_keys_land.cpp
const std::vector<Key<spec::MeadowDesc>>& meadow_keys();
const std::vector<Key<spec::OutputDesc>>& output_keys();
const std::vector<Key<spec::AnimationDesc>>& animation_keys();
const std::vector<Key<spec::TreeDesc>>& tree_keys();
const std::vector<Key<spec::ForestDesc>>& forest_keys();
const std::vector<Key<spec::RocksDesc>>& rocks_keys();                     // scene_keys_land.cpp
const std::vector<Key<spec::CommunityDesc>>& community_keys();             // scene_keys_land.cpp
const std::vector<Key<spec::CommunitySpecies>>& community_species_keys();  // scene_keys_trees.cpp
const std::vector<Key<spec::MeshDesc>>& mesh_keys();
const std::vector<Key<spec::MeshMaterialDesc>>& mesh_material_keys();
const std::vector<Key<spec::BarkOverride>>& bark_keys();
const std::vector<Key<spec::LeafOverride>>& leaf_keys();
const std::vector<Key<spec::TreemakerOverride>>& treemaker_keys();

}  // namespace arbor::formats
