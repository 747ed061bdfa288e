#pragma once
// Outputs appear complete or not at all: write to a temporary sibling, then rename.
#include <functional>
#include <string>

namespace omnicam {

// Calls write(tmpPath), then renames tmpPath to path. The temporary keeps the final extension
// so that format-by-extension writers (OpenImageIO) pick the right format. On any exception the
// temporary is removed and the exception propagates.
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write);
void writeTextAtomically(const std::string& path, const std::string& text);

}  // namespace omnicam
