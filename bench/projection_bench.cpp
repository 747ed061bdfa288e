// make bench (omnicam_bench): the cost of world → pixel per mirror shape, for points 1 km away in
// every direction (most of them not imaged): the work behind `omnicam project`, `rings`, views
// and landmark annotations. docs/performance.md quotes the µs per point of each shape.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <vector>

#include "make_camera.h"
#include "test_rigs.h"

namespace omnicam {
namespace {

const std::vector<Vec3>& farPoints() {
  static const std::vector<Vec3> points = [] {
    std::mt19937_64 random(7);
    std::normal_distribution<double> normal;
    std::vector<Vec3> out;
    for (int k = 0; k < 512; ++k) out.push_back(1000.0 * Vec3(normal(random), normal(random), normal(random)).normalized());
    return out;
  }();
  return points;
}

RigSpec aligned(MirrorShape shape, double cameraDistance) {
  RigSpec rig = test::shaped(shape, cameraDistance);
  rig.mirrorRig().mount = CameraMount{};
  return rig;
}

void projectFar(benchmark::State& state, const RigSpec& rig, bool traced) {
  const auto camera = makeCamera(rig, traced);
  int64_t points = 0, seen = 0;
  for (auto _ : state)
    for (const Vec3& p : farPoints()) {
      const auto raster = camera->project(p);
      seen += raster.has_value();
      ++points;
      benchmark::DoNotOptimize(raster);
    }
  // Seconds per point (the time of one iteration is that of 512 points).
  state.counters["s/point"] = benchmark::Counter(static_cast<double>(points), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["seen"] = static_cast<double>(seen) / static_cast<double>(std::max<int64_t>(points, 1));
}

void BM_ProjectHyperboloidIdeal(benchmark::State& s) { projectFar(s, RigSpec{}, false); }
void BM_ProjectHyperboloidTraced(benchmark::State& s) { projectFar(s, RigSpec{}, true); }
void BM_ProjectHyperboloidMisaligned(benchmark::State& s) { projectFar(s, test::misaligned(2.0, 1.0), false); }
void BM_ProjectParaboloid(benchmark::State& s) { projectFar(s, aligned(MirrorShape::Paraboloid, 0.05), false); }
void BM_ProjectParaboloidOrthographic(benchmark::State& s) { projectFar(s, aligned(MirrorShape::Paraboloid, 0.0), false); }
void BM_ProjectParaboloidOrthographicMoved(benchmark::State& s) { projectFar(s, test::shaped(MirrorShape::Paraboloid, 0.0), false); }
void BM_ProjectSphere(benchmark::State& s) { projectFar(s, aligned(MirrorShape::Sphere, 0.05), false); }
void BM_ProjectCone(benchmark::State& s) { projectFar(s, aligned(MirrorShape::Cone, 0.05), false); }
void BM_ProjectSphereMisaligned(benchmark::State& s) { projectFar(s, test::shaped(MirrorShape::Sphere, 0.05), false); }
void BM_ProjectConeMisaligned(benchmark::State& s) { projectFar(s, test::shaped(MirrorShape::Cone, 0.05), false); }

BENCHMARK(BM_ProjectHyperboloidIdeal)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectHyperboloidTraced)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectHyperboloidMisaligned)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectParaboloid)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectParaboloidOrthographic)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectParaboloidOrthographicMoved)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectSphere)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectCone)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectSphereMisaligned)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProjectConeMisaligned)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace omnicam
