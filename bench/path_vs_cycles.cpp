// make bench: how long the fast renderer's path shading and Blender Cycles each take per frame to
// reach a given error (PSNR, 8-bit sRGB inside the mirror) against a converged frame of the
// textured hall at 360 px — both engines converge to the same frame (docs/path-tracing.md,
// "Measured") — one engine after the other in one run. Each engine renders the hall's three poses
// as a sequence: the fast renderer after a warm-up frame, Cycles in one Blender session whose first
// frame and start-up are reported apart (docs/performance.md, "Path shading"). Prints the ladder
// and the time ratios; the converged frame is the fast renderer's (2 × 1024 spp, unfiltered, about
// a minute).
#include <cstdio>
#include <filesystem>

#include "bench_flags.h"
#include "hall_arena.h"
#include "malloc_tuning.h"
#include "path_convergence.h"
#include "scene_loader.h"

int main(int argc, char** argv) {
  using namespace omnicam;
  const bench::BenchFlags flags(argc, argv, {}, "path_vs_cycles (no options)");
  keepFreedMemoryInTheHeap();  // as the CLI does: frames' buffers are not faulted in anew
  const Scene scene = loadScene(writeLabHall(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json",
                                            (std::filesystem::temp_directory_path() / "omnicam_path_vs_cycles").string()));
  const std::vector<RobotPose> poses = hallPoses();
  const RobotPose& pose = poses.front();
  PathConvergenceOptions options;
  std::printf("path_vs_cycles: converged fast frame (%d x %d spp)...\n", options.fastConvergedSeeds, options.fastConvergedSpp);
  const ImageRGBA converged = convergedFastFrame(scene, pose, options.size, options.fastConvergedSpp, options.fastConvergedSeeds);
  PathConvergenceResults results;
  measureTimeToError(scene, poses, converged, options, results, [](const std::string&, int done, int total) {
    std::printf("path_vs_cycles: %d of %d\n", done, total);
  });
  std::printf("%-8s %5s %9s %12s %11s %8s\n", "engine", "spp", "denoised", "s per frame", "start-up s", "PSNR dB");
  for (const LadderPoint& p : results.ladder)
    std::printf("%-8s %5d %9s %12.3f %11.2f %8.2f\n", p.engine.c_str(), p.spp, p.filtered ? "yes" : "no", p.seconds,
                p.startupSeconds, p.psnrDb);
  for (const auto& t : results.timeToError) {
    if (t.fastSeconds > 0.0 && t.cyclesSeconds > 0.0)
      std::printf("to %.0f dB: fast %.3f s, Cycles %.2f s per frame: %.0fx\n", t.targetDb, t.fastSeconds, t.cyclesSeconds,
                  t.cyclesSeconds / t.fastSeconds);
    else
      std::printf("to %.0f dB: fast %s, Cycles %s\n", t.targetDb, t.fastSeconds > 0.0 ? "reached" : "not reached on its ladder",
                  t.cyclesSeconds > 0.0 ? "reached" : "not reached on its ladder");
  }
  return 0;
}
