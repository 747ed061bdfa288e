// The pixels and annotations omnicam makes today, as SHA-256 of their decoded values: the proof a
// reshaping of the house (issue #34) must give, "not one pixel changes". A fixed set of renders —
// every engine and mode; the ideal, physical, sphere, paraboloid, cone and tilted rigs; moving
// frames under a global and a rolling shutter; both dataset layouts with every output and COCO —
// is made through the CLI, decoded by omnicam's readers, and hashed value by value (so an
// encoder's bytes may change, a value may not). The hashes are in tests/golden_hashes.txt.
//
// A change that is meant to change pixels records them again, and its note says why:
//   OMNICAM_RECORD_GOLDEN=1 build/bin/golden_hashes_test   (rewrites tests/golden_hashes.txt)
#include <gtest/gtest.h>

#include <algorithm>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cpu_independent_math.h"
#include "dataset_reader.h"
#include "image.h"
#include "sha256.h"
#include "shell_command.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* kGoldenFile = OMNICAM_SOURCE_DIR "/tests/golden_hashes.txt";

template <class T>
std::string hashValues(const std::vector<T>& values) {
  return sha256OfBytes(std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)));
}

// An image's decoded pixels (linear RGBA floats), with its size.
std::string hashImage(const ImageRGBA& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height) + ":" + hashValues(image.pixels);
}

