#pragma once
// Outputs appear complete or not at all: bytes go to a private temporary sibling (created
// exclusively, mkstemp-style), every write is checked, the file is flushed to disk, and only then
// renamed into place. A failure (disk full, file-size limit, permissions) removes the temporary
// and throws OutputError; the final name is never left truncated.
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <optional>
#include <vector>

#include "file_descriptor.h"
#include "interrupts.h"

namespace omnicam {

// Synced: fsync'd before the rename, its folder after, so it survives a power cut, not only a kill.
// Unsynced: the rename alone (a killed process still never leaves a partial file); for files
// whose hash is recorded elsewhere and checked on resume, like dataset frames.
enum class Durability { Synced, Unsynced };
void writeBytesAtomically(const std::string& path, std::string_view bytes,
                          Durability durability = Durability::Synced);
// The same for the file `name` (no '/') inside the open folder `folderFd`, which the caller
// reached without following links (safe_files.h); `shownPath` names the file in errors.
void writeBytesAtomicallyAt(int folderFd, const std::string& name, const std::string& shownPath, std::string_view bytes,
                            Durability durability);
// The same fed piece by piece (memory: one piece, whatever the file's size): `next` points its
// argument at the next piece (valid until the next call) and returns false when there are no
// more. An exception from `next` removes the temporary and propagates.
using PieceSource = std::function<bool(std::string_view& piece)>;
void writeStreamAtomicallyAt(int folderFd, const std::string& name, const std::string& shownPath, const PieceSource& next,
                             Durability durability);
inline void writeTextAtomically(const std::string& path, const std::string& text) {
  writeBytesAtomically(path, text);
}

// Files that appear together or not at all (an image and its sidecar): stage() writes each to
// its temporary (where a full disk fails: OutputError, and the group's temporaries go),
// commit() then renames them all into place. A group destroyed uncommitted removes its
// temporaries: nothing appears. The renames are one after another: one that fails (a folder
// made under the name meanwhile, a file system remounted read-only) leaves the files renamed
// before it in place. From the first stage() on, SIGTERM and SIGINT wait for the group: have
// every file's bytes ready before.
class AtomicFileGroup {
 public:
  AtomicFileGroup();
  ~AtomicFileGroup();
  AtomicFileGroup(const AtomicFileGroup&) = delete;
  AtomicFileGroup& operator=(const AtomicFileGroup&) = delete;
  // The user's own path (links in its folders followed, as the user meant).
  void stage(const std::string& path, std::string_view bytes);
  void stageStream(const std::string& path, const PieceSource& next);
  // `name` in the open folder `folder` (SafeFolder's: reached without following links).
  void stageAt(FileDescriptor folder, const std::string& name, const std::string& shownPath, const PieceSource& next);
  void commit();

 private:
  struct Staged;
  std::optional<DeferInterrupts> deferred_;  // from the first stage(): its temporaries are renamed or removed first
  std::vector<Staged> staged_;
};

// `bytes` as a PieceSource of one piece.
PieceSource onePiece(std::string_view bytes);

// A file's path and its bytes, ready to be written.
struct FileBytes {
  std::string path;
  std::vector<unsigned char> bytes;
};
// The files through one AtomicFileGroup: all of them, or none.
void writeFilesTogether(const std::vector<FileBytes>& files);

// Checks, before any work, that `path` can become an output file: not an existing folder, in a
// folder that exists, its name short enough for the file system with the temporary's suffix.
// InputError("<flag>: <path> ...") otherwise.
void checkOutputFile(const std::string& path, const std::string& flag);
// The same for an output folder: a folder already, or a name that can be created.
void checkOutputFolder(const std::string& path, const std::string& flag);
// Whether two names reach one file: the same file when both exist (hard links too), else the same
// path once made absolute, with links and "." and ".." resolved (names of files yet to be written).
bool namesSameFile(const std::string& a, const std::string& b);
// InputError("<flag>: <path> is <inputName>; ...") if `path` names the same existing file as
// `input`, by any spelling or hard link: writing it would destroy what is being read. (A `path`
// that is a symbolic link is replaced by the write, not written through: allowed.)
void checkOutputIsNotInput(const std::string& path, const std::string& flag, const std::string& input,
                           const std::string& inputName);

// InputError("<flag>: <path> is inside <folderName> ...") if `path` lies in `folder` or below it,
// by any spelling (links in the existing part resolved): an output there could replace what a
// command reads from the folder (a compared dataset's manifest or frames).
void checkOutputIsOutsideFolder(const std::string& path, const std::string& flag, const std::string& folder,
                                const std::string& folderName);

// A fresh unpredictable temporary name for the file `name`: ".<stem>.tmp-XXXXXXXXXX<ext>".
std::string atomicTemporaryName(const std::string& name);
// Whether `fileName` is a name atomicTemporaryName gives: ".<stem>.tmp-" and exactly its 10
// characters (a-z, 0-9), then the extension if any.
bool isAtomicTemporaryName(const std::string& fileName);
// Removes the temporaries killed runs left directly in `folders` (relative to `dir`; "" is `dir`
// itself): regular files of such names only. A folder that is a link is not looked into, and
// nothing elsewhere is touched: a user's own files, in folders omnicam did not make or of names
// it does not give, stay. Errors are ignored.
void removeAtomicTemporaries(const std::string& dir, const std::set<std::string>& folders);
// `folders` and every folder above each of them, up to "" (`dir` itself).
std::set<std::string> withParentFolders(const std::set<std::string>& folders);

}  // namespace omnicam
