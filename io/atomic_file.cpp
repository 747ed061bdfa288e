#include "atomic_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <random>
#include <cstdlib>
#include <cstring>
#include <climits>
#include <filesystem>
#include <string_view>

#include "errors.h"
#include "interrupts.h"
#include "file_descriptor.h"

namespace omnicam {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void failWrite(const std::string& shownPath, int folderFd, const std::string& tmp, int error) {
  if (!tmp.empty()) ::unlinkat(folderFd, tmp.c_str(), 0);
  throw OutputError(shownPath + ": cannot write (" + std::strerror(error) + ")");
}

std::string randomSuffix() {
  static std::atomic<uint64_t> counter{0};
  thread_local std::mt19937_64 random(std::random_device{}() ^ (static_cast<uint64_t>(::getpid()) << 32));
  static const char kAlphabet[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  uint64_t bits = random() ^ (counter++ * 0x9E3779B97F4A7C15ull);
  std::string suffix;
  for (int i = 0; i < 10; ++i, bits /= 36) suffix += kAlphabet[bits % 36];
  return suffix;
}

}  // namespace

namespace {

// The bytes of `next` in a fresh temporary sibling of `name`, written, checked and closed; its
// name. A failure removes it and throws OutputError.
std::string writeTemporaryAt(int folderFd, const std::string& name, const std::string& shownPath, const PieceSource& next,
                             Durability durability) {
  struct stat existing {};
  if (::fstatat(folderFd, name.c_str(), &existing, AT_SYMLINK_NOFOLLOW) == 0 && S_ISDIR(existing.st_mode))
    throw InputError(shownPath + ": is an existing folder, not a file name");
  // The temporary keeps the final extension and is created exclusively (O_EXCL, which also
  // refuses a planted link) under an unpredictable name, as mkstemp does, but with the umask's
  // permissions of a normal file.
  std::string tmp;
  int fd = -1;
  for (int attempt = 0; fd < 0; ++attempt) {
    tmp = atomicTemporaryName(name);
    fd = ::openat(folderFd, tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0 && (errno != EEXIST || attempt > 100)) failWrite(shownPath, folderFd, "", errno);
  }
  std::string_view piece;
  for (;;) {
    bool more = false;
    try {
      more = next(piece);
    } catch (...) {
      ::close(fd);
      ::unlinkat(folderFd, tmp.c_str(), 0);
      throw;
    }
    if (!more) break;
    size_t written = 0;
    while (written < piece.size()) {
      const ssize_t n = ::write(fd, piece.data() + written, piece.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const int error = n < 0 ? errno : EIO;
        ::close(fd);
        failWrite(shownPath, folderFd, tmp, error);
      }
      written += static_cast<size_t>(n);
    }
  }
  if (durability == Durability::Synced && ::fsync(fd) != 0) {
    const int error = errno;
    ::close(fd);
    failWrite(shownPath, folderFd, tmp, error);
  }
  if (::close(fd) != 0) failWrite(shownPath, folderFd, tmp, errno);
  return tmp;
}

// rename replaces whatever entry holds the name (a planted link included) and writes nothing
// through it.
void renameIntoPlace(int folderFd, const std::string& tmp, const std::string& name, const std::string& shownPath) {
  if (::renameat(folderFd, tmp.c_str(), folderFd, name.c_str()) != 0) failWrite(shownPath, folderFd, tmp, errno);
}

// A rename lives in its folder: without flushing the folder too, a power cut can lose the new name
// although the file's bytes are on disk. (A file system that cannot flush folders says EINVAL.)
void flushFolder(int folderFd, const std::string& shownPath) {
  if (::fsync(folderFd) != 0 && errno != EINVAL)
    throw OutputError(shownPath + ": written, but its folder could not be flushed to disk (" + std::strerror(errno) + ")");
}

// The folder of the user's own path: links in it are followed, as the user meant.
FileDescriptor openParentFolder(const std::string& path) {
  const fs::path target(path);
  const std::string folder = target.parent_path().empty() ? "." : target.parent_path().string();
  FileDescriptor folderFd(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (folderFd.get() < 0) failWrite(showPath(path), AT_FDCWD, "", errno);
  return folderFd;
}

}  // namespace

PieceSource onePiece(std::string_view bytes) {
  return [bytes, given = false](std::string_view& piece) mutable {
    if (given) return false;
    piece = bytes;
    return given = true;
  };
}

void writeBytesAtomically(const std::string& path, std::string_view bytes, Durability durability) {
  const FileDescriptor folderFd = openParentFolder(path);
  writeBytesAtomicallyAt(folderFd.get(), fs::path(path).filename().string(), showPath(path), bytes, durability);
}

void writeBytesAtomicallyAt(int folderFd, const std::string& name, const std::string& shownPath, std::string_view bytes,
                            Durability durability) {
  writeStreamAtomicallyAt(folderFd, name, shownPath, onePiece(bytes), durability);
}

void writeStreamAtomicallyAt(int folderFd, const std::string& name, const std::string& shownPath, const PieceSource& next,
                             Durability durability) {
  // SIGTERM or SIGINT now is acted on once the temporary is renamed or removed (base/interrupts.h).
  const DeferInterrupts deferred;
  renameIntoPlace(folderFd, writeTemporaryAt(folderFd, name, shownPath, next, durability), name, shownPath);
  if (durability == Durability::Synced) flushFolder(folderFd, shownPath);
}

struct AtomicFileGroup::Staged {
  FileDescriptor folder;
  std::string temporary, name, shownPath;
};

AtomicFileGroup::AtomicFileGroup() = default;

AtomicFileGroup::~AtomicFileGroup() {
  for (const Staged& file : staged_) ::unlinkat(file.folder.get(), file.temporary.c_str(), 0);
}

void AtomicFileGroup::stage(const std::string& path, std::string_view bytes) { stageStream(path, onePiece(bytes)); }

void AtomicFileGroup::stageStream(const std::string& path, const PieceSource& next) {
  stageAt(openParentFolder(path), fs::path(path).filename().string(), showPath(path), next);
}

void AtomicFileGroup::stageAt(FileDescriptor folder, const std::string& name, const std::string& shownPath, const PieceSource& next) {
  if (!deferred_) deferred_.emplace();
  std::string temporary = writeTemporaryAt(folder.get(), name, shownPath, next, Durability::Synced);
  staged_.push_back({std::move(folder), std::move(temporary), name, shownPath});
}

void writeFilesTogether(const std::vector<FileBytes>& files) {
  AtomicFileGroup group;
  for (const FileBytes& file : files)
    group.stage(file.path, std::string_view(reinterpret_cast<const char*>(file.bytes.data()), file.bytes.size()));
  group.commit();
}

void AtomicFileGroup::commit() {
  std::vector<Staged> renamed;
  while (!staged_.empty()) {
    renamed.push_back(std::move(staged_.front()));
    staged_.erase(staged_.begin());
    const Staged& file = renamed.back();
    renameIntoPlace(file.folder.get(), file.temporary, file.name, file.shownPath);
  }
  // Each folder once (a frame and its sidecar share theirs).
  std::set<std::pair<dev_t, ino_t>> flushed;
  for (const Staged& file : renamed) {
    struct stat folder {};
    if (::fstat(file.folder.get(), &folder) == 0 && !flushed.insert({folder.st_dev, folder.st_ino}).second) continue;
    flushFolder(file.folder.get(), file.shownPath);
  }
}

namespace {

// Every component within NAME_MAX less what a temporary adds (".", ".tmp-" and 10 characters),
// the whole within PATH_MAX: a name the file system would refuse is the user's mistake, found
// before any work.
void checkNameLengths(const std::string& path, const std::string& flag) {
  constexpr size_t kTemporaryExtra = 16;
  if (path.empty()) throw InputError(flag + ": empty path");
  if (path.size() + kTemporaryExtra >= PATH_MAX) throw InputError(flag + ": path is longer than the file system allows");
  for (const auto& part : fs::path(path))
    if (part.string().size() + kTemporaryExtra > NAME_MAX)
      throw InputError(flag + ": a name in the path is longer than " + std::to_string(NAME_MAX - kTemporaryExtra) +
                       " bytes");
}

}  // namespace

void checkOutputFile(const std::string& path, const std::string& flag) {
  checkNameLengths(path, flag);
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(flag + ": " + showPath(path) + " is an existing folder, not a file name");
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec)) {
    if (fs::exists(parent, ec)) throw InputError(flag + ": " + showPath(parent.string()) + " exists and is not a folder");
    throw InputError(flag + ": folder " + showPath(parent.string()) + " does not exist");
  }
}

