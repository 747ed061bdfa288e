#include "json_text.h"

#include "json_fields.h"

#include <algorithm>
#include <set>
#include <string_view>
#include <vector>

#include "errors.h"
#include "file_confinement.h"

namespace omnicam {

using nlohmann::json;

// nlohmann's messages quote the token they stopped at ("last read: 'tru'", "parsing '1e400'"),
// and a token can be a whole megabyte-long string: it is echoed like any user text.
std::string jsonErrorText(std::string what) {
  // nlohmann's own names ("[json.exception.parse_error.101] parse error at line 1, ...") say
  // nothing to a user: the place and the reason are what is kept.
  if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos) what.erase(0, what.find("] ") + 2);
  if (what.rfind("parse error at ", 0) == 0) what.erase(0, std::string_view("parse error at ").size());
  for (const std::string_view marker : {"; last read: '", "parsing '"}) {
    const size_t open = what.find(marker);
    if (open == std::string::npos) continue;
    const size_t begin = open + marker.size();
    size_t end = what.rfind("'; expected ");  // nlohmann may name what it expected after the token
    if (end == std::string::npos || end < begin) end = what.size() - 1;
    if (end < begin || what[end] != '\'') return what;
    return what.substr(0, begin - 1) + quote(what.substr(begin, end - begin)) + what.substr(end + 1);
  }
  return what;
}

namespace {

// The checking pass over a JSON text (SAX: no tree is built, no work per sibling): syntax, no
// key twice in one object, nesting at most `maxDepth`. nlohmann's own callback parser would do
// the key check too, but it rescans the parent at every object's end: quadratic in siblings.
// A key given twice is named with the place of its object (`cameras[1].rig: duplicate key "x"`).
class StrictJsonCheck : public json::json_sax_t {
 public:
  StrictJsonCheck(const std::string& file, int maxDepth) : file_(file), maxDepth_(maxDepth) {}
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    enter(false);
    return true;
  }
  bool key(string_t& key) override {
    if (!open_.back().keys.insert(key).second) {
      const std::string place = placeOfInnermost();
      throw InputError(showPath(file_) + ": " + (place.empty() ? "" : place + ": ") + "duplicate key " + quote(key));
    }
    open_.back().key = key;
    return true;
  }
  bool end_object() override {
    open_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override {
    enter(true);
    return true;
  }
  bool end_array() override {
    open_.pop_back();
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const json::exception& e) override {
    // Syntax errors, and numbers such as 1e400 that overflow.
    throw InputError(showPath(file_) + ": not valid JSON (" + jsonErrorText(e.what()) + ")");
  }

 private:
  // An object or array being read: an array counts its elements, an object holds its keys so far
  // and the last one (whose value is being read).
  struct Open {
    bool array = false;
    size_t elements = 0;
    std::set<std::string> keys;
    std::string key;
  };
  bool value() {
    if (!open_.empty() && open_.back().array) ++open_.back().elements;
    return true;
  }
  void enter(bool array) {
    value();
    if (static_cast<int>(open_.size()) + 1 > maxDepth_)
      throw InputError(showPath(file_) + ": JSON nested deeper than " + std::to_string(maxDepth_) +
                       " levels of objects and arrays");
    open_.push_back(Open{array, 0, {}, {}});
  }
  // Where the innermost open container sits: "cameras[1].rig" ("" at the top level). Keys that
  // are not plain names are quoted, as user text.
  std::string placeOfInnermost() const {
    std::string place;
    for (size_t i = 0; i + 1 < open_.size(); ++i) {
      if (open_[i].array) {
        place += "[" + std::to_string(open_[i].elements - 1) + "]";
        continue;
      }
      const std::string& key = open_[i].key;
      const bool plain = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
      });
      place += (place.empty() ? "" : ".") + (plain ? key : quote(key));
    }
    return place;
  }
  const std::string& file_;
  const int maxDepth_;
  std::vector<Open> open_;
};

}  // namespace

void checkJsonText(const std::string& text, const std::string& file, int maxDepth) {
  StrictJsonCheck check(file, maxDepth);
  json::sax_parse(text, &check);
}

nlohmann::json parseJsonText(const std::string& text, const std::string& file, int maxDepth) {
  checkJsonText(text, file, maxDepth);
  // Checked: the plain parser (no callback, linear time) builds the tree.
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(showPath(file) + ": not valid JSON (" + jsonErrorText(e.what()) + ")");
  }
}

nlohmann::json readJsonFile(const std::string& file, int64_t maxBytes, int maxDepth) {
  std::string why;
  const auto text = readWholeFile(file, why, maxBytes);
  if (!text) throw InputError(showPath(file) + ": " + why);
  return parseJsonText(*text, file, maxDepth);
}

namespace {

void collectDifferences(const json& a, const json& b, const std::string& at, size_t limit, std::vector<std::string>& out) {
  if (out.size() >= limit || a == b) return;
  if (a.is_object() && b.is_object()) {
    std::set<std::string> keys;
    for (const auto& [key, value] : a.items()) keys.insert(key);
    for (const auto& [key, value] : b.items()) keys.insert(key);
    for (const std::string& key : keys) {
      // A key is whatever a file holds (a forged one may clear a terminal): as messages show keys.
      const std::string member = at.empty() ? keySegment(key) : at + "." + keySegment(key);
      if (a.contains(key) != b.contains(key)) {
        if (out.size() < limit) out.push_back(member);  // one has it, the other not (a null included)
      } else {
        collectDifferences(a.at(key), b.at(key), member, limit, out);
      }
    }
  } else if (a.is_array() && b.is_array() && a.size() == b.size()) {
    for (size_t i = 0; i < a.size(); ++i) collectDifferences(a[i], b[i], at + "[" + std::to_string(i) + "]", limit, out);
  } else {
    out.push_back(at);
  }
}

}  // namespace

std::vector<std::string> jsonDifferences(const json& a, const json& b, size_t limit) {
  std::vector<std::string> out;
  collectDifferences(a, b, "", limit, out);
  return out;
}

std::string jsonDifferenceList(const json& a, const json& b, const std::string& whole, size_t shown) {
  const std::vector<std::string> paths = jsonDifferences(a, b, shown + 1);
  std::string list;
  for (size_t k = 0; k < std::min(paths.size(), shown); ++k) list += (list.empty() ? "" : ", ") + (paths[k].empty() ? whole : paths[k]);
  if (paths.size() > shown) list += ", and more";
  return list.empty() ? whole : list;
}

}  // namespace omnicam
