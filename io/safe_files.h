#pragma once
// Files inside a folder whose contents omnicam does not trust: a dataset folder on a shared file
// system, where other users, a colleague's archive or an earlier tool may have planted symbolic
// links, FIFOs, devices or huge files. The folder itself is the user's own (its path is followed
// as given); every path inside it is walked one name at a time with openat(O_NOFOLLOW), so no
// link inside is ever followed. Files are opened non-blocking, after lstat said they are regular
// (a FIFO never blocks, a device is never opened), and read or hashed only up to a size bound.
//
// Errors name the file (root/relative): InputError for what was found there (exit 2),
// OutputError when the file system refuses to create or write (exit 5).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "atomic_file.h"
#include "file_descriptor.h"

namespace omnicam {

// What a path inside the folder is, links not followed. Missing also when a folder on the way
// is missing; Blocked when something on the way is a link or not a folder.
enum class EntryKind { Missing, File, Folder, Link, Other, Blocked };

struct FileDigest;

// A folder omnicam does not trust, opened once (a dataset's): every path inside it is walked
// from the held descriptor, one name at a time, never re-walked from the root's own path. The
// free functions below do the same for a folder named by its path, opening it on each call.
class SafeFolder {
 public:
  // Opens `root` (followed as given: the user's own path); with `create`, makes it first when
  // missing (OutputError if that fails). A missing folder without `create` is looked for again by
  // each call, as the free functions do.
  explicit SafeFolder(const std::string& root, bool create = false);
  const std::string& path() const { return root_; }

  EntryKind entry(const std::string& relative) const;
  std::string readFile(const std::string& relative, int64_t maxBytes) const;
  void checkFile(const std::string& relative, int64_t maxBytes) const;
  FileDigest sha256(const std::string& relative, int64_t maxBytes) const;
  void checkFolders(const std::string& relative) const;
  void makeFolders(const std::string& relative) const;
  void writeFile(const std::string& relative, std::string_view bytes, Durability durability) const;
  // writeFile fed piece by piece (writeStreamAtomicallyAt): a file of any size in one piece's memory.
  void writeFileFrom(const std::string& relative, const PieceSource& next, Durability durability) const;
  // writeFileFrom into `group`: the file appears with the group's others when it commits.
  void stageFile(AtomicFileGroup& group, const std::string& relative, std::string_view bytes) const;
  bool removeFile(const std::string& relative) const;
  bool removeEmptyFolder(const std::string& relative) const;
  // Claims the folder for this process (flock(2) on the folder itself: no lock file, and the claim
  // ends with the process however it ends): `shared` with other shared claims, or alone. False if
  // another process holds a claim that excludes this one; true for a folder not opened.
  bool tryClaim(bool shared) const;
  // The folder `relative` inside (made as needed, reached without following links) claimed by this
  // process alone, for as long as the descriptor returned lives: for a short step no two processes
  // may take at once. nullopt while another process holds a claim on it (the caller waits, and
  // can stop waiting). Where the file system has no claims, the folder's descriptor, claiming nothing.
  std::optional<FileDescriptor> tryClaimAlone(const std::string& relative) const;

 private:
  // The folder a new file `parts` goes into, made as needed, reached without following links.
  FileDescriptor folderOfNewFile(const std::vector<std::string>& parts) const;

  std::string root_;
  FileDescriptor fd_;
};

EntryKind entryInside(const std::string& root, const std::string& relative);

// The whole of a regular file of at most `maxBytes`; InputError otherwise (missing, a link or
// something not a folder on the way, not a regular file, larger).
std::string readFileInside(const std::string& root, const std::string& relative, int64_t maxBytes);

// Checks that root/relative is what readFileInside would read, without reading it.
void checkFileInside(const std::string& root, const std::string& relative, int64_t maxBytes);

// SHA-256 of a regular file of at most `maxBytes`, streamed. `problem` says why there is none:
// "missing", "is a symbolic link (not followed)", "is not a regular file", ...
struct FileDigest {
  std::string sha256, problem;
  bool ok() const { return problem.empty(); }
};
FileDigest sha256Inside(const std::string& root, const std::string& relative, int64_t maxBytes);

// Checks, creating nothing, that every part of `relative` that exists is a folder and not a link.
void checkFoldersInside(const std::string& root, const std::string& relative);
// Creates the folder `relative` and the missing folders on the way, each checked like that.
void makeFoldersInside(const std::string& root, const std::string& relative);
// A run's own folders inside its output folder: every one checked first, then all made, so a
// link planted under one of the names stops the run before anything is made or written.
void makeAllFoldersInside(const std::string& root, const std::vector<std::string>& relatives);
// writeBytesAtomically for root/relative: its folders walked like that (missing ones created),
// the temporary created exclusively beside it, renamed into place.
void writeFileInside(const std::string& root, const std::string& relative, std::string_view bytes,
                     Durability durability);

// Removes root/relative if it is a regular file (never a link, a folder or anything else);
// true if it did.
bool removeFileInside(const std::string& root, const std::string& relative);
// Removes root/relative if it is an empty folder (not a link); true if it did.
bool removeEmptyFolderInside(const std::string& root, const std::string& relative);

}  // namespace omnicam
