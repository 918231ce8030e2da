// Importer of Arbaro parameter files (.xml): <arbaro><species name="…"><param name value/>…
// Per-level names carry the level digit 0–3 as a prefix ("1DownAngle"). Unknown names and bad
// values are errors with their line; Arbaro's own extensions are reported and ignored.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <string>

#include <pugixml.hpp>

#include "generator/species.h"
#include "formats/species_file.h"

namespace arbor::formats {

namespace {

// Parameters Arbaro added to the paper's set; arbor does not implement them.
bool is_arbaro_extension(std::string_view name) {
  static const char* const names[] = {"Species", "LeafStemLen", "LeafDistrib", "LeafQuality",
                                      "Smooth",  "Seed",        "RandomSeed"};
  for (const char* n : names) {
    if (name == n) return true;
  }
  return name.size() == 11 && name[0] >= '0' && name[0] <= '3' && name.substr(1) == "BranchDist";
}

class LineIndex {
 public:
  explicit LineIndex(std::string_view text) {
    starts_.push_back(0);
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '\n') starts_.push_back(i + 1);
    }
  }
  std::pair<int, int> position(std::ptrdiff_t offset) const {
    if (offset < 0) return {0, 0};
    const auto it = std::upper_bound(starts_.begin(), starts_.end(), static_cast<size_t>(offset));
    const size_t line = static_cast<size_t>(it - starts_.begin());
    return {static_cast<int>(line),
            static_cast<int>(static_cast<size_t>(offset) - starts_[line - 1] + 1)};
  }

 private:
  std::vector<size_t> starts_;
};

bool parse_number(std::string_view s, double& out) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

}  // namespace

generator::Species parse_arbaro_xml(std::string_view text, const std::string& path) {
  const LineIndex lines(text);
  auto where = [&](std::ptrdiff_t offset) {
    const auto [line, column] = lines.position(offset);
    return SourceLocation{path, line, column};
  };
  pugi::xml_document doc;
  // As a fragment, so that pugixml keeps text outside the root element (it drops it otherwise).
  const pugi::xml_parse_result parsed =
      doc.load_buffer(text.data(), text.size(), pugi::parse_default | pugi::parse_fragment);
  if (!parsed)
    throw InputError(where(parsed.offset), std::string("malformed XML: ") + parsed.description());

  // Text is not part of the format anywhere (pugixml keeps only text that is not white space):
  // text before or after the root, or between the elements, is refused where it starts.
  auto refuse_text = [&](const pugi::xml_node& parent, const char* where_text) {
    for (const pugi::xml_node& node : parent.children()) {
      if (node.type() == pugi::node_pcdata || node.type() == pugi::node_cdata) {
        // The node starts with the white space before the text: point at the text itself.
        auto at = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, node.offset_debug()));
        while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
        throw InputError(where(static_cast<std::ptrdiff_t>(at)),
                         std::string("unexpected text ") + where_text);
      }
    }
  };
  refuse_text(doc, "outside the <arbaro> element");
  int roots = 0;
  for (const pugi::xml_node& node : doc.children()) {
    if (node.type() == pugi::node_element && ++roots > 1) {
      throw InputError(where(node.offset_debug()), "a second root element <" +
                                                       std::string(node.name()) +
                                                       ">: the file holds one <arbaro> element");
    }
  }
  const pugi::xml_node root = doc.document_element();
  if (!root)
    throw InputError({path, 1, 1}, "no <arbaro> element: this is not an Arbaro parameter file");
  if (std::string_view(root.name()) != "arbaro") {
    throw InputError(where(root.offset_debug()),
                     "expected an <arbaro> root element, found <" + std::string(root.name()) + ">");
  }
  const pugi::xml_node species_node = root.child("species");
  if (!species_node) throw InputError(where(root.offset_debug()), "no <species> element");
  refuse_text(root, "in <arbaro>");
  refuse_text(species_node, "in <species>");

  generator::Species sp;
  sp.path = path;
  sp.name = species_node.attribute("name").as_string();
  std::map<std::string, SourceLocation> positions;
  for (const pugi::xml_node& node : species_node.children()) {
    if (node.type() != pugi::node_element) continue;
    const SourceLocation at = where(node.offset_debug());
    if (std::string_view(node.name()) != "param") {
      throw InputError(at, "unexpected element <" + std::string(node.name()) + "> in <species>");
    }
    const pugi::xml_attribute name_attr = node.attribute("name");
    const pugi::xml_attribute value_attr = node.attribute("value");
    if (!name_attr || !value_attr) throw InputError(at, "<param> needs 'name' and 'value'");
    const std::string name = name_attr.as_string();
    const std::string value = value_attr.as_string();

    if (is_arbaro_extension(name)) {
      sp.warnings.push_back(format_diagnostic(at, "warning",
                                              "Arbaro's parameter '" + name +
                                                  "' is not part of the paper's "
                                                  "model; ignored"));
      continue;
    }
    const generator::ParamInfo* info = nullptr;
    int level = -1;
    if (!name.empty() && name[0] >= '0' && name[0] <= '9') {
      level = name[0] - '0';
      info = generator::find_level_param(std::string_view(name).substr(1));
      if (info && level > 3) {
        throw InputError(at, "level " + std::to_string(level) + " in '" + name +
                                 "': levels are 0 to 3; deeper levels reuse level 3");
      }
      if (info && info->level0_only && level != 0) {
        throw InputError(at, "'" + name + "' exists only for the trunk (level 0)");
      }
      if (info && info->children_only && level == 0) {
        sp.warnings.push_back(format_diagnostic(
            at, "warning", "'" + name + "' has no meaning for the trunk; ignored"));
        continue;
      }
    } else {
      info = generator::find_tree_param(name);
    }
    if (!info) throw InputError(at, "unknown parameter '" + name + "'");

    double v = 0.0;
    if (!parse_number(value, v)) {
      throw InputError(at, "the value of '" + name + "' is not a number: '" + value + "'");
    }
    const std::string problem = generator::set_param(sp.weber_penn(), *info, std::max(level, 0), v);
    if (!problem.empty())
      throw InputError(at, (level >= 0 ? std::string(1, name[0]) : "") + problem);
    positions[name] = at;
  }
  generator::finish_species(sp, positions);
  return sp;
}

}  // namespace arbor::formats