class GoldenHashes : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = fs::temp_directory_path() / ("omnicam_golden_" + std::to_string(::getpid()));
    fs::remove_all(work_);
    fs::create_directories(work_);
  }
  void TearDown() override { fs::remove_all(work_); }

  // robocup2006 with `rig` merged into its rig block, as a scene file of the work folder.
  std::string scene(const std::string& name, const json& rig) const {
    std::ifstream in(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
    json s = json::parse(in);
    s["rig"].merge_patch(rig);
    if (rig.contains("mirror")) s["rig"]["mirror"] = rig["mirror"];  // another shape: none of the hyperboloid's fields
    const fs::path file = work_ / (name + ".json");
    std::ofstream(file) << s.dump(1);
    return file.string();
  }
  // robocup2006 seen by a lens camera (docs/lens-cameras.md) instead of its mirror.
  std::string lensScene(const std::string& name, const json& lens, const json& shutter = json()) const {
    std::ifstream in(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
    json s = json::parse(in);
    s["rig"] = {{"height", 0.4}, {"lens", lens}};
    if (!shutter.is_null()) s["rig"]["shutter"] = shutter;
    const fs::path file = work_ / (name + ".json");
    std::ofstream(file) << s.dump(1);
    return file.string();
  }
  std::string path(const std::string& name) const { return (work_ / name).string(); }
  void omnicam(const std::string& args) const {
    const auto [code, out] = testing::runShell(environment_ + OMNICAM_BINARY + " " + args + " 2>&1");
    if (code != 0) throw std::runtime_error("omnicam " + args + " exited " + std::to_string(code) + ":\n" + out);
  }
  // One render through the CLI, its pixels hashed.
  void render(const std::string& name, const std::string& scenePath, const std::string& args) {
    const std::string out = path(name + ".exr");
    omnicam("render " + scenePath + " " + args + " -o " + out);
    hashes_[name] = hashImage(readImage(out));
  }
  // Every frame's every output of a dataset, decoded by the dataset reader, and its gathered
  // annotation files.
  void dataset(const std::string& name, const json& spec) {
    const std::string specPath = path(name + ".spec.json");
    std::ofstream(specPath) << spec.dump(1);
    omnicam("dataset " + specPath + " -o " + path(name));
    const DatasetReader reader(path(name));
    for (const std::string& camera : reader.cameras())
      for (int index : reader.frames()) {
        std::vector<OutputKind> kinds;
        for (const auto& [kindName, file] : reader.frame(index).cameras.at(camera).files)
          if (const auto kind = outputNamed(kindName); kind && *kind != OutputKind::Multilayer) kinds.push_back(*kind);
        if (reader.frame(index).cameras.at(camera).file(OutputKind::Multilayer))
          for (OutputKind kind : {OutputKind::Rgb, OutputKind::Depth, OutputKind::Normal, OutputKind::Instance,
                                  OutputKind::Semantic, OutputKind::Landmarks, OutputKind::Coco})
            kinds.push_back(kind);
        for (const auto& [kind, decoded] : reader.readOutputs(index, camera, kinds, true)) {
          const std::string key = name + "/" + camera + "/" + std::to_string(index) + "/" + outputName(kind);
          if (decoded.image) hashes_[key] = hashImage(*decoded.image);
          else if (decoded.data) hashes_[key] = hashValues(decoded.data->values);
          else if (!decoded.ids.empty()) hashes_[key] = hashValues(decoded.ids);
          else hashes_[key] = sha256OfBytes(decoded.json.dump());
        }
        for (const char* gathered : {"coco.json", "landmarks.json"}) {
          if (!fs::exists(work_ / name / camera / gathered)) continue;
          json annotations = json::parse(testing::readFile(work_ / name / camera / gathered));
          // COCO's info names the spec file, which lies in this run's own temporary folder.
          if (annotations.contains("info")) annotations["info"].erase("description");
          hashes_[name + "/" + camera + "/" + gathered] = sha256OfBytes(annotations.dump());
        }
      }
  }

  void renderOwnSet();
  std::map<std::string, std::string> golden() const;

  fs::path work_;
  std::string environment_;  // variables set for each omnicam run, as "NAME=value " words
  std::map<std::string, std::string> hashes_;
};

// Every render of the set that omnicam's own code makes (the fast engine: renders and datasets).
void GoldenHashes::renderOwnSet() {
  const std::string robocup = OMNICAM_SOURCE_DIR "/scenes/robocup2006.json";
  const std::string small = "--size 48 --spp 4 --pose=1.2,-0.4,30";
  // The fast engine, every mode, both shadings.
  render("fast_exact_unlit", robocup, small);
  render("fast_exact_lit", robocup, small + " --shading lit");
  render("fast_cubemap", robocup, small + " --mode cubemap --face-size 64");
  render("fast_cubemap5", robocup, small + " --mode cubemap --faces 5 --face-size 64");
  render("fast_thesis_mesh", robocup, small + " --mode thesis-mesh --polygons 256 --face-size 64");
  // Rigs: a moved and turned camera with a lens, the other shapes, a tilted mount.
  const std::string physical = scene("physical", {{"camera", {{"offset_mm", {2, -1, 0.5}}, {"rotation_deg", {1, -0.5, 0.3}},
                                                              {"distortion", {{"k1", -0.08}, {"p1", 0.0005}}}}}});
  render("fast_physical", physical, small + " --shading lit");
  render("fast_sphere", scene("sphere", {{"mirror", {{"shape", "sphere"}, {"radius", 0.03}, {"camera_distance_m", 0.12}}}}), small);
  render("fast_paraboloid", scene("paraboloid", {{"mirror", {{"shape", "paraboloid"}, {"h", 0.02}}}}), small);
  render("fast_cone", scene("cone", {{"mirror", {{"shape", "cone"}, {"rim_radius", 0.03}, {"camera_distance_m", 0.05}}}}), small);
  render("fast_tilted", scene("tilted", {{"tilt_deg", {2.5, -1.5}}}), small);
  // Time: a global and a rolling shutter while the robot drives and turns.
  const std::string global = scene("global", {{"shutter", {{"exposure_s", 0.02}}}});
  const std::string rolling = scene("rolling", {{"shutter", {{"exposure_s", 0.004}, {"rolling", {{"line_time_us", 300}}}}}});
  render("fast_moving_global", global, small + " --velocity 1,0.2,90");
  render("fast_moving_rolling", rolling, small + " --velocity 1,0.2,90");
  // Lens cameras: a Kannala-Brandt fisheye, a panorama, a distorted pinhole, rolling.
  const json kb = {{"model", "kannala_brandt"}, {"width", 64}, {"height", 48}, {"fx", 19}, {"fy", 19},
                   {"k", {0.02, -0.005, 0.001, 0}}, {"max_theta_deg", 100}, {"rotation_deg", {0, 15, 0}}};
  render("fast_lens_kannala_brandt", lensScene("kb", kb), "--spp 4 --pose=1.2,-0.4,30 --shading lit");
  const json pano = {{"model", "equirectangular"}, {"width", 64}, {"height", 32}};
  render("fast_lens_panorama", lensScene("pano", pano), "--spp 4 --pose=1.2,-0.4,30");
  const json pinhole = {{"model", "pinhole"}, {"width", 48}, {"height", 36}, {"fx", 40}, {"fy", 40},
                        {"distortion", {{"k1", -0.2}, {"p2", 0.001}}}, {"rotation_deg", {0, 20, -10}}};
  render("fast_lens_pinhole_rolling", lensScene("pinhole", pinhole, {{"exposure_s", 0.004}, {"rolling", {{"line_time_us", 300}}}}), "--spp 4 --pose=1.2,-0.4,30 --velocity 1,0.2,90");
  // Path tracing: its sampling calls sin, cos and sqrt for every bounce.
  render("fast_path", robocup, "--size 32 --spp 4 --pose=1.2,-0.4,30 --shading path");
  // Denoised: the filter of all the light, and the coverage refinement of the field lines' pixels.
  render("fast_path_denoised", robocup, "--size 48 --spp 4 --pose=1.2,-0.4,30 --shading path --denoise");
  // Datasets: both layouts, every output and COCO, two cameras, a moving robot.
  const json outputs = {{"depth", true}, {"instance", true}, {"semantic", true}, {"normal", true}, {"landmarks", true}, {"coco", true}};
  json spec = {{"format", "omnicam-dataset/1"}, {"scene", robocup}, {"spp", 4}, {"shading", "lit"}, {"size", 48},
               {"poses", {{"path", "thesis-loop"}, {"frames", 2}}}, {"motion", {{"velocity", {0.5, 0, 45}}}},
               {"cameras", {{{"name", "front"}, {"mount", {{"x", 0.1}, {"y", 0}, {"yaw_deg", 0}}}},
                            {{"name", "rear"}, {"mount", {{"x", -0.1}, {"y", 0}, {"yaw_deg", 180}}},
                             {"rig", {{"shutter", {{"exposure_s", 0.004}, {"rolling", {{"line_time_us", 300}}}}}}}}}},
               {"outputs", outputs}};
  spec["outputs"]["rgb"] = "png";
  dataset("dataset_files", spec);
  spec["layout"] = "multilayer";
  spec["outputs"].erase("rgb");
  dataset("dataset_multilayer", spec);
}

// The golden file's hashes, by name.
std::map<std::string, std::string> GoldenHashes::golden() const {
  std::map<std::string, std::string> golden;
  std::ifstream in(kGoldenFile);
  if (!in) throw std::runtime_error(std::string(kGoldenFile) + " is missing");
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name, hash;
    fields >> name >> hash;
    golden[name] = hash;
  }
  return golden;
}

