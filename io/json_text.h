#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

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

}  // namespace omnicam
