// make bench: what a dataset frame costs, part by part — the fused colour + AOV render and
// each file's encoding — for a 360×360 robocup2006 frame at 1 spp (Google Benchmark).
// The whole-process ratio (all outputs against RGB only) is bench/dataset_ratio.sh.
#include <OpenImageIO/imageio.h>
#include <benchmark/benchmark.h>
#include <cstdlib>

#include "exr_channels.h"
#include "fast_renderer.h"
#include "image.h"
#include "malloc_tuning.h"
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
    settings.rig.mirrorRig().imageSize = 360;
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
// One multilayer frame file: colour (half) alone, or with depth (float32), normals (half) and
// instance and class ids (uint32), by compression (state.range(0): ExrCompression), colour as
// half or float32 (state.range(2)).
void BM_EncodeMultilayer(benchmark::State& state) {
  const Frame& f = frame();
  const AovFrame& a = f.aovs;
  const bool everything = state.range(1) != 0;
  std::vector<uint32_t> instance(a.instance.begin(), a.instance.end()), semantic = instance;
  std::vector<ExrChannelSource> channels;
  const ExrSampleType colour = state.range(2) ? ExrSampleType::Float : ExrSampleType::Half;
  for (int c = 0; c < 4; ++c) channels.push_back({std::string(1, "RGBA"[c]), colour, f.rgb.pixels.data() + c, nullptr, 4});
  if (everything) {
    channels.push_back({"depth.Z", ExrSampleType::Float, a.depth.data(), nullptr, 1});
    for (int c = 0; c < 3; ++c) channels.push_back({std::string("normal.") + "XYZ"[c], ExrSampleType::Half, a.normal.data() + c, nullptr, 3});
    channels.push_back({"instance.I", ExrSampleType::Uint, nullptr, instance.data(), 1});
    channels.push_back({"semantic.I", ExrSampleType::Uint, nullptr, semantic.data(), 1});
  }
  ExrWriteOptions options;
  options.compression = static_cast<ExrCompression>(state.range(0));
  size_t size = 0;
  for (auto _ : state) size = encodeExrChannels("frame.exr", a.width, a.height, channels, options).size();
  state.counters["MB"] = static_cast<double>(size) / 1e6;
}
// Rows read as BM_EncodeMultilayer/compression:1/every_channel:0/float_colour:0 (compression: 0
// none, 1 RLE, 3 zip; ExrCompression).
BENCHMARK(BM_EncodeMultilayer)
    ->ArgsProduct({{0, 1, 3}, {0, 1}, {0, 1}})
    ->ArgNames({"compression", "every_channel", "float_colour"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_RenderRgb)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderRgbAndAovs)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EncodeRgbPng)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EncodeDepthExr)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EncodeNormalExr)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EncodeInstancePng)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace omnicam

int main(int argc, char** argv) {
  omnicam::keepFreedMemoryInTheHeap();  // as the CLI does
  if (const char* t = std::getenv("EXR_THREADS")) OIIO::attribute("exr_threads", std::atoi(t));
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;  // as the other benchmarks: a typo starts no run
  benchmark::RunSpecifiedBenchmarks();
}
