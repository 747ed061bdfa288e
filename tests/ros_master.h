#pragma once
// A ROS 1 master of a test's own: `rosmaster --core` on a free localhost port, with ROS_HOME and
// its logs in the test's folder, stopped by its pid (TestDaemons). No roscore, no rosout.
#include <filesystem>
#include <string>

#include "test_daemons.h"

namespace omnicam::testing {

class RosMaster {
 public:
  explicit RosMaster(const std::filesystem::path& root);

  // Empty when the master accepts connections; else what went wrong, with its log.
  const std::string& problem() const { return problem_; }
  // http://127.0.0.1:PORT/, for ROS_MASTER_URI.
  const std::string& uri() const { return uri_; }
  // ROS_MASTER_URI, ROS_HOME and ROS_LOG_DIR for a process that uses this master.
  std::vector<std::string> environment() const;
  // Ends the master (SIGTERM) and waits for it: a node then finds no master.
  void stop();
  // Starts a new master on the same port (after stop()): one that knows no node.
  void restart();

 private:
  void start();

  std::filesystem::path root_;
  std::string uri_, problem_;
  int port_ = 0;
  TestDaemons daemons_;
};

}  // namespace omnicam::testing
