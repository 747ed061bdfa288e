// `omnicam dataset --backend slurm` on a real Slurm: the test starts a single-node cluster of its
// own (munged, slurmctld, slurmd; config in a temporary folder, ports on localhost, no systemd),
// submits a dataset as a job array, kills one task with SIGKILL mid-run, resubmits (only that
// shard runs again), verifies the dataset, compares it byte for byte with a local render, and
// stops exactly the daemons it started, by pid. It never skips: a cluster that cannot start is
// a failure that says why.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <map>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <thread>

#include "shell_command.h"

extern char** environ;

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A free TCP port on localhost (the kernel's pick; released again at once).
int freePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
  socklen_t length = sizeof address;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
  ::close(fd);
  return ntohs(address.sin_port);
}

class SlurmCluster {
 public:
  explicit SlurmCluster(const fs::path& root) : root_(root) {
    for (const char* sub : {"state", "spool", "log"}) fs::create_directories(root_ / sub);
    for (const char* binary : {"/usr/sbin/munged", "/usr/sbin/mungekey", "/usr/sbin/slurmctld", "/usr/sbin/slurmd",
                               "/usr/bin/sbatch", "/usr/bin/sinfo", "/usr/bin/squeue", "/usr/bin/scancel"})
      if (!fs::exists(binary)) problem_ += std::string(binary) + " is missing (make deps installs slurmctld slurmd slurm-client munge); ";
    if (!problem_.empty()) return;
    const std::string key = (root_ / "munge.key").string();
    if (testing::runShell("/usr/sbin/mungekey -c -b 1024 -k " + key + " 2>&1").code != 0) {
      problem_ = "mungekey could not create a key";
      return;
    }
    const std::string socket = (root_ / "munge.sock").string();
    start("munged", {"/usr/sbin/munged", "-F", "-f", "--key-file=" + key, "--socket=" + socket,
                     "--pid-file=" + (root_ / "munged.pid").string(), "--log-file=" + (root_ / "log/munged.log").string(),
                     "--seed-file=" + (root_ / "munged.seed").string()});
    // munged must be up before the Slurm daemons authenticate through it.
    waitFor([&] { return fs::exists(socket); }, 10.0);
    const int controllerPort = freePort(), nodePort = freePort();
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
    if (!waitFor([&] { return shell("/usr/bin/sinfo -h -o %t").out.find("idle") != std::string::npos; }, 60.0))
      problem_ = "the node never became idle; sinfo: " + shell("/usr/bin/sinfo 2>&1").out + logs();
  }

