// make bench: frames/s of the fast renderer (exact mode) on a 360×360 robocup2006 frame at the
// thesis start pose, 1 and 16 spp, unlit and lit. Uses every core TBB finds.
#include <benchmark/benchmark.h>

#include "fast_renderer.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

const Scene& arena() {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  return scene;
}

void BM_ExactRobocup2006(benchmark::State& state) {
  const Scene& scene = arena();
  static const FastRenderer renderer(scene);
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.imageSize = 360;
  settings.spp = static_cast<int>(state.range(0));
  settings.shading = state.range(1) ? Shading::Lit : Shading::Unlit;
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(scene.startPose, settings));
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(std::string(shadingName(settings.shading)) + ", spp " + std::to_string(settings.spp));
}
BENCHMARK(BM_ExactRobocup2006)
    ->ArgNames({"spp", "lit"})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({16, 0})
    ->Args({16, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace omnicam

BENCHMARK_MAIN();
