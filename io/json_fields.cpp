#include "json_fields.h"

#include <cmath>

#include "closest_name.h"
#include "errors.h"
#include "number_format.h"
#include "input_limits.h"

namespace omnicam {

using nlohmann::json;

std::string jsonTypeName(const json& v) { return v.type_name(); }

std::string jsonValueText(const json& v) { return v.is_number() ? v.dump() : jsonTypeName(v); }

JsonFields::JsonFields(const json& object, std::string file, std::string where)
    : object_(object), file_(std::move(file)), where_(std::move(where)) {
  if (!object_.is_object())
    throw InputError(fieldLocation(file_, where_.empty() ? "(root)" : where_) + ": must be an object (got " +
                     jsonTypeName(object_) + ")");
}

std::string jsonShapeText(const json& v) { return v.is_array() ? "an array of " + std::to_string(v.size()) : jsonValueText(v); }

std::string fieldLocation(const std::string& file, const std::string& path) {
  if (path.empty()) return showPath(file);
  return file.empty() ? path : showPath(file) + ": " + path;
}

std::string keySegment(const std::string& key) {
  static constexpr const char* kPlain = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.[]";
  const bool plain = !key.empty() && key.size() <= kEchoedTextChars && key.find_first_not_of(kPlain) == std::string::npos;
  return plain ? key : quote(key);
}

std::string JsonFields::path(const std::string& key) const {
  return where_.empty() ? keySegment(key) : where_ + "." + keySegment(key);
}

void JsonFields::fail(const std::string& key, const std::string& what) const {
  throw InputError(fieldLocation(file_, path(key)) + ": " + what);
}

bool JsonFields::has(const std::string& key) const {
  asked_.insert(key);
  return object_.contains(key);
}

std::vector<std::string> JsonFields::namesAskedFor() const {
  std::vector<std::string> names(read_.begin(), read_.end());
  for (const std::string& name : asked_)
    if (!read_.count(name)) names.push_back(name);
  return names;
}

void JsonFields::refuseTypos() const {
  const std::vector<std::string> names = namesAskedFor();
  for (auto it = object_.begin(); it != object_.end(); ++it)
    if (it.key() != "comment" && !read_.count(it.key()) && !asked_.count(it.key()) && closestName(it.key(), names))
      fail(it.key(), "unknown field" + didYouMean(it.key(), names));
}

const json* JsonFields::find(const std::string& key) {
  read_.insert(key);
  asked_.insert(key);
  auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

const json& JsonFields::required(const std::string& key) {
  const json* v = find(key);
  if (!v) {
    // A field not read yet that is a typo of this one ("line_time" for "line_time_us") is most
    // likely the mistake; it may also be a field read later (fx before a missing fy), so it is
    // named as a question, not refused as unknown.
    // A sibling of the same length one letter apart (fx and fy, edge_u and edge_v, x_axis and
    // y_axis) is a field of its own, not asked about; two letters swapped ("materail") is a typo.
    const auto sibling = [&](const std::string& other) {
      if (other.size() != key.size()) return false;
      size_t differing = 0;
      for (size_t k = 0; k < key.size(); ++k) differing += other[k] != key[k];
      return differing == 1;
    };
    for (auto it = object_.begin(); it != object_.end(); ++it)
      if (it.key() != "comment" && !read_.count(it.key()) && !sibling(it.key()) && closestName(it.key(), {key}))
        fail(key, "missing required field (the object has " + keySegment(it.key()) + ": a typo of " + keySegment(key) + "?)");
    fail(key, "missing required field");
  }
  return *v;
}

const json& JsonFields::raw(const std::string& key) { return required(key); }

double JsonFields::number(const std::string& key) {
  const json& v = required(key);
  if (!v.is_number()) fail(key, "must be a number (got " + jsonTypeName(v) + ")");
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(key, "must be finite");
  return d;
}

double JsonFields::number(const std::string& key, double fallback) {
  return has(key) ? number(key) : (read_.insert(key), fallback);
}

double JsonFields::number(const std::string& key, const Range& r) {
  const double d = number(key);
  if (!((r.openLow ? d > r.lo : d >= r.lo) && d <= r.hi))
    fail(key, "must be in " + std::string(r.openLow ? "(" : "[") + shortNumber(r.lo) + ", " + shortNumber(r.hi) + "]" +
                  (r.unit.empty() ? "" : " " + r.unit) + " (got " + roundTrip(d) + ")");
  return d;
}

double JsonFields::number(const std::string& key, double fallback, const Range& range) {
  return has(key) ? number(key, range) : (read_.insert(key), fallback);
}

double JsonFields::positive(const std::string& key) {
  const double d = number(key);
  if (!(d > 0.0)) fail(key, "must be > 0 (got " + roundTrip(d) + ")");
  return d;
}

double JsonFields::positive(const std::string& key, double fallback) {
  return has(key) ? positive(key) : (read_.insert(key), fallback);
}

double JsonFields::nonNegative(const std::string& key, double fallback) {
  const double d = number(key, fallback);
  if (d < 0.0) fail(key, "must be >= 0 (got " + roundTrip(d) + ")");
  return d;
}

int64_t JsonFields::integer(const std::string& key, int64_t minimum, int64_t maximum) {
  return integer(key, minimum, maximum, "in [" + std::to_string(minimum) + ", " + std::to_string(maximum) + "]");
}

int64_t JsonFields::integer(const std::string& key, int64_t minimum, int64_t maximum, const std::string& rule) {
  const json& v = required(key);
  // A whole number out of range is out of range, whether written 1e19 or as digits beyond 64 bits
  // (which the JSON reader holds as a double); a whole double in range (4.0) is no integer.
  const bool wholeOutOfRange = v.is_number_float() && std::isfinite(v.get<double>()) && v.get<double>() == std::floor(v.get<double>()) &&
                               !(v.get<double>() >= static_cast<double>(minimum) && v.get<double>() <= static_cast<double>(maximum));
  if (wholeOutOfRange) fail(key, "must be " + rule + " (got " + jsonValueText(v) + ")");
  if (!v.is_number_integer()) fail(key, "must be an integer (got " + jsonValueText(v) + ")");
  const auto i = integerInRange(v, minimum, maximum);
  if (!i) fail(key, "must be " + rule + " (got " + v.dump() + ")");
  return *i;
}

int JsonFields::integer(const std::string& key, int fallback, int minimum, int maximum) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  return static_cast<int>(integer(key, int64_t{minimum}, int64_t{maximum}));
}

std::optional<int64_t> integerInRange(const json& value, int64_t minimum, int64_t maximum) {
  // Non-negative integers parse as unsigned, negative ones as signed: compare each as it is.
  if (value.is_number_unsigned()) {
    const uint64_t u = value.get<uint64_t>();
    if (maximum < 0 || u > static_cast<uint64_t>(maximum) || static_cast<int64_t>(u) < minimum) return std::nullopt;
    return static_cast<int64_t>(u);
  }
  if (!value.is_number_integer()) return std::nullopt;
  const int64_t i = value.get<int64_t>();
  if (i < minimum || i > maximum) return std::nullopt;
  return i;
}

bool JsonFields::boolean(const std::string& key, bool fallback) {
  const json* v = find(key);
  if (!v) return fallback;
  if (!v->is_boolean()) fail(key, "must be true or false (got " + jsonTypeName(*v) + ")");
  return v->get<bool>();
}

std::string JsonFields::string(const std::string& key) {
  const json& v = required(key);
  if (!v.is_string()) fail(key, "must be a string (got " + jsonTypeName(v) + ")");
  return v.get<std::string>();
}

std::string JsonFields::string(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : (read_.insert(key), fallback);
}

Vec3 jsonVec3(const json& v, const std::string& file, const std::string& path) {
  if (!v.is_array() || v.size() != 3)
    throw InputError(fieldLocation(file, path) + ": must be an array of 3 numbers (got " + jsonShapeText(v) + ")");
  Vec3 out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      throw InputError(fieldLocation(file, path + "[" + std::to_string(i) + "]") + ": must be a finite number");
    out[i] = v[i].get<double>();
    if (std::abs(out[i]) > limits::kMaxWorldCoordinate)
      throw InputError(fieldLocation(file, path + "[" + std::to_string(i) + "]") + ": must be within ±" +
                       shortNumber(limits::kMaxWorldCoordinate) + " (got " + roundTrip(out[i]) + ")");
  }
  return out;
}

