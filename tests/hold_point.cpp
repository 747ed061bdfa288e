#include "hold_point.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <thread>
#include <vector>

namespace omnicam::testing {

namespace fs = std::filesystem;

HoldPoint::HoldPoint(const fs::path& folder, const std::string& manifestName)
    : folder_(folder), manifestName_(manifestName) {
  fs::create_directories(folder_);
  ::mkfifo((folder_ / "release").c_str(), 0600);
}

HoldPoint::~HoldPoint() { release(); }

std::vector<std::string> HoldPoint::environment() const {
  return {"LD_PRELOAD=" OMNICAM_HOLD_PRELOAD, "OMNICAM_HOLD_MANIFEST=" + manifestName_,
          "OMNICAM_HOLD_DIR=" + folder_.string()};
}

std::string HoldPoint::shellAssignments() const {
  std::string line;
  for (const std::string& assignment : environment()) {
    const size_t equals = assignment.find('=');
    line += assignment.substr(0, equals + 1) + "'" + assignment.substr(equals + 1) + "' ";
  }
  return line;
}

bool HoldPoint::waitUntilHeld(const std::function<bool()>& ended, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  // Opening the FIFO for writing without blocking succeeds only while the held process has it
  // open for reading: that is the hold itself, not a moment that could pass.
  while (std::chrono::steady_clock::now() < deadline) {
    releaseFd_ = ::open((folder_ / "release").c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (releaseFd_ >= 0) return true;
    if (errno != ENXIO || ended()) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // polling, not timing: see above
  }
  return false;
}

void HoldPoint::release() {
  if (releaseFd_ >= 0) ::close(releaseFd_);
  releaseFd_ = -1;
}

}  // namespace omnicam::testing
