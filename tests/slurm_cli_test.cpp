// `omnicam dataset --backend slurm` on a real Slurm: the test starts a single-node cluster of its
// own (munged, slurmctld, slurmd; config in a temporary folder, ports on localhost, no systemd),
// submits a dataset as a job array, kills one task with SIGKILL mid-run, resubmits (only that
// shard runs again), verifies the dataset, compares it byte for byte with a local render, and
// stops exactly the daemons it started, by pid. It never skips: a cluster that cannot start is
// a failure that says why.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>

#include "hold_point.h"
#include "slurm_cluster.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::frameHashes;
using testing::readFile;
using testing::SlurmCluster;

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


TEST_F(SlurmCliTest, AJobArrayRendersTheShardsAResubmissionRedoesOnlyTheKilledOne) {
  if (::geteuid() != 0) FAIL() << "the Slurm test runs its daemons as root (SlurmUser=root); run make test as root";
  const SlurmCluster cluster(dir_ / "cluster");
  ASSERT_TRUE(cluster.problem().empty()) << "Slurm did not start: " << cluster.problem() << cluster.logs();

  // 3 shards of 16 frames: a shard lists its first window of 8 frames, and shard 1 is held
  // there (tests/hold_point.h) until Slurm kills it, however fast or slow the machine.
  const fs::path spec = dir_ / "spec.json";
  std::ofstream(spec) << R"({"format": "omnicam-dataset/1", "scene": ")" << OMNICAM_SOURCE_DIR
                      << R"(/scenes/robocup2006.json", "spp": 9, "shading": "lit", "size": 128,
                        "poses": {"path": "thesis-loop", "frames": 48},
                        "outputs": {"rgb": "png", "depth": true, "instance": true, "semantic": true, "normal": true, "landmarks": true}})";
  const fs::path out = dir_ / "ds";
  const std::string submit = std::string(OMNICAM_BINARY) + " dataset " + spec.string() + " -o " + out.string() +
                             " --backend slurm --shards 3 --slurm-args \"--job-name=omnicam-test --cpus-per-task=1\" 2>&1";
  testing::HoldPoint hold(dir_ / "hold", "shard-1-of-3.json");
  auto r = cluster.shell(hold.shellAssignments() + submit);  // sbatch passes the environment on
  ASSERT_EQ(r.code, 0) << r.out << cluster.logs();
  std::smatch ids;
  ASSERT_TRUE(std::regex_search(r.out, ids, std::regex(R"(array job (\d+) \(shards 0-2 of 3\) and merge job (\d+))"))) << r.out;
  const std::string arrayJob = ids[1], mergeJob = ids[2];

  // Shard 1's task, held once it has listed finished frames, is killed by Slurm with SIGKILL.
  const fs::path shard1 = out / "shards/shard-1-of-3.json";
  const bool held = hold.waitUntilHeld(
      [&] { return cluster.shell("/usr/bin/squeue -h -j " + arrayJob + " 2>/dev/null").out.empty(); }, 300.0);
  ASSERT_TRUE(held) << "shard 1 was never held mid-run; its log:\n" << readFile(out / "slurm/shard-1.log")
                    << readFile(out / "slurm/sbatch.log") << cluster.logs();
  const json midRun = json::parse(readFile(shard1));
  ASSERT_EQ(midRun.at("frames").size(), 8u) << "the first window of frames is listed at once";
  ASSERT_FALSE(midRun.at("complete").get<bool>());
  // Submitted again while shard 1 is held: the array runs and its merge waits, so nothing is
  // queued beside them (its tasks would render the same shards) and nothing in DIR changes.
  const std::string scriptBefore = readFile(out / "slurm/render.sbatch");
  const auto twice = cluster.shell(submit);
  EXPECT_EQ(twice.code, 2) << twice.out;
  EXPECT_NE(twice.out.find("the earlier submission's jobs " + arrayJob + "," + mergeJob + " are still queued or running"),
            std::string::npos) << twice.out;
  EXPECT_EQ(readFile(out / "slurm/render.sbatch"), scriptBefore);
  // --status names the jobs to look for.
  const auto whileHeld = testing::runShell(std::string(OMNICAM_BINARY) + " dataset --status " + out.string() + " 2>&1");
  EXPECT_EQ(whileHeld.code, 1) << whileHeld.out;
  EXPECT_NE(whileHeld.out.find("\n  submitted to Slurm as array job " + arrayJob + " and merge job " + mergeJob + ": `squeue --jobs=" +
                               arrayJob + "," + mergeJob + "` lists them while they are queued or running\n"),
            std::string::npos) << whileHeld.out;
  ASSERT_EQ(cluster.shell("/usr/bin/scancel --batch --signal=KILL " + arrayJob + "_1").code, 0);
  // Still held until it is gone: the hold is released only when the test ends.
  ASSERT_TRUE(cluster.waitUntilDone({arrayJob, mergeJob}, 300.0)) << cluster.shell("/usr/bin/squeue").out << cluster.logs();

  // The merge ran after the array (afterany) and found shard 1 unfinished.
  EXPECT_NE(readFile(out / "slurm/merge.log").find("shard 1/3:"), std::string::npos) << readFile(out / "slurm/merge.log");
  r = testing::runShell(std::string(OMNICAM_BINARY) + " dataset --status " + out.string() + " 2>&1");
  EXPECT_EQ(r.code, 1) << r.out;
  // What finishes it is the Slurm way: a resubmission (not shards by hand), whose merge job merges.
  EXPECT_NE(r.out.find("once the Slurm array has ended, submit the same command again to render the shards not yet finished"),
            std::string::npos) << r.out;

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
  EXPECT_EQ(frameHashes(out).size(), 48u);

  // The multilayer layout through the same array and merge: the one-go dataset's frame files and
  // its annotations gathered per camera by the merge job.
  const fs::path layered = dir_ / "layered.json";
  std::ofstream(layered) << R"({"format": "omnicam-dataset/1", "scene": ")" << OMNICAM_SOURCE_DIR
                         << R"(/scenes/robocup2006.json", "size": 64, "layout": "multilayer",
                           "poses": {"path": "thesis-loop", "frames": 6}, "outputs": {"coco": true}})";
  r = cluster.shell(std::string(OMNICAM_BINARY) + " dataset " + layered.string() + " -o " + (dir_ / "layered").string() +
                    " --backend slurm --shards 2 --slurm-args \"--job-name=omnicam-test --cpus-per-task=1\" 2>&1");
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_TRUE(std::regex_search(r.out, ids, std::regex(R"(array job (\d+) \(shards 0-1 of 2\) and merge job (\d+))"))) << r.out;
  ASSERT_TRUE(cluster.waitUntilDone({ids[1], ids[2]}, 300.0)) << cluster.logs();
  r = testing::runShell(std::string(OMNICAM_BINARY) + " dataset " + layered.string() + " -o " + (dir_ / "layered-local").string() + " 2>&1");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(frameHashes(dir_ / "layered"), frameHashes(dir_ / "layered-local"));
  EXPECT_EQ(frameHashes(dir_ / "layered").size(), 6u);
  for (const char* gathered : {"cam0/coco.json", "cam0/landmarks.json"})
    EXPECT_EQ(readFile(dir_ / "layered" / gathered), readFile(dir_ / "layered-local" / gathered)) << gathered;
  r = testing::runShell(std::string(OMNICAM_BINARY) + " dataset --verify " + (dir_ / "layered").string() + " 2>&1");
  EXPECT_EQ(r.code, 0) << r.out;
}

}  // namespace
}  // namespace omnicam