TEST_F(GoldenHashes, ThePixelsAndAnnotationsOfAFixedSetOfRendersAreUnchanged) {
  renderOwnSet();
  // The ground truths.
  const std::string robocup = OMNICAM_SOURCE_DIR "/scenes/robocup2006.json";
  const json equidistant = {{"model", "fisheye_equidistant"}, {"width", 32}, {"height", 32}, {"f_px", 9}, {"fov_deg", 190}};
  render("povray_lens_fisheye", lensScene("equidistant", equidistant), "--engine povray --spp 4 --pose=1.2,-0.4,30");
  render("povray_ideal", robocup, "--engine povray --size 32 --spp 4 --pose=1.2,-0.4,30");
  const std::string turned = scene("turned", {{"camera", {{"offset_mm", {2, -1, 0.5}}, {"rotation_deg", {1, -0.5, 0.3}}}}});
  render("povray_physical", turned, "--engine povray --size 32 --spp 4 --pose=1.2,-0.4,30");
  render("blender_ideal", robocup, "--engine blender --size 32 --spp 4 --pose=1.2,-0.4,30");

  if (std::getenv("OMNICAM_RECORD_GOLDEN")) {
    std::ofstream out(kGoldenFile);
    out << "# tests/golden_hashes_test.cpp: SHA-256 of decoded pixels and annotations (issue #34). Recorded with\n"
        << "# OMNICAM_RECORD_GOLDEN=1; a change that records them again says why in its note.\n";
    for (const auto& [name, hash] : hashes_) out << name << ' ' << hash << '\n';
    std::printf("recorded %zu hashes in %s\n", hashes_.size(), kGoldenFile);
    return;
  }
  const std::map<std::string, std::string> golden = this->golden();
  EXPECT_EQ(golden.size(), hashes_.size()) << "the set of renders changed";
  for (const auto& [name, hash] : hashes_) {
    const auto it = golden.find(name);
    if (it == golden.end()) ADD_FAILURE() << name << ": not in " << kGoldenFile;
    else EXPECT_EQ(hash, it->second) << name << ": its decoded values changed";
  }
}