  // Stops exactly what it started: SIGTERM, then SIGKILL after 10 s.
  ~SlurmCluster() {
    for (auto it = started_.rbegin(); it != started_.rend(); ++it) ::kill(it->second, SIGTERM);
    for (auto it = started_.rbegin(); it != started_.rend(); ++it) {
      const auto deadline = Clock::now() + std::chrono::seconds(10);
      int status = 0;
      while (::waitpid(it->second, &status, WNOHANG) == 0) {
        if (Clock::now() > deadline) {
          ::kill(it->second, SIGKILL);
          ::waitpid(it->second, &status, 0);
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    }
  }

  const std::string& problem() const { return problem_; }
  testing::CommandResult shell(const std::string& command) const {
    return testing::runShell("SLURM_CONF=" + conf_ + " " + command);
  }
  // Until none of `jobs` is queued or running.
  bool waitUntilDone(const std::vector<std::string>& jobs, double seconds) const {
    std::string list;
    for (const std::string& j : jobs) list += (list.empty() ? "" : ",") + j;
    return waitFor([&] { return shell("/usr/bin/squeue -h -j " + list + " 2>/dev/null").out.empty(); }, seconds);
  }
  std::string logs() const {
    std::string out;
    for (const char* log : {"log/slurmctld.log", "log/slurmd.log", "munged.out", "slurmctld.out", "slurmd.out"})
      out += std::string("\n--- ") + log + ":\n" + readFile(root_ / log).substr(0, 3000);
    return out;
  }

  static bool waitFor(const std::function<bool()>& ready, double seconds) {
    const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < deadline) {
      if (ready()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return ready();
  }

 private:
  void start(const std::string& name, const std::vector<std::string>& argv) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string log = (root_ / (name + ".out")).string();
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = 0;
    if (::posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ) == 0) started_.emplace_back(name, pid);
    else problem_ += "cannot start " + name + "; ";
    posix_spawn_file_actions_destroy(&actions);
  }

  fs::path root_;
  std::string conf_, problem_;
  std::vector<std::pair<std::string, pid_t>> started_;
};

class SlurmCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_slurm_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// Every frame's files and hashes, by frame index: what "the same dataset" means.
std::map<int, std::string> frameHashes(const fs::path& dataset) {
  const json manifest = json::parse(readFile(dataset / "manifest.json"));
  std::map<int, std::string> hashes;
  for (const json& frame : manifest.at("frames")) hashes[frame.at("index")] = frame.at("cameras").dump();
  return hashes;
}

TEST_F(SlurmCliTest, AJobArrayRendersTheShardsAResubmissionRedoesOnlyTheKilledOne) {
  if (::geteuid() != 0) FAIL() << "the Slurm test runs its daemons as root (SlurmUser=root); run make test as root";
  const SlurmCluster cluster(dir_ / "cluster");
  ASSERT_TRUE(cluster.problem().empty()) << "Slurm did not start: " << cluster.problem() << cluster.logs();

  // 3 shards of 32 frames: a shard takes seconds and lists its frames in batches of 8, so one
  // can be killed mid-run.
  const fs::path spec = dir_ / "spec.json";
  std::ofstream(spec) << R"({"format": "omnicam-dataset/1", "scene": ")" << OMNICAM_SOURCE_DIR
                      << R"(/scenes/robocup2006.json", "spp": 36, "shading": "lit", "size": 160,
                        "poses": {"path": "thesis-loop", "frames": 96},
                        "outputs": {"rgb": "png", "depth": true, "instance": true, "semantic": true, "normal": true, "landmarks": true}})";
  const fs::path out = dir_ / "ds";
  const std::string submit = std::string(OMNICAM_BINARY) + " dataset " + spec.string() + " -o " + out.string() +
                             " --backend slurm --shards 3 --slurm-args \"--job-name=omnicam-test --cpus-per-task=1\" 2>&1";
  auto r = cluster.shell(submit);
  ASSERT_EQ(r.code, 0) << r.out << cluster.logs();
  std::smatch ids;
  ASSERT_TRUE(std::regex_search(r.out, ids, std::regex(R"(array job (\d+) \(shards 0-2 of 3\) and merge job (\d+))"))) << r.out;
  const std::string arrayJob = ids[1], mergeJob = ids[2];

  // Kill shard 1's task with SIGKILL once it has finished a frame and before it finishes all.
  const fs::path shard1 = out / "shards/shard-1-of-3.json";
  const bool midRun = SlurmCluster::waitFor(
      [&] {
        if (!fs::exists(shard1)) return false;
        try {
          const json m = json::parse(readFile(shard1));
          return !m.at("frames").empty() && !m.at("complete").get<bool>();
        } catch (const std::exception&) {
          return false;  // read while being replaced: look again
        }
      },
      120.0);
  ASSERT_TRUE(midRun) << "shard 1 never was mid-run; its log:\n" << readFile(out / "slurm/shard-1.log")
                      << readFile(out / "slurm/sbatch.log") << cluster.logs();
  ASSERT_EQ(cluster.shell("/usr/bin/scancel --batch --signal=KILL " + arrayJob + "_1").code, 0);
  ASSERT_TRUE(cluster.waitUntilDone({arrayJob, mergeJob}, 300.0)) << cluster.shell("/usr/bin/squeue").out << cluster.logs();

  // The merge ran after the array (afterany) and found shard 1 unfinished.
  EXPECT_NE(readFile(out / "slurm/merge.log").find("shard 1/3:"), std::string::npos) << readFile(out / "slurm/merge.log");
  r = testing::runShell(std::string(OMNICAM_BINARY) + " dataset --status " + out.string() + " 2>&1");
  EXPECT_EQ(r.code, 1) << r.out;

  // Resubmitting renders only the killed shard.
  r = cluster.shell(submit);
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_TRUE(std::regex_search(r.out, ids, std::regex(R"(array job (\d+) \(shards 1 of 3\) and merge job (\d+))"))) << r.out;
  ASSERT_TRUE(cluster.waitUntilDone({ids[1], ids[2]}, 300.0)) << cluster.logs();
  r = testing::runShell(std::string(OMNICAM_BINARY) + " dataset --status " + out.string() + " 2>&1");
  EXPECT_EQ(r.code, 0) << r.out << readFile(out / "slurm/merge.log") << readFile(out / "slurm/shard-1.log");
  r = testing::runShell(std::string(OMNICAM_BINARY) + " dataset --verify " + out.string() + " 2>&1");
  EXPECT_EQ(r.code, 0) << r.out;

  // Everything submitted again: nothing left to render.
  r = cluster.shell(submit);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("every shard of 3 is complete"), std::string::npos) << r.out;

  // The same frames rendered locally in one go: byte-identical files.
  r = testing::runShell(std::string(OMNICAM_BINARY) + " dataset " + spec.string() + " -o " + (dir_ / "local").string() + " 2>&1");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(frameHashes(out), frameHashes(dir_ / "local"));
  EXPECT_EQ(frameHashes(out).size(), 96u);
}

}  // namespace
}  // namespace omnicam
