// make bench: what a dataset frame costs, part by part — the fused colour + AOV render and
// each file's encoding — for a 360×360 robocup2006 frame at 1 spp (Google Benchmark).
// The whole-process ratio (all outputs against RGB only) is bench/dataset_ratio.sh.
#include <OpenImageIO/imageio.h>
#include <benchmark/benchmark.h>
#include <cstdlib>

#include "fast_renderer.h"
#include "image.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

struct Frame {
  Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  FastRenderer renderer{scene};
  RenderSettings settings;
  ImageRGBA rgb;
  AovFrame aovs;
  Frame() {
    settings.rig = scene.rig;
    settings.rig.imageSize = 360;
    rgb = renderer.render(scene.startPose, settings, aovs);
  }
};

Frame& frame() {
  static Frame f;
  return f;
}

void BM_RenderRgb(benchmark::State& state) {
  Frame& f = frame();
  for (auto _ : state) benchmark::DoNotOptimize(f.renderer.render(f.scene.startPose, f.settings));
}
void BM_RenderRgbAndAovs(benchmark::State& state) {
  Frame& f = frame();
  AovFrame aovs;
  for (auto _ : state) benchmark::DoNotOptimize(f.renderer.render(f.scene.startPose, f.settings, aovs));
}
void BM_EncodeRgbPng(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(encodeImage("rgb.png", frame().rgb));
}
void BM_EncodeDepthExr(benchmark::State& state) {
  const AovFrame& a = frame().aovs;
  for (auto _ : state) benchmark::DoNotOptimize(encodeDataExr("depth.exr", a.width, a.height, 1, a.depth.data()));
}
void BM_EncodeNormalExr(benchmark::State& state) {
  const AovFrame& a = frame().aovs;
  for (auto _ : state) benchmark::DoNotOptimize(encodeDataExr("normal.exr", a.width, a.height, 3, a.normal.data(), ExrPrecision::Half));
}
void BM_EncodeInstancePng(benchmark::State& state) {
  const AovFrame& a = frame().aovs;
  for (auto _ : state) benchmark::DoNotOptimize(encodeUint16Png("instance.png", a.width, a.height, a.instance));
}
BENCHMARK(BM_RenderRgb)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderRgbAndAovs)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EncodeRgbPng)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EncodeDepthExr)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EncodeNormalExr)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EncodeInstancePng)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace omnicam

int main(int argc, char** argv) {
  if (const char* t = std::getenv("EXR_THREADS")) OIIO::attribute("exr_threads", std::atoi(t));
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
}