std::vector<double> JsonFields::numbers(const std::string& key, const std::vector<double>& fallback,
                                       const Range& range) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  const json& v = required(key);
  if (!v.is_array() || v.size() != fallback.size())
    fail(key, "must be an array of " + std::to_string(fallback.size()) + " numbers (got " + jsonShapeText(v) + ")");
  std::vector<double> out;
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string element = key + "[" + std::to_string(i) + "]";
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) fail(element, "must be a finite number");
    const double x = v[i].get<double>();
    if (!(range.openLow ? x > range.lo : x >= range.lo) || !(x <= range.hi))
      fail(element, std::string("must be in ") + (range.openLow ? "(" : "[") + shortNumber(range.lo) + ", " +
                        shortNumber(range.hi) + "]" + (range.unit.empty() ? "" : " " + range.unit) + " (got " +
                        roundTrip(x) + ")");
    out.push_back(x);
  }
  return out;
}

Vec3 JsonFields::vec3(const std::string& key) { return jsonVec3(required(key), file_, path(key)); }

Vec3 JsonFields::vec3(const std::string& key, const Vec3& fallback) {
  return has(key) ? vec3(key) : (read_.insert(key), fallback);
}

Vec3f JsonFields::colour(const std::string& key, const Vec3f& fallback, double max) {
  if (!has(key)) {
    read_.insert(key);
    return fallback;
  }
  const json& v = required(key);
  if (!v.is_number() && !(v.is_array() && v.size() == 3)) fail(key, "must be a number or an array of 3 numbers");
  // Read here, not by jsonVec3: a colour's range is `max` (emission up to 1e6), not a coordinate's.
  Vec3 c;
  for (int i = 0; i < 3; ++i) {
    const json& component = v.is_array() ? v[i] : v;
    if (!component.is_number() || !std::isfinite(component.get<double>()))
      fail(v.is_array() ? key + "[" + std::to_string(i) + "]" : key, "must be a finite number");
    c[i] = component.get<double>();
    if (!(c[i] >= 0.0 && c[i] <= max))
      fail(key, "components must be in [0, " + shortNumber(max) + "] (got " + roundTrip(c[i]) + ")");
  }
  return c.cast<float>();
}

JsonFields JsonFields::object(const std::string& key) { return JsonFields(required(key), file_, path(key)); }

std::optional<JsonFields> JsonFields::optionalObject(const std::string& key) {
  const json* v = find(key);
  if (!v) return std::nullopt;
  return JsonFields(*v, file_, path(key));
}

void JsonFields::finish() const {
  for (auto it = object_.begin(); it != object_.end(); ++it) {
    // "comment" annotates any object (JSON has no comments); it is documentation only.
    if (it.key() == "comment" || read_.count(it.key())) continue;
    throw InputError(fieldLocation(file_, path(it.key())) + ": unknown field" + didYouMean(it.key(), namesAskedFor()));
  }
}

}  // namespace omnicam
