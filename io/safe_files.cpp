#include "safe_files.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include "errors.h"
#include "sha256.h"

namespace omnicam {

namespace fs = std::filesystem;

namespace {

constexpr const char* kLinkNotFollowed = "is a symbolic link (links inside this folder are not followed)";

// Something found on the way to a path inside the folder: `where` (a prefix of the relative
// path, or all of it) and what is wrong with it. Thrown inside this file only.
struct Problem {
  std::string where, what;
  EntryKind kind = EntryKind::Other;
  bool output = false;  // the file system refused a write (OutputError), not a planted entry
};

std::string fullPath(const std::string& root, const std::string& relative) {
  return relative.empty() ? root : (fs::path(root) / relative).string();
}

[[noreturn]] void rethrow(const std::string& root, const Problem& p) {
  const std::string message = showPath(fullPath(root, p.where)) + ": " + p.what;
  if (p.output) throw OutputError(message);
  throw InputError(message);
}

std::string errorText(const std::string& action, int error) { return action + " (" + std::strerror(error) + ")"; }

// The names of a relative path. Empty names, "." and ".." are refused: each caller's paths are
// checked where they come from (a manifest, omnicam's layout); this is the last guard.
std::vector<std::string> partsOf(const std::string& relative) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (start <= relative.size()) {
    const size_t end = std::min(relative.find('/', start), relative.size());
    const std::string part = relative.substr(start, end - start);
    if (part.empty() || part == "." || part == "..")
      throw InputError(quote(relative, kEchoedPathChars) + ": not a plain relative path inside the folder");
    parts.push_back(part);
    start = end + 1;
  }
  return parts;
}

std::string prefixOf(const std::vector<std::string>& parts, size_t count) {
  std::string prefix;
  for (size_t i = 0; i < count; ++i) prefix += (i ? "/" : "") + parts[i];
  return prefix;
}

// What `name` in `folder` is, links not followed (st filled unless Missing).
EntryKind kindAt(int folder, const std::string& name, struct stat& st) {
  if (::fstatat(folder, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0)
    return errno == ENOENT ? EntryKind::Missing : EntryKind::Other;
  if (S_ISLNK(st.st_mode)) return EntryKind::Link;
  if (S_ISDIR(st.st_mode)) return EntryKind::Folder;
  return S_ISREG(st.st_mode) ? EntryKind::File : EntryKind::Other;
}

// Opens the folder `name` in `parent`, never through a link; creates it first when missing and
// `create` is set.
FileDescriptor openFolderAt(int parent, const std::string& name, const std::string& where, bool create) {
  for (int attempt = 0; attempt < 3; ++attempt) {
    const int fd = ::openat(parent, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd >= 0) return FileDescriptor(fd);
    const int error = errno;
    struct stat st {};
    switch (kindAt(parent, name, st)) {
      case EntryKind::Link: throw Problem{where, kLinkNotFollowed, EntryKind::Link};
      case EntryKind::Missing:
        if (!create) throw Problem{where, "missing", EntryKind::Missing};
        if (::mkdirat(parent, name.c_str(), 0777) != 0 && errno != EEXIST)
          throw Problem{where, errorText("cannot create folder", errno), EntryKind::Missing, true};
        break;  // created (or by someone else meanwhile): open it
      case EntryKind::Folder:
        // Made by another process (a shard) between our open and our look: open it again.
        if (error == ENOENT) break;
        throw Problem{where, errorText("cannot open folder", error), EntryKind::Other};
      default: throw Problem{where, "is not a folder", EntryKind::Other};
    }
  }
  throw Problem{where, "keeps changing while being opened", EntryKind::Other};
}

// The folder holding parts[0..count): the user's root (followed as given), then one name at a
// time.
FileDescriptor openFolders(const std::string& root, int rootFd, const std::vector<std::string>& parts, size_t count,
                           bool create) {
  // An open folder handle is walked from its descriptor; a path is opened first.
  FileDescriptor folder(rootFd >= 0 ? ::fcntl(rootFd, F_DUPFD_CLOEXEC, 0) : ::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (folder.get() < 0 && rootFd >= 0) throw Problem{"", errorText("cannot duplicate the folder's descriptor", errno), EntryKind::Other, true};
  if (folder.get() < 0) {
    const int error = errno;
    if (error != ENOENT || !create)
      throw Problem{"", error == ENOENT ? "missing" : errorText("cannot open folder", error),
                    error == ENOENT ? EntryKind::Missing : EntryKind::Other};
    std::error_code ec;
    fs::create_directories(root, ec);  // the user's own path
    if (ec) throw Problem{"", "cannot create folder (" + ec.message() + ")", EntryKind::Missing, true};
    folder = FileDescriptor(::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (folder.get() < 0) throw Problem{"", errorText("cannot open folder", errno), EntryKind::Other};
  }
  for (size_t i = 0; i < count; ++i) folder = openFolderAt(folder.get(), parts[i], prefixOf(parts, i + 1), create);
  return folder;
}

// Opens the regular file `name` in `folder` for reading: checked before opening (a FIFO or a
// device is never opened) and after (the same file, still regular); O_NONBLOCK so that a FIFO
// swapped in between cannot block the open. Its size goes to `size`.
FileDescriptor openRegularFile(int folder, const std::string& name, const std::string& where, int64_t maxBytes,
                               int64_t& size) {
  struct stat before {};
  switch (kindAt(folder, name, before)) {
    case EntryKind::File: break;
    case EntryKind::Missing: throw Problem{where, "missing", EntryKind::Missing};
    case EntryKind::Link: throw Problem{where, kLinkNotFollowed, EntryKind::Link};
    default: throw Problem{where, "is not a regular file", EntryKind::Other};
  }
  if (before.st_size > maxBytes)
    throw Problem{where, "is larger than " + std::to_string(maxBytes) + " bytes", EntryKind::File};
  FileDescriptor fd(::openat(folder, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
  if (fd.get() < 0) throw Problem{where, errorText("cannot open", errno), EntryKind::File};
  struct stat after {};
  if (::fstat(fd.get(), &after) != 0 || !S_ISREG(after.st_mode) || after.st_dev != before.st_dev ||
      after.st_ino != before.st_ino)
    throw Problem{where, "changed while being opened", EntryKind::Other};
  size = after.st_size;
  return fd;
}

// Feeds every byte of `fd` to `sink` in pieces, at most `maxBytes` in all (a file may grow).
template <typename Sink>
void readAll(int fd, const std::string& where, int64_t maxBytes, Sink&& sink) {
  std::vector<char> buffer(1 << 16);
  int64_t total = 0;
  while (true) {
    const ssize_t n = ::read(fd, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Problem{where, errorText("cannot read", errno), EntryKind::File};
    if (n == 0) return;
    total += n;
    if (total > maxBytes) throw Problem{where, "is larger than " + std::to_string(maxBytes) + " bytes", EntryKind::File};
    sink(std::string_view(buffer.data(), static_cast<size_t>(n)));
  }
}

// Runs `use(fd)` on the regular file root/relative.
template <typename Use>
void withRegularFile(const std::string& root, int rootFd, const std::string& relative, int64_t maxBytes, Use&& use) {
  const std::vector<std::string> parts = partsOf(relative);
  const FileDescriptor folder = openFolders(root, rootFd, parts, parts.size() - 1, false);
  int64_t size = 0;
  const FileDescriptor file = openRegularFile(folder.get(), parts.back(), relative, maxBytes, size);
  use(file.get(), size);
}

// flock(2) without waiting: false only while another process holds a claim that excludes this
// one. A file system without flock claims nothing and excludes nothing: true.
bool tryFlock(int fd, int operation) {
  while (::flock(fd, operation | LOCK_NB) != 0)
    if (errno != EINTR) return errno != EWOULDBLOCK;
  return true;
}

}  // namespace

SafeFolder::SafeFolder(const std::string& root, bool create) : root_(root) {
  fd_ = FileDescriptor(::open(root.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  // Not there (or not openable): each call then looks again by the path and reports what it
  // finds, as the free functions do; only a missing folder is made here, when asked.
  if (fd_.get() >= 0 || errno != ENOENT || !create) return;
  try {
    fd_ = openFolders(root_, -1, {}, 0, true);
  } catch (const Problem& p) {
    rethrow(root_, p);
  }
}

bool SafeFolder::tryClaim(bool shared) const { return fd_.get() < 0 || tryFlock(fd_.get(), shared ? LOCK_SH : LOCK_EX); }

std::optional<FileDescriptor> SafeFolder::tryClaimAlone(const std::string& relative) const {
  const std::vector<std::string> parts = partsOf(relative);
  try {
    FileDescriptor folder = openFolders(root_, fd_.get(), parts, parts.size(), true);
    if (!tryFlock(folder.get(), LOCK_EX)) return std::nullopt;
    return folder;
  } catch (const Problem& p) {
    rethrow(root_, p);
  }
}

EntryKind SafeFolder::entry(const std::string& relative) const {
  const std::vector<std::string> parts = partsOf(relative);
  try {
    const FileDescriptor folder = openFolders(root_, fd_.get(), parts, parts.size() - 1, false);
    struct stat st {};
    return kindAt(folder.get(), parts.back(), st);
  } catch (const Problem& p) {
    return p.kind == EntryKind::Missing ? EntryKind::Missing : EntryKind::Blocked;
  }
}

std::string SafeFolder::readFile(const std::string& relative, int64_t maxBytes) const {
  std::string bytes;
  try {
    withRegularFile(root_, fd_.get(), relative, maxBytes, [&](int fd, int64_t size) {
      bytes.reserve(static_cast<size_t>(size));
      readAll(fd, relative, maxBytes, [&](std::string_view piece) { bytes.append(piece); });
    });
  } catch (const Problem& p) {
    rethrow(root_, p);
  }
  return bytes;
}

void SafeFolder::checkFile(const std::string& relative, int64_t maxBytes) const {
  try {
    withRegularFile(root_, fd_.get(), relative, maxBytes, [](int, int64_t) {});
  } catch (const Problem& p) {
    rethrow(root_, p);
  }
}

FileDigest SafeFolder::sha256(const std::string& relative, int64_t maxBytes) const {
  FileDigest digest;
  try {
    withRegularFile(root_, fd_.get(), relative, maxBytes, [&](int fd, int64_t) {
      Sha256 hash;
      readAll(fd, relative, maxBytes, [&](std::string_view piece) { hash.update(piece); });
      digest.sha256 = hash.hex();
    });
  } catch (const Problem& p) {
    digest.problem = p.where == relative ? p.what : showPath(p.where) + " " + p.what;
  }
  return digest;
}

void SafeFolder::checkFolders(const std::string& relative) const {
  const std::vector<std::string> parts = partsOf(relative);
  try {
    openFolders(root_, fd_.get(), parts, parts.size(), false);
  } catch (const Problem& p) {
    if (p.kind != EntryKind::Missing) rethrow(root_, p);
  }
}

void SafeFolder::makeFolders(const std::string& relative) const {
  const std::vector<std::string> parts = partsOf(relative);
  try {
    openFolders(root_, fd_.get(), parts, parts.size(), true);
  } catch (const Problem& p) {
    rethrow(root_, p);
  }
}

void SafeFolder::writeFile(const std::string& relative, std::string_view bytes, Durability durability) const {
  writeFileFrom(relative, onePiece(bytes), durability);
}

FileDescriptor SafeFolder::folderOfNewFile(const std::vector<std::string>& parts) const {
  try {
    return openFolders(root_, fd_.get(), parts, parts.size() - 1, true);
  } catch (const Problem& p) {
    rethrow(root_, p);
  }
}

void SafeFolder::stageFile(AtomicFileGroup& group, const std::string& relative, std::string_view bytes) const {
  const std::vector<std::string> parts = partsOf(relative);
  group.stageAt(folderOfNewFile(parts), parts.back(), showPath(fullPath(root_, relative)), onePiece(bytes));
}

void SafeFolder::writeFileFrom(const std::string& relative, const PieceSource& next, Durability durability) const {
  const std::vector<std::string> parts = partsOf(relative);
  writeStreamAtomicallyAt(folderOfNewFile(parts).get(), parts.back(), showPath(fullPath(root_, relative)), next, durability);
}

bool SafeFolder::removeFile(const std::string& relative) const {
  const std::vector<std::string> parts = partsOf(relative);
  try {
    const FileDescriptor folder = openFolders(root_, fd_.get(), parts, parts.size() - 1, false);
    struct stat st {};
    return kindAt(folder.get(), parts.back(), st) == EntryKind::File &&
           ::unlinkat(folder.get(), parts.back().c_str(), 0) == 0;
  } catch (const Problem&) {
    return false;
  }
}

bool SafeFolder::removeEmptyFolder(const std::string& relative) const {
  const std::vector<std::string> parts = partsOf(relative);
  try {
    const FileDescriptor folder = openFolders(root_, fd_.get(), parts, parts.size() - 1, false);
    struct stat st {};
    // AT_REMOVEDIR removes only an empty folder, and never through a link.
    return kindAt(folder.get(), parts.back(), st) == EntryKind::Folder &&
           ::unlinkat(folder.get(), parts.back().c_str(), AT_REMOVEDIR) == 0;
  } catch (const Problem&) {
    return false;
  }
}


EntryKind entryInside(const std::string& root, const std::string& relative) { return SafeFolder(root).entry(relative); }
std::string readFileInside(const std::string& root, const std::string& relative, int64_t maxBytes) {
  return SafeFolder(root).readFile(relative, maxBytes);
}
void checkFileInside(const std::string& root, const std::string& relative, int64_t maxBytes) {
  SafeFolder(root).checkFile(relative, maxBytes);
}
FileDigest sha256Inside(const std::string& root, const std::string& relative, int64_t maxBytes) {
  return SafeFolder(root).sha256(relative, maxBytes);
}
void checkFoldersInside(const std::string& root, const std::string& relative) { SafeFolder(root).checkFolders(relative); }
void makeFoldersInside(const std::string& root, const std::string& relative) { SafeFolder(root).makeFolders(relative); }
void makeAllFoldersInside(const std::string& root, const std::vector<std::string>& relatives) {
  const SafeFolder folder(root);
  for (const std::string& relative : relatives) folder.checkFolders(relative);
  for (const std::string& relative : relatives) folder.makeFolders(relative);
}
void writeFileInside(const std::string& root, const std::string& relative, std::string_view bytes, Durability durability) {
  SafeFolder(root).writeFile(relative, bytes, durability);
}
bool removeFileInside(const std::string& root, const std::string& relative) { return SafeFolder(root).removeFile(relative); }
bool removeEmptyFolderInside(const std::string& root, const std::string& relative) {
  return SafeFolder(root).removeEmptyFolder(relative);
}

}  // namespace omnicam
