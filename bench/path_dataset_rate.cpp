// make bench: the frames a path-traced dataset makes of the textured hall (360 px, denoised), how
// far each is from its converged frame and how many a second — issue #48's "≥ 38 dB at ≥ 4
// frames/s on 2 cores". The hall's three poses (docs/path-tracing.md) are rendered as a sequence
// after a warm-up frame, as a dataset renders them, at each spp of the ladder; PSNR is 8-bit sRGB
// inside the mirror disc against the converged fast frame of the same pose (2 × 1024 spp,
// unfiltered). The converged frames take about a minute each: given a folder (argument 1) they are
// kept there and reused by later runs (delete it after the renderer changes); without one they are
// rendered anew.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_flags.h"
#include "fast_renderer.h"
#include "hall_arena.h"
#include "image.h"
#include "malloc_tuning.h"
#include "path_convergence.h"
#include "render_noise.h"
#include "render_request.h"
#include "scene_loader.h"

namespace fs = std::filesystem;

namespace {

using namespace omnicam;

RenderSettings denoisedSettings(const Scene& scene, int spp) {
  return requestedSettings(scene.rig.resized(360), {{RequestField::Spp, int64_t{spp}},
                                                    {RequestField::Shading, "path"},
                                                    {RequestField::Denoise, true},
                                                    {RequestField::Seed, int64_t{77}}});
}

ImageRGBA cachedConverged(const Scene& scene, const RobotPose& pose, int index, const fs::path& cache) {
  const fs::path file = cache / ("converged_pose" + std::to_string(index) + ".exr");
  if (fs::is_regular_file(file)) return readImage(file.string());
  std::printf("path_dataset_rate: converged frame of pose %d (2 x 1024 spp)...\n", index);
  std::fflush(stdout);
  ImageRGBA converged = convergedFastFrame(scene, pose, 360, 1024, 2);
  writeImageAtomic(file.string(), converged);
  return converged;
}

}  // namespace

int main(int argc, char** argv) {
  keepFreedMemoryInTheHeap();  // as the CLI does: frames' buffers are not faulted in anew
  const bench::BenchFlags flags(argc, argv, {}, "path_dataset_rate [CACHE_FOLDER]", 1);
  const bool keep = !flags.positional().empty();
  const fs::path root = keep ? fs::path(flags.positional()[0])
                             : fs::temp_directory_path() / ("omnicam_path_dataset_rate_" + std::to_string(getpid()));
  const fs::path cache = root / "converged";
  fs::create_directories(cache);
  const Scene scene = loadScene(writeLabHall(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json", (root / "hall").string()));
  const std::vector<RobotPose> poses = hallPoses();
  std::vector<ImageRGBA> converged;
  for (size_t k = 0; k < poses.size(); ++k) converged.push_back(cachedConverged(scene, poses[k], static_cast<int>(k), cache));
  const FastRenderer renderer(scene);
  std::printf("%5s %12s %9s %9s %9s %9s\n", "spp", "frames/s", "pose 1", "pose 2", "pose 3", "lowest dB");
  for (int spp : {4, 9, 16, 25, 36}) {
    const RenderSettings settings = denoisedSettings(scene, spp);
    renderer.render(poses.back(), settings);  // warm: the sample table is built once per spp
    std::vector<double> psnr;
    double seconds = 0.0;
    for (size_t k = 0; k < poses.size(); ++k) {
      const auto start = std::chrono::steady_clock::now();
      const ImageRGBA frame = renderer.render(poses[k], settings);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      psnr.push_back(measureRenderNoise(frame, converged[k]).psnrDb);
    }
    std::printf("%5d %12.2f %9.2f %9.2f %9.2f %9.2f\n", spp, static_cast<double>(poses.size()) / seconds, psnr[0], psnr[1],
                psnr[2], std::min({psnr[0], psnr[1], psnr[2]}));
  }
  if (!keep) fs::remove_all(root);  // this run's own folder
  return 0;
}