void checkOutputFolder(const std::string& path, const std::string& flag) {
  checkNameLengths(path, flag);
  std::error_code ec;
  // The folder, or the nearest of its parents that exists, must be a folder: creating it would
  // fail otherwise, after other work.
  for (fs::path at = path; !at.empty(); at = at.parent_path()) {
    if (!fs::exists(at, ec) && !fs::is_symlink(at, ec)) {
      if (at == at.parent_path()) break;
      continue;
    }
    if (fs::is_symlink(at, ec) && !fs::exists(at, ec))
      throw InputError(flag + ": " + showPath(at.string()) + " is a symbolic link to nothing: remove it, or give another folder");
    if (!fs::is_directory(at, ec)) throw InputError(flag + ": " + showPath(at.string()) + " exists and is not a folder");
    break;
  }
}

bool namesSameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  const fs::path first = fs::weakly_canonical(fs::absolute(a), ec);
  if (ec) return false;
  const fs::path second = fs::weakly_canonical(fs::absolute(b), ec);
  return !ec && first == second;
}

void checkOutputIsNotInput(const std::string& path, const std::string& flag, const std::string& input,
                           const std::string& inputName) {
  std::error_code ec;
  // An output that is a link is replaced, never written through (writeBytesAtomically): the file it
  // points to is safe.
  if (fs::is_symlink(path, ec)) return;
  if (fs::exists(path, ec) && fs::exists(input, ec) && namesSameFile(path, input))
    throw InputError(flag + ": " + showPath(path) + " is " + inputName + "; writing it would destroy what is read: choose another name");
}

