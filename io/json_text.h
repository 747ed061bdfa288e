#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "input_limits.h"

namespace omnicam {

// Every JSON input goes through these: linear time, no key twice in one object, nested at most
// `maxDepth` levels (objects and arrays), else InputError naming `path`.
// Reads a whole JSON file strictly: at most `maxBytes` (a regular file).
nlohmann::json readJsonFile(const std::string& path, int64_t maxBytes = limits::kMaxJsonFileBytes,
                            int maxDepth = limits::kMaxJsonDepth);
nlohmann::json parseJsonText(const std::string& text, const std::string& path, int maxDepth = limits::kMaxJsonDepth);
// The same checks without building the tree (for JSON another library parses: glTF).
void checkJsonText(const std::string& text, const std::string& path, int maxDepth = limits::kMaxJsonDepth);

// A nlohmann::json exception's message as users read it: without the library's own names
// ("[json.exception.parse_error.101] parse error at"), the token it stopped at quoted and escaped.
std::string jsonErrorText(std::string what);

// Where two JSON values differ, as paths to the differing members ("mirror.k", "offset_mm[1]";
// "" when the values themselves differ in kind or length), the first `limit` in member order.
std::vector<std::string> jsonDifferences(const nlohmann::json& a, const nlohmann::json& b, size_t limit = 4);
// The same as messages list them: the first `shown` paths, ", and more" after them; `whole` for
// values that differ as a whole ("the whole rig").
std::string jsonDifferenceList(const nlohmann::json& a, const nlohmann::json& b, const std::string& whole, size_t shown = 4);

}  // namespace omnicam