// Issue #45: a frame is the same on every x86-64 machine. What a CPU's features steer: Embree's
// code path (avx2, or Embree's own choice on a CPU without it; OMNICAM_EMBREE_ISA forces each
// one here) and the build of glibc's libm (omnicam masks FMA, so an FMA CPU takes the plain
// build like a CPU without FMA; masking AVX too gives the SSE2 build that CPUs without AVX
// take). Under each path this CPU can take, omnicam's own renders must give the golden hashes;
// at least two of Embree's paths must be among them (SSE2 and one more, on any x86-64 since AVX).
TEST_F(GoldenHashes, EveryCodePathOfTheCpuMakesTheSamePixels) {
  __builtin_cpu_init();
  const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
                      __builtin_cpu_supports("avx512cd");
  const bool fmaBuildReachable = __builtin_cpu_supports("fma") && __builtin_cpu_supports("avx2");
  const auto probe = [](const std::string& tunables) {
    const auto [code, out] = testing::runShell("GLIBC_TUNABLES=" + tunables + " " LIBM_PROBE);
    if (code != 0) throw std::runtime_error("libm_probe exited " + std::to_string(code));
    return out;
  };
  // Where the FMA build exists, it really differs and the tunable really avoids it.
  const std::string plainBuild = probe(kPlainMathTunable);
  if (fmaBuildReachable) {
    ASSERT_NE(probe("glibc.cpu.hwcaps="), plainBuild)
        << kPlainMathTunable << " does not change libm's results: the tunable no longer selects its build";
  }
  ASSERT_EQ(plainBuild, probe("glibc.cpu.hwcaps=-AVX,-AVX2,-FMA,-FMA4")) << "libm's AVX and SSE2 builds disagree";

  // Embree's paths as Debian's Embree 3.13 is built: SSE2, AVX, AVX2, AVX-512 ("isa=sse4.2" takes
  // the SSE2 code there).
  struct Path {
    std::string name, environment;
    bool cpuHasIt;
  };
  // With the tunable omnicam would add already set, it does not start itself again (quicker).
  const std::string plainMath = std::string("GLIBC_TUNABLES=") + kPlainMathTunable;
  const std::vector<Path> paths = {
      {"Embree sse2", plainMath + " OMNICAM_EMBREE_ISA=sse2", true},
      {"Embree avx", plainMath + " OMNICAM_EMBREE_ISA=avx", __builtin_cpu_supports("avx") != 0},
      {"Embree avx2", plainMath + " OMNICAM_EMBREE_ISA=avx2", __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")},
      {"Embree avx512", plainMath + " OMNICAM_EMBREE_ISA=avx512", avx512},
      {"libm's SSE2 build (a CPU without AVX)", "GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX,-AVX2,-FMA,-FMA4", true},
  };
  const std::map<std::string, std::string> golden = this->golden();
  const auto embreePathsHere = std::count_if(paths.begin(), paths.end(), [](const Path& p) {
    return p.cpuHasIt && p.name.rfind("Embree", 0) == 0;
  });
  ASSERT_GE(embreePathsHere, 2) << "this CPU offers Embree only its SSE2 path: nothing to compare it with";
  for (const Path& path : paths) {
    SCOPED_TRACE(path.name);
    if (!path.cpuHasIt) {  // a path no machine like this one takes
      std::printf("not on this CPU: %s\n", path.name.c_str());
      continue;
    }
    std::printf("checking: %s\n", path.name.c_str());
    environment_ = path.environment + " ";
    hashes_.clear();
    renderOwnSet();
    for (const auto& [name, hash] : hashes_) {
      const auto it = golden.find(name);
      if (it == golden.end()) ADD_FAILURE() << name << ": not in " << kGoldenFile;
      else EXPECT_EQ(hash, it->second) << name << ": its decoded values differ on the path " << path.name;
    }
  }
}

}  // namespace
}  // namespace omnicam
