#include "ros_master.h"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "shell_command.h"

namespace omnicam::testing {

namespace fs = std::filesystem;

namespace {

bool accepts(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const bool connected = ::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  ::close(fd);
  return connected;
}

constexpr const char* kRosmaster = "/usr/bin/rosmaster";

}  // namespace

RosMaster::RosMaster(const fs::path& root) : root_(root) {
  if (!fs::exists(kRosmaster)) {
    problem_ = std::string(kRosmaster) + " is missing (make deps installs python3-rosmaster)";
    return;
  }
  fs::create_directories(root_ / "ros_home");
  port_ = TestDaemons::freePort();
  uri_ = "http://127.0.0.1:" + std::to_string(port_) + "/";
  start();
}

void RosMaster::restart() { start(); }

void RosMaster::start() {
  if (!daemons_.start("rosmaster", {kRosmaster, "--core", "-p", std::to_string(port_)}, root_ / "rosmaster.out",
                      environment())) {
    problem_ = "cannot start rosmaster";
    return;
  }
  // (The limit only bounds a failure; a loaded machine never reaches it.)
  if (!TestDaemons::waitFor([&] { return accepts(port_); }, 60.0))
    problem_ = "rosmaster never accepted connections on port " + std::to_string(port_) + ": " +
               readFile(root_ / "rosmaster.out").substr(0, 3000);
}

std::vector<std::string> RosMaster::environment() const {
  const std::string home = (root_ / "ros_home").string();
  return {"ROS_MASTER_URI=" + uri_, "ROS_HOME=" + home, "ROS_LOG_DIR=" + home + "/log", "ROS_IP=127.0.0.1"};
}

void RosMaster::stop() { daemons_.stop("rosmaster"); }

}  // namespace omnicam::testing
