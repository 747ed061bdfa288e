#include "ros_master.h"

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

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
  // A foreign process on the port may accept and never answer: give up on it after 2 s.
  const timeval patience{2, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &patience, sizeof patience);
  ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &patience, sizeof patience);
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
  // The reply is the array [code, message, pid]: code 1, then the pid as the third value's <int>
  // (or <i4>).
  size_t at = reply.find("<data>");
  std::vector<std::string> values;
  while (at != std::string::npos && values.size() < 3) {
    const size_t open = reply.find("<value>", at), close = reply.find("</value>", open);
    if (open == std::string::npos || close == std::string::npos) break;
    values.push_back(reply.substr(open + 7, close - open - 7));
    at = close + 8;
  }
  const auto integer = [](const std::string& value) {
    const size_t digits = value.find_first_of("0123456789");
    const bool typed = value.rfind("<int>", 0) == 0 || value.rfind("<i4>", 0) == 0;
    return typed && digits != std::string::npos ? std::atoi(value.c_str() + digits) : 0;
  };
  return values.size() == 3 && integer(values[0]) == 1 ? integer(values[2]) : 0;
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
