#include "slurm_cluster.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace omnicam::testing {

namespace fs = std::filesystem;

std::map<int, std::string> frameHashes(const fs::path& dataset) {
  const nlohmann::json manifest = nlohmann::json::parse(readFile(dataset / "manifest.json"));
  std::map<int, std::string> hashes;
  for (const nlohmann::json& frame : manifest.at("frames")) hashes[frame.at("index")] = frame.at("cameras").dump();
  return hashes;
}

SlurmCluster::SlurmCluster(const fs::path& root) : root_(root) {
  for (const char* sub : {"state", "spool", "log"}) fs::create_directories(root_ / sub);
  for (const char* binary : {"/usr/sbin/munged", "/usr/sbin/mungekey", "/usr/sbin/slurmctld", "/usr/sbin/slurmd",
                             "/usr/bin/sbatch", "/usr/bin/sinfo", "/usr/bin/squeue", "/usr/bin/scancel"})
    if (!fs::exists(binary)) problem_ += std::string(binary) + " is missing (make deps installs slurmctld slurmd slurm-client munge); ";
  if (!problem_.empty()) return;
  const std::string key = (root_ / "munge.key").string();
  if (runShell("/usr/sbin/mungekey -c -b 1024 -k " + key + " 2>&1").code != 0) {
    problem_ = "mungekey could not create a key";
    return;
  }
  const std::string socket = (root_ / "munge.sock").string();
  start("munged", {"/usr/sbin/munged", "-F", "-f", "--key-file=" + key, "--socket=" + socket,
                   "--pid-file=" + (root_ / "munged.pid").string(), "--log-file=" + (root_ / "log/munged.log").string(),
                   "--seed-file=" + (root_ / "munged.seed").string()});
  // munged must be up before the Slurm daemons authenticate through it.
  // (The limits here and below only bound a failure; a loaded machine reaches them never.)
  if (!waitFor([&] { return fs::exists(socket); }, 120.0)) {
    problem_ = "munged never created its socket " + socket + logs();
    return;
  }
  const int controllerPort = TestDaemons::freePort(), nodePort = TestDaemons::freePort();
  std::ofstream(root_ / "slurm.conf")
      << "ClusterName=omnicamtest\nSlurmctldHost=localhost(127.0.0.1)\nSlurmctldPort=" << controllerPort
      << "\nSlurmdPort=" << nodePort << "\nSlurmUser=root\nSlurmdUser=root\nAuthType=auth/munge\nAuthInfo=socket="
      << socket << "\nCredType=cred/munge\nProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
      << "JobAcctGatherType=jobacct_gather/none\nAccountingStorageType=accounting_storage/none\nMpiDefault=none\n"
      << "SwitchType=switch/none\nSchedulerType=sched/builtin\nSelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\n"
      << "StateSaveLocation=" << (root_ / "state").string() << "\nSlurmdSpoolDir=" << (root_ / "spool").string()
      << "\nSlurmctldPidFile=" << (root_ / "slurmctld.pid").string() << "\nSlurmdPidFile="
      << (root_ / "slurmd.pid").string() << "\nSlurmctldLogFile=" << (root_ / "log/slurmctld.log").string()
      << "\nSlurmdLogFile=" << (root_ / "log/slurmd.log").string()
      << "\nReturnToService=2\nInactiveLimit=0\nKillWait=2\n"
      << "NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN\n"
      << "PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP\n";
  conf_ = (root_ / "slurm.conf").string();
  start("slurmctld", {"/usr/sbin/slurmctld", "-D", "-i", "-f", conf_});
  start("slurmd", {"/usr/sbin/slurmd", "-D", "-f", conf_, "-N", "localhost"});
  if (!waitFor([&] { return shell("/usr/bin/sinfo -h -o %t").out.find("idle") != std::string::npos; }, 180.0))
    problem_ = "the node never became idle; sinfo: " + shell("/usr/bin/sinfo 2>&1").out + logs();
}

CommandResult SlurmCluster::shell(const std::string& command) const {
  return runShell("SLURM_CONF=" + conf_ + " " + command);
}

bool SlurmCluster::waitUntilDone(const std::vector<std::string>& jobs, double seconds) const {
  std::string list;
  for (const std::string& j : jobs) list += (list.empty() ? "" : ",") + j;
  return waitFor([&] { return shell("/usr/bin/squeue -h -j " + list + " 2>/dev/null").out.empty(); }, seconds);
}

std::string SlurmCluster::logs() const {
  std::string out;
  for (const char* log : {"log/slurmctld.log", "log/slurmd.log", "munged.out", "slurmctld.out", "slurmd.out"})
    out += std::string("\n--- ") + log + ":\n" + readFile(root_ / log).substr(0, 3000);
  return out;
}

void SlurmCluster::start(const std::string& name, const std::vector<std::string>& argv) {
  if (!daemons_.start(name, argv, root_ / (name + ".out"))) problem_ += "cannot start " + name + "; ";
}

}  // namespace omnicam::testing
