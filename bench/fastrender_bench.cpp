// make bench: frames/s of the fast renderer (exact mode) on a 360×360 robocup2006 frame at the
// thesis start pose, 1 and 16 spp, unlit and lit: the ideal rig in closed form, and a physical
// rig (2 mm / 1° misaligned, distorting lens) traced through the mirror (docs/physical-camera.md:
// target ≥ 50 % of the closed form's frames/s); and moving frames (docs/motion.md). Uses every
// core TBB finds.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "fast_renderer.h"
#include "recording_camera.h"
#include "hall_arena.h"
#include "malloc_tuning.h"
#include "scene_loader.h"
#include "test_lenses.h"

namespace omnicam {
namespace {

const Scene& arena() {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  return scene;
}

void renderFrames(benchmark::State& state, const FastRenderer& renderer, const RigSpec& rig,
                  const BodyVelocity& velocity = {}) {
  const Scene& scene = arena();
  RenderSettings settings;
  settings.rig = rig;
  // The mirror rigs at 360², as they always were benchmarked; a lens at its own size.
  std::visit(Overloaded{[](MirrorRig& mirror) { mirror.imageSize = 360; }, [](LensCameraSpec&) {}}, settings.rig.kind);
  settings.spp = static_cast<int>(state.range(0));
  settings.shading = state.range(1) ? Shading::Lit : Shading::Unlit;
  // Sample tables are built once per camera and spp, then serve every frame: build them first,
  // so that frames/s is the rate of frames.
  const CameraPlacement placement(scene.startPose, velocity);
  benchmark::DoNotOptimize(renderer.render(placement, settings));
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(placement, settings));
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(std::string(shadingName(settings.shading)) + ", spp " + std::to_string(settings.spp));
}

void BM_ExactRobocup2006(benchmark::State& state) {
  static const FastRenderer renderer(arena());  // its own: sample tables are cached per camera
  renderFrames(state, renderer, arena().rig);
}

void BM_PhysicalRigRobocup2006(benchmark::State& state) {
  static const FastRenderer renderer(arena());
  RigSpec rig = arena().rig;
  rig.mirrorRig().mount.offsetMm = {2.0, -1.0, 0.5};
  rig.mirrorRig().mount.rotationDeg = {1.0, -0.5, 0.3};
  rig.mirrorRig().mount.distortion = {-0.08, 0.01, 0.0005, -0.0004, 0.0};
  renderFrames(state, renderer, rig);
}

// docs/motion.md: a frame at 1 m/s and 90°/s, its samples stratified over a 1/30 s exposure
// (global) or read line by line (rolling, 30 µs lines), against the still frame above (target:
// ≤ 1.25× its time at 16 spp).
void BM_MotionBlurRobocup2006(benchmark::State& state) {
  static const FastRenderer renderer(arena());
  RigSpec rig = arena().rig;
  rig.shutter = {1.0 / 30.0, std::nullopt, 0};
  renderFrames(state, renderer, rig, {1.0, 0.0, 90.0});
}

void BM_RollingShutterRobocup2006(benchmark::State& state) {
  static const FastRenderer renderer(arena());
  RigSpec rig = arena().rig;
  rig.shutter = {1.0 / 30.0, RollingShutter{30.0, Readout::TopToBottom}, 0};
  renderFrames(state, renderer, rig, {1.0, 0.0, 90.0});
}

// docs/lens-cameras.md: lens cameras at the mirror's viewpoint, about as many pixels as the
// mirror's 360×360 — a 190° Kannala–Brandt fisheye (360×360) and a full panorama (512×256) —
// their rays inverted per sample like the physical rig's, against the closed form above.
void BM_FisheyeRobocup2006(benchmark::State& state) {
  static const FastRenderer renderer(arena());
  const KannalaBrandt lens{105.0, 105.0, 179.5, 179.5, {0.02, -0.005, 0.001, -0.0002}, radians(95.0)};
  renderFrames(state, renderer, test::lensRig(lens, 360, 360, {0.0, 0.0, 0.0}, arena().rig.height));
}

void BM_PanoramaRobocup2006(benchmark::State& state) {
  static const FastRenderer renderer(arena());
  renderFrames(state, renderer, test::lensRig(Equirectangular{512, 256}, 512, 256, {0.0, 0.0, 0.0}, arena().rig.height));
}

// docs/path-tracing.md: path shading of the textured hall (four disc lamps, 2 bounces) at the
// texture-realism experiment's first thesis-loop pose, unfiltered and denoised (the frames
// datasets use).
const Scene& texturedHall() {
  static const Scene scene = loadScene(writeLabHall(
      OMNICAM_SOURCE_DIR "/scenes/robocup2006.json", (std::filesystem::temp_directory_path() / "omnicam_bench_hall").string()));
  return scene;
}

void BM_PathTexturedHall(benchmark::State& state) {
  static const FastRenderer renderer(texturedHall());
  RenderSettings settings;
  settings.rig = texturedHall().rig.resized(360);
  settings.spp = static_cast<int>(state.range(0));
  settings.shading = Shading::Path;
  settings.denoise = state.range(1) != 0;
  const RobotPose pose{2.7, -1.8, 180.0};
  benchmark::DoNotOptimize(renderer.render(pose, settings));
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(pose, settings));
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(std::string("path, spp ") + std::to_string(settings.spp) + (settings.denoise ? ", denoised" : ""));
}
BENCHMARK(BM_PathTexturedHall)
    ->ArgNames({"spp", "denoise"})
    ->Args({1, 0})
    ->Args({4, 1})
    ->Args({16, 0})
    ->Args({16, 1})
    ->Args({kPathDatasetSpp, 1})  // a path-traced dataset's frame: the recording stage's yardstick
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Embree's own ray rate on one core in the textured hall, the yardstick of a path sample's cost
// (docs/performance.md, "Light at speed"): incoherent rays as bounces cast them, from points
// spread through the hall in uniform directions. kind 0: shadow rays (any hit) 2 m long; kind 1:
// closest hits with the hit's details (RayScene::intersect, what a scattered ray costs the path
// tracer: uv, normal, the double-precision re-intersection of #45).
void BM_EmbreeRaysInTexturedHall(benchmark::State& state) {
  static const RayScene rays(texturedHall());
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const HallOptions hall;
  std::vector<Vec3> origins, directions;
  for (int k = 0; k < 1 << 16; ++k) {
    origins.emplace_back((2.0 * unit(random) - 1.0) * (hall.halfLength - 0.2), (2.0 * unit(random) - 1.0) * (hall.halfWidth - 0.2),
                         0.05 + unit(random) * (hall.height - 0.1));
    const double z = 2.0 * unit(random) - 1.0, phi = 2.0 * kPi * unit(random), r = std::sqrt(1.0 - z * z);
    directions.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  const bool closest = state.range(0) != 0;
  size_t k = 0;
  for (auto _ : state) {
    if (closest) benchmark::DoNotOptimize(rays.intersect(origins[k], directions[k]));
    else benchmark::DoNotOptimize(rays.occluded(origins[k], directions[k], 0.0, 2.0));
    k = (k + 1) & (origins.size() - 1);
  }
  state.counters["Mrays/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * 1e-6, benchmark::Counter::kIsRate);
  state.SetLabel(closest ? "closest hit with details, one core" : "shadow rays (any hit, 2 m), one core");
}
BENCHMARK(BM_EmbreeRaysInTexturedHall)->ArgName("closest")->DenseRange(0, 1);

// The recording camera with every stage on (blur, lateral CA, vignetting, exposure, white balance,
// Bayer mosaic and demosaicing by state.range(0): 0 bilinear, 1 VNG, 2 edge-aware; shot, read and
// row noise; filmic tone; JPEG 90) on a 360-px path-traced frame: frames/s beside
// BM_PathTexturedHall's, which it must not halve.
void BM_RecordingCameraEveryStage(benchmark::State& state) {
  RenderSettings settings;
  settings.rig = texturedHall().rig.resized(360);
  settings.spp = 4;
  settings.shading = Shading::Path;
  settings.denoise = true;
  static const ImageRGBA frame = FastRenderer(texturedHall()).render(RobotPose{2.7, -1.8, 180.0}, settings);
  RecordingCamera camera;
  camera.blurRadiusPx = 1.0;
  camera.chromaticAberration = 0.003;
  camera.vignetting = 0.3;
  camera.exposureEv = 0.3;
  camera.whiteBalance = {1.1, 1.0, 0.9};
  camera.bayer = BayerPattern::RGGB;
  camera.demosaic = static_cast<DemosaicMethod>(state.range(0));
  camera.fullWellElectrons = 3000;
  camera.readNoise = 0.005;
  camera.rowNoise = 0.002;
  camera.tone = ToneCurve::Filmic;
  camera.jpegQuality = 90;
  uint64_t index = 0;
  for (auto _ : state) benchmark::DoNotOptimize(recordFrame(camera, frame, index++));
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  static const char* const methods[] = {"bilinear", "VNG", "edge-aware"};
  state.SetLabel(std::string("every stage, ") + methods[state.range(0)] + " demosaicing");
}
BENCHMARK(BM_RecordingCameraEveryStage)->ArgName("demosaic")->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime();

// 1 and 16 spp, unlit and lit, for either rig.
void frameArgs(benchmark::internal::Benchmark* b) {
  b->ArgNames({"spp", "lit"})->Args({1, 0})->Args({1, 1})->Args({16, 0})->Args({16, 1});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}
BENCHMARK(BM_ExactRobocup2006)->Apply(frameArgs);
BENCHMARK(BM_PhysicalRigRobocup2006)->Apply(frameArgs);
BENCHMARK(BM_MotionBlurRobocup2006)->Apply(frameArgs);
BENCHMARK(BM_RollingShutterRobocup2006)->Apply(frameArgs);
BENCHMARK(BM_FisheyeRobocup2006)->Apply(frameArgs);
BENCHMARK(BM_PanoramaRobocup2006)->Apply(frameArgs);

}  // namespace
}  // namespace omnicam

int main(int argc, char** argv) {
  omnicam::keepFreedMemoryInTheHeap();  // as the CLI does: frames' buffers are not faulted in anew
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;  // as the other benchmarks: a typo starts no run
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
