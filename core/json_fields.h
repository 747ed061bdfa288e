#pragma once
// Strict reading of one JSON object: every read names its field path for error messages, and
// finish() rejects fields nobody read (Mitsuba-style: unknown parameters are errors).
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "geometry.h"

namespace omnicam {

class JsonFields {
 public:
  // `where` is the field path of this object as messages show it ("" for the root; user keys
  // quoted, as path() does), `file` prefixes every error.
  JsonFields(const nlohmann::json& object, std::string file, std::string where);

  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  // The field path of `key` for messages: "objects[2].radius", materials."a b".color.
  std::string path(const std::string& key) const;
  bool has(const std::string& key) const;
  const nlohmann::json& raw(const std::string& key);  // required, any type

  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  // Checks a number against an open/closed range; `rule` is the text of the requirement.
  double positive(const std::string& key);
  double positive(const std::string& key, double fallback);
  double nonNegative(const std::string& key, double fallback);
  int integer(const std::string& key, int fallback, int minimum, int maximum);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  Vec3 vec3(const std::string& key);
  Vec3 vec3(const std::string& key, const Vec3& fallback);
  // A colour: [r, g, b] in [0, max] or a single number for grey.
  Vec3f colour(const std::string& key, const Vec3f& fallback, double max);
  JsonFields object(const std::string& key);
  std::optional<JsonFields> optionalObject(const std::string& key);

  void finish() const;
  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }

 private:
  const nlohmann::json& required(const std::string& key);
  const nlohmann::json* find(const std::string& key);
  const nlohmann::json& object_;
  std::string file_, where_;
  std::set<std::string> read_;
};

// A JSON key as a segment of a field path in messages: as is when plain ("rim_elevation_deg", or
// an element such as "poses[3]" that callers pass), quoted otherwise (a material named "x\ny").
std::string keySegment(const std::string& key);
// Reads a JSON array of numbers of a fixed length; `path` (as path() gives it) is used for errors.
Vec3 jsonVec3(const nlohmann::json& value, const std::string& file, const std::string& path);
std::string jsonTypeName(const nlohmann::json& value);

}  // namespace omnicam