void checkOutputIsOutsideFolder(const std::string& path, const std::string& flag, const std::string& folder,
                                const std::string& folderName) {
  std::error_code ec;
  const fs::path output = fs::weakly_canonical(fs::absolute(path), ec);
  if (ec) return;
  const fs::path inside = fs::weakly_canonical(fs::absolute(folder), ec);
  if (ec) return;
  const auto [folderEnd, outputAt] = std::mismatch(inside.begin(), inside.end(), output.begin(), output.end());
  (void)outputAt;
  if (folderEnd == inside.end())
    throw InputError(flag + ": " + showPath(path) + " is inside " + folderName + " (" + showPath(folder) +
                     "); writing there could replace what is read: choose a place outside it");
}

std::string atomicTemporaryName(const std::string& name) {
  const fs::path leaf(name);
  return "." + leaf.stem().string() + ".tmp-" + randomSuffix() + leaf.extension().string();
}

bool isAtomicTemporaryName(const std::string& name) {
  constexpr size_t kMarker = 5, kSuffix = 10;  // ".tmp-", randomSuffix()
  const size_t at = name.rfind(".tmp-");
  if (name.empty() || name[0] != '.' || at == std::string::npos || at < 2 || name.size() < at + kMarker + kSuffix) return false;
  const std::string_view suffix(name.data() + at + kMarker, kSuffix), extension(name.data() + at + kMarker + kSuffix);
  const bool drawn = std::all_of(suffix.begin(), suffix.end(), [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'); });
  // What follows is the final name's extension (".png"), or nothing.
  const bool anExtension = extension.empty() || (extension.size() > 1 && extension[0] == '.' && extension.find('.', 1) == std::string_view::npos);
  return drawn && anExtension;
}

void removeAtomicTemporaries(const std::string& dir, const std::set<std::string>& folders) {
  const FileDescriptor root(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (root.get() < 0) return;
  for (const std::string& relative : folders) {
    // Each folder reached from the held root one name at a time, never through a link.
    FileDescriptor folder(::dup(root.get()));
    for (const fs::path& part : fs::path(relative)) {
      if (folder.get() < 0) break;
      folder = FileDescriptor(::openat(folder.get(), part.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    }
    if (folder.get() < 0) continue;
    DIR* listing = ::fdopendir(folder.get());
    if (!listing) continue;
    folder.release();  // closedir closes it
    while (const dirent* entry = ::readdir(listing)) {
      struct stat st {};
      if (isAtomicTemporaryName(entry->d_name) && ::fstatat(::dirfd(listing), entry->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 &&
          S_ISREG(st.st_mode))
        ::unlinkat(::dirfd(listing), entry->d_name, 0);  // one that fails stays; the others go on
    }
    ::closedir(listing);
  }
}

std::set<std::string> withParentFolders(const std::set<std::string>& folders) {
  std::set<std::string> all{""};
  for (const std::string& folder : folders)
    for (fs::path at = folder; !at.empty() && at != at.parent_path(); at = at.parent_path()) all.insert(at.generic_string());
  return all;
}

}  // namespace omnicam
