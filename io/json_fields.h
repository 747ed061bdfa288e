#pragma once
// Strict reading of one JSON object: every read names its field path for error messages, and
// finish() rejects fields nobody read (Mitsuba-style: unknown parameters are errors).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

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

  // A finite number in [lo, hi] ((lo, hi] when openLow); `unit` follows the range in messages.
  struct Range {
    Range(double low, double high, bool openBelow = false, std::string unitText = "")
        : lo(low), hi(high), openLow(openBelow), unit(std::move(unitText)) {}
    double lo, hi;
    bool openLow;
    std::string unit;
  };
  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  double number(const std::string& key, const Range& range);
  double number(const std::string& key, double fallback, const Range& range);
  double positive(const std::string& key);
  double positive(const std::string& key, double fallback);
  double nonNegative(const std::string& key, double fallback);
  // An integer (a JSON number without fraction or exponent) in [minimum, maximum]: required
  // (first), or `fallback` when absent. Out of range is an error, never wrapped.
  int64_t integer(const std::string& key, int64_t minimum, int64_t maximum);
  // The same, out of range told as `rule` says ("must be " + rule): for a field whose own rule is
  // narrower than the 64 bits read here and checked later (a request's, as the CLI's flag says it).
  int64_t integer(const std::string& key, int64_t minimum, int64_t maximum, const std::string& rule);
  int integer(const std::string& key, int fallback, int minimum, int maximum);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  Vec3 vec3(const std::string& key);
  // An optional array of exactly `count` numbers, each in `range`; `fallback` when absent.
  std::vector<double> numbers(const std::string& key, const std::vector<double>& fallback, const Range& range);
  Vec3 vec3(const std::string& key, const Vec3& fallback);
  // A colour: [r, g, b] in [0, max] or a single number for grey.
  Vec3f colour(const std::string& key, const Vec3f& fallback, double max);
  JsonFields object(const std::string& key);
  std::optional<JsonFields> optionalObject(const std::string& key);

  void finish() const;
  // InputError for a field not read that is a typo of one asked for ("between_pose" when
  // "between_poses" was looked for): for readers about to refuse a missing choice, so that the typo
  // is named rather than the choice.
  void refuseTypos() const;
  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }

 private:
  const nlohmann::json& required(const std::string& key);
  const nlohmann::json* find(const std::string& key);
  const nlohmann::json& object_;
  std::string file_, where_;
  std::set<std::string> read_;
  mutable std::set<std::string> asked_;  // read, or asked for with has(): the names a typo may mean
  std::vector<std::string> namesAskedFor() const;
};

// Where a message points: "file: field.path"; "field.path" alone for JSON that came from no file
// (a Python keyword's value, named by `path`); "file" alone for the file's whole content.
std::string fieldLocation(const std::string& file, const std::string& path);
// A JSON key as a segment of a field path in messages: as is when plain ("rim_elevation_deg", or
// an element such as "poses[3]" that callers pass), quoted otherwise (a material named "x\ny").
std::string keySegment(const std::string& key);
// Reads a JSON array of numbers of a fixed length; `path` (as path() gives it) is used for errors.
Vec3 jsonVec3(const nlohmann::json& value, const std::string& file, const std::string& path);
std::string jsonTypeName(const nlohmann::json& value);
// A value as messages echo it: a number as JSON writes it, anything else by its type.
std::string jsonValueText(const nlohmann::json& value);
// The same, but an array as its length ("an array of 3"): for "must be an array of N".
std::string jsonShapeText(const nlohmann::json& value);
// The value of an integer JSON number in [minimum, maximum]; nullopt for anything else (not a
// number, a fraction, out of range: 4294967346 is never 50, 2^64 - 1 never -1).
std::optional<int64_t> integerInRange(const nlohmann::json& value, int64_t minimum, int64_t maximum);

}  // namespace omnicam
