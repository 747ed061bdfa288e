#pragma once
// A single-node Slurm cluster of its own for tests and benchmarks: munged, slurmctld and slurmd
// with a generated slurm.conf in a temporary folder, ports on localhost, 2 CPUs, no systemd
// (ProctrackType=proctrack/linuxproc, TaskPlugin=task/none; the daemons run as root). It stops
// exactly the daemons it started, by pid. A cluster that cannot start says why in problem().
#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "shell_command.h"
#include "test_daemons.h"

namespace omnicam::testing {

class SlurmCluster {
 public:
  explicit SlurmCluster(const std::filesystem::path& root);
  // Stops exactly what it started (TestDaemons).
  SlurmCluster(const SlurmCluster&) = delete;
  SlurmCluster& operator=(const SlurmCluster&) = delete;

  // Empty when the node came up idle.
  const std::string& problem() const { return problem_; }
  // Runs a shell command against this cluster (SLURM_CONF set).
  CommandResult shell(const std::string& command) const;
  // Until none of `jobs` is queued or running, at most `seconds`.
  bool waitUntilDone(const std::vector<std::string>& jobs, double seconds) const;
  // The daemons' logs (their first 3000 characters each), for failure messages.
  std::string logs() const;

  static bool waitFor(const std::function<bool()>& ready, double seconds) { return TestDaemons::waitFor(ready, seconds); }

 private:
  void start(const std::string& name, const std::vector<std::string>& argv);

  std::filesystem::path root_;
  std::string conf_, problem_;
  TestDaemons daemons_;  // the last member, so destroyed first: the daemons stop before the rest goes
};

// Every frame's files and hashes in DATASET/manifest.json, by frame index: equal maps mean the
// same dataset.
std::map<int, std::string> frameHashes(const std::filesystem::path& dataset);

}  // namespace omnicam::testing
