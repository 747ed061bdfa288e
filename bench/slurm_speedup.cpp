// Slurm speed-up of a POV-Ray ground-truth dataset on one 2-CPU node: the same dataset as a job
// array of 2 tasks × 1 thread (--cpus-per-task=1, each POV-Ray on Work_Threads=1) against 1 task
// × 2 threads (--cpus-per-task=2). Starts a single-node cluster of its own (tests/slurm_cluster.h),
// times each submission from sbatch to the merge job's end (whole-process wall time, one run),
// checks both datasets verify and hold the same frames, and prints a table (or CSV).
//
//   build/bin/slurm_speedup [--frames N] [--spp S] [--size PX] [--csv FILE]   (defaults 24, 16, 360)
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>

#include "bench_flags.h"

#include "slurm_cluster.h"

namespace fs = std::filesystem;
using omnicam::testing::frameHashes;
using omnicam::testing::SlurmCluster;

namespace {

struct Config {
  const char* name;
  int shards, cpusPerTask;
};

// Thrown, not exited: the cluster's destructor must stop the daemons.
[[noreturn]] void fail(const std::string& what) { throw std::runtime_error(what); }

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress lines as they come, also into a pipe
  const omnicam::bench::BenchFlags flags(argc, argv, {"--frames", "--spp", "--size", "--csv"},
                                         "slurm_speedup [--frames N] [--spp N] [--size PX] [--csv PATH]");
  const int frames = flags.integer("--frames", 24, 1, 100000), spp = flags.integer("--spp", 16, 1, 65536),
            size = flags.integer("--size", 360, 8, 16384);
  const std::string csv = flags.text("--csv", "");
  if (::geteuid() != 0) {
    std::fprintf(stderr, "slurm_speedup: the cluster's daemons run as root (SlurmUser=root)\n");
    return 1;
  }
  const fs::path dir = fs::temp_directory_path() / ("omnicam_slurm_speedup_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  int status = 0;
  try {
    const SlurmCluster cluster(dir / "cluster");
    if (!cluster.problem().empty()) fail("Slurm did not start: " + cluster.problem() + cluster.logs());
    const fs::path spec = dir / "spec.json";
    std::ofstream(spec) << R"({"format": "omnicam-dataset/1", "scene": ")" << OMNICAM_SOURCE_DIR
                        << R"(/scenes/robocup2006.json", "engine": "povray", "spp": )" << spp << R"(, "size": )" << size
                        << R"(, "poses": {"path": "thesis-loop", "frames": )" << frames << R"(}, "outputs": {"rgb": "png"}})";
    const Config configs[] = {{"1 task x 2 threads", 1, 2}, {"2 tasks x 1 thread", 2, 1}};
    double seconds[2] = {0, 0};
    std::printf("POV-Ray dataset on Slurm: robocup2006 thesis-loop, %d frames, %dx%d, %d spp, one 2-CPU node\n", frames,
                size, size, spp);
    for (int c = 0; c < 2; ++c) {
      const Config& config = configs[c];
      const fs::path out = dir / ("ds" + std::to_string(c));
      const auto start = std::chrono::steady_clock::now();
      const auto r = cluster.shell(std::string(OMNICAM_BINARY) + " dataset " + spec.string() + " -o " + out.string() +
                                   " --backend slurm --shards " + std::to_string(config.shards) +
                                   " --slurm-args \"--cpus-per-task=" + std::to_string(config.cpusPerTask) + "\" 2>&1");
      std::smatch ids;
      if (r.code != 0 || !std::regex_search(r.out, ids, std::regex(R"(array job (\d+) .* merge job (\d+))")))
        fail("submission failed: " + r.out + cluster.logs());
      if (!cluster.waitUntilDone({ids[1], ids[2]}, 3600.0)) fail("the jobs did not end within an hour" + cluster.logs());
      seconds[c] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const auto verify = omnicam::testing::runShell(std::string(OMNICAM_BINARY) + " dataset --verify " + out.string() + " 2>&1");
      if (verify.code != 0) fail(config.name + std::string(": the dataset does not verify: ") + verify.out);
      std::printf("  %-20s %8.1f s  %7.2f s/frame\n", config.name, seconds[c], seconds[c] / frames);
    }
    const bool same = frameHashes(dir / "ds0") == frameHashes(dir / "ds1");
    std::printf("  speed-up of 2 tasks x 1 thread over 1 task x 2 threads: %.2fx; same frames: %s\n",
                seconds[0] / seconds[1], same ? "yes" : "NO");
    if (!same) status = 1;
    if (!csv.empty())
      std::ofstream(csv) << "config,tasks,threads_per_task,frames,seconds\n"
                         << "1x2,1,2," << frames << "," << seconds[0] << "\n2x1,2,1," << frames << "," << seconds[1] << "\n";
  } catch (const std::exception& e) {
    std::fprintf(stderr, "slurm_speedup: %s\n(files kept in %s)\n", e.what(), dir.c_str());
    return 1;
  }
  fs::remove_all(dir);
  return status;
}
