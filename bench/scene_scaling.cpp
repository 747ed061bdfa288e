// make bench: how the fast renderer's cost grows with scene size (issue #12). robocup2006 plus
// 10³…10⁶ extra triangles (tessellated debris spheres scattered around the field, seeded), exact
// mode, 360×360, 1 spp, unlit, at the thesis start pose, on every core TBB finds. Prints frames/s
// against triangle count and the ratio to robocup2006 alone, all measured in one run (Embree's
// BVH makes a ray's cost grow like log(triangles); the goal is ≥ 50 % at 10⁶).
// Usage: scene_scaling [--csv PATH] [--image PNG]   (--image: the 10⁶-triangle frame)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <unistd.h>

#include <filesystem>

#include "bench_flags.h"
#include "fast_renderer.h"
#include "hall_arena.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

using Clock = std::chrono::steady_clock;

// A UV sphere of about `triangles` triangles.
Mesh sphereMesh(const Vec3& centre, double radius, int triangles) {
  const int slices = std::max(4, static_cast<int>(std::sqrt(triangles / 2.0)));
  const int stacks = std::max(3, triangles / (2 * slices) + 1);
  Mesh mesh;
  for (int j = 0; j <= stacks; ++j)
    for (int i = 0; i <= slices; ++i) {
      const double theta = M_PI * j / stacks, phi = 2 * M_PI * i / slices;
      mesh.vertices.push_back(centre + radius * Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                                     std::cos(theta)));
    }
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const int a = j * (slices + 1) + i, b = a + slices + 1;
      if (j > 0) mesh.triangles.emplace_back(a, b, a + 1);
      if (j + 1 < stacks) mesh.triangles.emplace_back(a + 1, b, b + 1);
    }
  return mesh;
}

// robocup2006 with `triangles` more, as debris spheres of 2000 triangles on the carpet margin.
Scene withDebris(const Scene& arena, int triangles) {
  Scene scene = arena;
  std::mt19937_64 random(12);
  auto unit = [&] { return static_cast<double>(random() >> 11) * 0x1.0p-53; };
  const int perSphere = std::min(triangles, 2000);
  int added = 0;
  while (added < triangles) {
    const double x = -2.95 + 5.9 * unit(), side = unit() < 0.5 ? -1.0 : 1.0;
    const double radius = 0.03 + 0.07 * unit();
    SceneObject object;
    object.name = "debris_" + std::to_string(scene.objects.size());
    object.material = 0;
    Mesh mesh = sphereMesh(Vec3(x, side * (1.85 + 0.2 * unit()), radius), radius, std::min(perSphere, triangles - added));
    added += static_cast<int>(mesh.triangles.size());
    object.shape = std::move(mesh);
    scene.objects.push_back(std::move(object));
  }
  return scene;
}

size_t triangleCount(const Scene& scene) {
  size_t n = 0;
  for (const SceneObject& o : scene.objects)
    if (const Mesh* mesh = std::get_if<Mesh>(&o.shape)) n += mesh->triangles.size();
  return n;
}

// Frames/s over at least a second (after one warm-up frame).
double framesPerSecond(const FastRenderer& renderer, const Scene& scene) {
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 360;
  renderer.render(scene.startPose, settings);
  int frames = 0;
  const auto start = Clock::now();
  double seconds = 0.0;
  while (seconds < 1.0 || frames < 5) {
    renderer.render(scene.startPose, settings);
    ++frames;
    seconds = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return frames / seconds;
}

}  // namespace
}  // namespace omnicam

int main(int argc, char** argv) {
  using namespace omnicam;
  const bench::BenchFlags flags(argc, argv, {"--csv", "--image"}, "scene_scaling [--csv PATH] [--image PNG]");
  const std::string csvPath = flags.text("--csv", ""), imagePath = flags.text("--image", "");
  const char* csv = csvPath.empty() ? nullptr : csvPath.c_str();
  const char* image = imagePath.empty() ? nullptr : imagePath.c_str();
  const Scene field = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  const std::filesystem::path hallDir = std::filesystem::temp_directory_path() / ("omnicam_scaling_" + std::to_string(::getpid()));
  HallOptions hallOptions;
  hallOptions.fieldScene = OMNICAM_SOURCE_DIR "/scenes/robocup2006.json";
  writeHallArena(hallOptions, (hallDir / "hall.json").string());
  const Scene hall = loadScene((hallDir / "hall.json").string());
  std::filesystem::remove_all(hallDir);
  std::ofstream out;
  if (csv) out.open(csv), out << "arena,triangles,build_seconds,frames_per_second,fraction_of_arena_alone\n";
  std::printf("scene size vs speed: exact mode, 360x360, 1 spp, unlit, thesis start pose, one run\n");
  std::printf("%-12s %12s %10s %10s %10s\n", "arena", "+triangles", "build s", "frames/s", "vs alone");
  for (const auto& [name, arena] : {std::pair<const char*, const Scene*>{"robocup2006", &field}, {"hall", &hall}}) {
    const double baseline = framesPerSecond(FastRenderer(*arena), *arena);
    std::printf("%-12s %12d %10s %10.1f %9.1f%%\n", name, 0, "-", baseline, 100.0);
    if (csv) out << name << ",0,0," << baseline << ",1\n";
    for (int triangles : {1000, 10000, 100000, 1000000}) {
      const Scene scene = withDebris(*arena, triangles);
      const auto start = Clock::now();
      const FastRenderer renderer(scene);
      const double build = std::chrono::duration<double>(Clock::now() - start).count();
      const double fps = framesPerSecond(renderer, scene);
      std::printf("%-12s %12zu %10.3f %10.1f %9.1f%%\n", name, triangleCount(scene), build, fps, 100.0 * fps / baseline);
      if (csv) out << name << ',' << triangleCount(scene) << ',' << build << ',' << fps << ',' << fps / baseline << '\n';
      if (image && triangles == 1000000 && arena == &hall) {
        RenderSettings settings;
        settings.rig = scene.rig;
        settings.rig.mirrorRig().imageSize = 360;
        settings.spp = 4;
        writeImageAtomic(image, renderer.render(scene.startPose, settings));
      }
    }
  }
  return 0;
}
