#include "ros_master.h"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include "shell_command.h"

namespace omnicam::testing {

namespace fs = std::filesystem;

namespace {

// The pid of the master that answers on localhost:`port` (its XML-RPC getPid, by hand: the
// test helpers link no ROS), 0 if none answers.
int masterPidAt(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string reply;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) {
    const std::string body =
        "<?xml version=\"1.0\"?><methodCall><methodName>getPid</methodName><params><param><value>"
        "<string>/omnicam_test</string></value></param></params></methodCall>";
    const std::string request = "POST / HTTP/1.0\r\nContent-Type: text/xml\r\nContent-Length: " +
                                std::to_string(body.size()) + "\r\n\r\n" + body;
    if (::send(fd, request.data(), request.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(request.size())) {
      char buffer[4096];
      for (ssize_t n; (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) reply.append(buffer, static_cast<size_t>(n));
    }
  }
  ::close(fd);
  // The reply is [code, message, pid]: the third <int> (or <i4>).
  size_t at = 0;
  for (int value = 0; value < 3; ++value) {
    at = reply.find("<value>", at);
    if (at == std::string::npos) return 0;
    at += 7;
    if (value == 0 && reply.compare(at, 7, "<array>") == 0) --value;  // the reply's outer array
  }
  const size_t digits = reply.find_first_of("0123456789", at);
  return digits == std::string::npos ? 0 : std::atoi(reply.c_str() + digits);
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
  // Until this master answers: another process could have taken the free port first, so the
  // answer must come from the pid started. (The limit only bounds a failure.)
  const pid_t pid = daemons_.pid("rosmaster");
  if (!TestDaemons::waitFor([&] { return masterPidAt(port_) == pid; }, 60.0))
    problem_ = "rosmaster (pid " + std::to_string(pid) + ") never answered on port " + std::to_string(port_) + ": " +
               readFile(root_ / "rosmaster.out").substr(0, 3000);
}

std::vector<std::string> RosMaster::environment() const {
  const std::string home = (root_ / "ros_home").string();
  return {"ROS_MASTER_URI=" + uri_, "ROS_HOME=" + home, "ROS_LOG_DIR=" + home + "/log", "ROS_IP=127.0.0.1"};
}

void RosMaster::stop() { daemons_.stop("rosmaster"); }

}  // namespace omnicam::testing
