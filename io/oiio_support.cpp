#include "oiio_support.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <mutex>

#include "errors.h"
#include "input_limits.h"

namespace omnicam::image_io {

namespace {

// The redirection's state, shared by every QuietStderr.
std::mutex& mutex() {
  static std::mutex m;
  return m;
}
int& depth() {
  static int d = 0;
  return d;
}
int& saved() {
  static int fd = -1;
  return fd;
}

}  // namespace

QuietStderr::QuietStderr() {
  std::lock_guard<std::mutex> lock(mutex());
  if (depth()++ > 0) return;
  std::fflush(stderr);
  saved() = ::dup(STDERR_FILENO);
  const int devnull = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (saved() >= 0 && devnull >= 0) ::dup2(devnull, STDERR_FILENO);
  if (devnull >= 0) ::close(devnull);
}

QuietStderr::~QuietStderr() {
  std::lock_guard<std::mutex> lock(mutex());
  if (--depth() > 0) return;
  std::fflush(stderr);
  if (saved() >= 0) {
    ::dup2(saved(), STDERR_FILENO);
    ::close(saved());
    saved() = -1;
  }
}

std::string firstLine(const std::string& text) {
  const std::string line = text.substr(0, text.find('\n'));
  return line.empty() ? "no details" : line;
}

void checkHeader(const OIIO::ImageSpec& spec, const std::string& name) {
  if (spec.width < 1 || spec.height < 1 || spec.depth > 1)
    throw InputError(name + ": image has no pixels or is a volume (" + std::to_string(spec.width) + "x" +
                     std::to_string(spec.height) + ")");
  if (spec.width > limits::kMaxImageDimension || spec.height > limits::kMaxImageDimension ||
      static_cast<int64_t>(spec.width) * spec.height > limits::kMaxImagePixels)
    throw InputError(name + ": image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                     " pixels; the limit is " + std::to_string(limits::kMaxImageDimension) + " per side and " +
                     std::to_string(limits::kMaxImagePixels) + " in all");
  if (spec.nchannels < 1 || spec.nchannels > 16)
    throw InputError(name + ": image has " + std::to_string(spec.nchannels) + " channels (1 to 16 are read)");
  // One rule with the frame-file reader (exr_channels.h): pixels start at (0, 0).
  if (spec.x != 0 || spec.y != 0) throw InputError(name + ": the image's data window does not start at pixel (0, 0)");
}

}  // namespace omnicam::image_io
