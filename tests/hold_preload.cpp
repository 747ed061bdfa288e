// LD_PRELOAD library for tests: holds an omnicam process at a point the test chooses, so that a
// test can kill or interrupt it mid-run on any machine, fast or slow (tests/hold_point.h).
//
// It wraps rename(2) and renameat(2), with which every atomic write ends (io/atomic_file.cpp;
// files inside a dataset folder are renamed relative to their open folder). After a rename
// onto a file named $OMNICAM_HOLD_MANIFEST whose content lists at least one frame and is not
// complete, it creates $OMNICAM_HOLD_DIR/held (once: a second process sharing the folder never
// holds) and blocks reading the FIFO $OMNICAM_HOLD_DIR/release until the test closes it or kills
// the process. Without those variables it only renames.
#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

using RenameFunction = int (*)(const char*, const char*);
using RenameAtFunction = int (*)(int, const char*, int, const char*);

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string fileText(const char* path) {
  std::string text;
  const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return text;
  char buffer[65536];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0 || (n < 0 && errno == EINTR);)
    if (n > 0) text.append(buffer, static_cast<size_t>(n));
  ::close(fd);
  return text;
}

// The manifest is written with nlohmann::json::dump(1): an empty frame list is "[]".
bool listsFramesAndIsIncomplete(const std::string& manifest) {
  const size_t frames = manifest.find("\"frames\": [");
  if (frames == std::string::npos) return false;
  const size_t next = manifest.find_first_not_of(" \n", frames + std::strlen("\"frames\": ["));
  return next != std::string::npos && manifest[next] != ']' && manifest.find("\"complete\": false") != std::string::npos;
}

void holdIfChosen(const char* renamedTo) {
  const char* manifestName = std::getenv("OMNICAM_HOLD_MANIFEST");
  const char* folder = std::getenv("OMNICAM_HOLD_DIR");
  if (!manifestName || !folder || !endsWith(renamedTo, std::string("/") + manifestName)) return;
  if (!listsFramesAndIsIncomplete(fileText(renamedTo))) return;
  const std::string held = std::string(folder) + "/held", release = std::string(folder) + "/release";
  const int marker = ::open(held.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (marker < 0) return;  // held once already
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::write(marker, pid.data(), pid.size()) < 0) std::perror("hold_preload: held");
  ::close(marker);
  int fd;
  while ((fd = ::open(release.c_str(), O_RDONLY | O_CLOEXEC)) < 0 && errno == EINTR) {
  }
  if (fd < 0) return;
  // Until the test closes its end (EOF) or writes to it; signals (Ctrl-C's flag) do not end it.
  for (char byte;;) {
    const ssize_t n = ::read(fd, &byte, 1);
    if (n >= 0 || errno != EINTR) break;
  }
  ::close(fd);
}

// The path `name` names relative to the open folder `folder` (or the working folder).
std::string pathAt(int folder, const char* name) {
  if (name[0] == '/') return name;
  const std::string link = folder == AT_FDCWD ? "/proc/self/cwd" : "/proc/self/fd/" + std::to_string(folder);
  char target[4096];
  const ssize_t n = ::readlink(link.c_str(), target, sizeof target);
  if (n <= 0 || static_cast<size_t>(n) == sizeof target) return name;
  return std::string(target, static_cast<size_t>(n)) + "/" + name;
}

}  // namespace

extern "C" int renameat(int fromFolder, const char* from, int toFolder, const char* to) {
  static const auto real = reinterpret_cast<RenameAtFunction>(::dlsym(RTLD_NEXT, "renameat"));
  const int result = real(fromFolder, from, toFolder, to);
  if (result == 0) {
    const int savedErrno = errno;
    holdIfChosen(pathAt(toFolder, to).c_str());
    errno = savedErrno;
  }
  return result;
}

extern "C" int rename(const char* from, const char* to) {
  static const auto real = reinterpret_cast<RenameFunction>(::dlsym(RTLD_NEXT, "rename"));
  const int result = real(from, to);
  if (result == 0) {
    const int savedErrno = errno;
    holdIfChosen(to);
    errno = savedErrno;
  }
  return result;
}
