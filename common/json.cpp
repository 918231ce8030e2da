// JSON objects for the command line's --json output.
#include "common/json.h"

#include <cmath>
#include <cstdio>

namespace arbor {

std::string json_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out;
}

JsonObject& JsonObject::raw(const std::string& key, const std::string& value) {
  if (!body_.empty()) body_ += ", ";
  body_ += "\"" + json_escape(key) + "\": " + value;
  return *this;
}

namespace {
std::string number_text(double value, int digits) {
  if (!std::isfinite(value)) return "null";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}
}  // namespace

JsonObject& JsonObject::number(const std::string& key, double value, int digits) {
  return raw(key, number_text(value, digits));
}

JsonObject& JsonObject::numbers(const std::string& key, const std::vector<double>& values,
                                int digits) {
  std::string list = "[";
  for (std::size_t i = 0; i < values.size(); ++i)
    list += (i ? ", " : "") + number_text(values[i], digits);
  return raw(key, list + "]");
}

JsonObject& JsonObject::integer(const std::string& key, long long value) {
  return raw(key, std::to_string(value));
}

JsonObject& JsonObject::integer(const std::string& key, unsigned long long value) {
  return raw(key, std::to_string(value));
}

JsonObject& JsonObject::text(const std::string& key, const std::string& value) {
  return raw(key, "\"" + json_escape(value) + "\"");
}

JsonObject& JsonObject::boolean(const std::string& key, bool value) {
  return raw(key, value ? "true" : "false");
}

JsonObject& JsonObject::integers(const std::string& key, const std::vector<long long>& values) {
  std::string list = "[";
  for (std::size_t i = 0; i < values.size(); ++i)
    list += (i ? ", " : "") + std::to_string(values[i]);
  return raw(key, list + "]");
}

JsonObject& JsonObject::object(const std::string& key, const JsonObject& value) {
  return raw(key, value.str());
}

JsonObject& JsonObject::objects(const std::string& key, const std::vector<JsonObject>& values) {
  std::string list = "[";
  for (std::size_t i = 0; i < values.size(); ++i) list += (i ? ", " : "") + values[i].str();
  return raw(key, list + "]");
}

}  // namespace arbor
