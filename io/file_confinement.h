#pragma once
// Where the files a scene pulls in may come from: inside the scene's folder, symlinks resolved
// (docs/robustness.md). Used for textures, glTF files and the glTF's own buffers and images.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "input_limits.h"

namespace omnicam {

// `name` relative to `folder` (or absolute), resolved through every symlink. nullopt, with `why`
// set to one line, if it does not exist, is not a regular file, or — unless `allowOutside` —
// lies outside `folder` (itself resolved).
std::optional<std::filesystem::path> resolveConfined(const std::filesystem::path& folder, const std::string& name,
                                                     bool allowOutside, std::string& why);
// Every refusal of a file outside the scene's folder says these words. The library names no flag:
// each front (the CLI, Python) tells how it allows such files, through withOutsideFilesHint.
inline constexpr std::string_view kOutsideFolderWords = "resolves outside the scene's folder";
// `message`, and " (`howToAllow`)" when it refuses a file outside the scene's folder.
std::string withOutsideFilesHint(const std::string& message, std::string_view howToAllow);

// True if the resolved `path` lies inside the resolved `folder`.
bool isInsideFolder(const std::filesystem::path& folder, const std::filesystem::path& path);

// A whole file of at most `maxBytes` (checked before reading). nullopt with `why`.
std::optional<std::string> readWholeFile(const std::string& path, std::string& why,
                                         int64_t maxBytes = limits::kMaxInputFileBytes);

}  // namespace omnicam
