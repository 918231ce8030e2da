// Writing JSON: one object at a time, keys in the order they are added, `{"key": value, …}` on
// one line. Numbers are printed with a given number of significant digits; infinities and NaN,
// which JSON cannot spell, become null.
#pragma once

#include <string>
#include <vector>

namespace arbor {

// The body of a JSON string: quotes and backslashes escaped, control characters dropped.
std::string json_escape(const std::string& text);

class JsonObject {
 public:
  JsonObject& number(const std::string& key, double value, int digits = 9);
  JsonObject& integer(const std::string& key, long long value);
  JsonObject& integer(const std::string& key, unsigned long long value);
  JsonObject& text(const std::string& key, const std::string& value);
  JsonObject& boolean(const std::string& key, bool value);
  JsonObject& numbers(const std::string& key, const std::vector<double>& values, int digits = 9);
  JsonObject& integers(const std::string& key, const std::vector<long long>& values);
  JsonObject& object(const std::string& key, const JsonObject& value);
  JsonObject& objects(const std::string& key, const std::vector<JsonObject>& values);
  std::string str() const { return "{" + body_ + "}"; }

 private:
  JsonObject& raw(const std::string& key, const std::string& value);
  std::string body_;
};

}  // namespace arbor
