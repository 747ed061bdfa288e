#pragma once
// Outputs appear complete or not at all: bytes go to a private temporary sibling (created
// exclusively, mkstemp-style), every write is checked, the file is flushed to disk, and only then
// renamed into place. A failure (disk full, file-size limit, permissions) removes the temporary
// and throws OutputError; the final name is never left truncated.
#include <string>
#include <string_view>

namespace omnicam {

void writeBytesAtomically(const std::string& path, std::string_view bytes);
inline void writeTextAtomically(const std::string& path, const std::string& text) {
  writeBytesAtomically(path, text);
}

// Throws InputError("<flag>: <path> is an existing folder") if `path` names a folder: an output
// file must never be renamed onto one (checked before any work, so nothing is half-written).
void requireNotAFolder(const std::string& path, const std::string& flag);

// Temporary siblings left behind by killed runs match this (".<stem>.tmp-XXXXXX<ext>").
bool isAtomicTemporaryName(const std::string& fileName);

}  // namespace omnicam
