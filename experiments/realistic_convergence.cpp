#include "realistic_convergence.h"

#include "plot_script.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <list>
#include <sstream>

#include "atomic_file.h"
#include "errors.h"
#include "experiment_folder.h"
#include "external_process.h"
#include "hall_arena.h"
#include "indirect_filter.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "number_format.h"

namespace omnicam {

namespace fs = std::filesystem;

ConvergenceOptions ConvergenceOptions::quick() {
  ConvergenceOptions o;
  o.size = 32;
  o.ladder = {4, 16};
  o.referenceSpp = 64;
  o.diagnosisSpp = 4;
  o.experimentSize = 64;
  o.experimentReferenceSpp = 64;
  o.poseIndices = {0};
  o.everyPath = false;
  o.quickRun = true;
  return o;
}

namespace {

// The clamp measured (Cycles counts everything seen in the mirror as indirect light).
constexpr double kClampIndirect = 1.0;

// Seeds never shared between a rung, its reference and a seed pair.
constexpr int kReferenceSeed = 90000, kPairSeeds[2] = {1, 2};
int rungSeed(size_t rung) { return 1000 * static_cast<int>(rung + 1); }

struct Study {
  const ConvergenceOptions& options;
  const Scene& hall;
  std::vector<RobotPose> poses;
  const ExperimentProgress& progress;
  int done = 0, total = 0;

  std::vector<ImageRGBA> render(const RealisticRendering& setup, int size, int spp, int seed, const std::string& stage) {
    std::vector<ImageRGBA> images = renderRealistic(hall, poses, setup, size, spp, seed, options.blenderTimeoutSeconds);
    progress(stage, ++done, total);
    return images;
  }
  // Noise of a seed pair, averaged over the poses.
  PathVariant pair(const std::string& name, const std::string& description, const RealisticRendering& setup,
                   const Scene* scene = nullptr) {
    const Scene& which = scene ? *scene : hall;
    PathVariant v{name, description};
    const std::vector<ImageRGBA> a = renderRealistic(which, poses, setup, options.size, options.diagnosisSpp, kPairSeeds[0],
                                                     options.blenderTimeoutSeconds);
    progress("paths", ++done, total);
    const std::vector<ImageRGBA> b = renderRealistic(which, poses, setup, options.size, options.diagnosisSpp, kPairSeeds[1],
                                                     options.blenderTimeoutSeconds);
    progress("paths", ++done, total);
    for (size_t p = 0; p < poses.size(); ++p) {
      const RenderNoise noise = measureRenderNoise(a[p], b[p]);
      v.pairPsnrDb += noise.psnrDb / static_cast<double>(poses.size());
      v.outlierShare += noise.outlierShare / static_cast<double>(poses.size());
    }
    v.estimatedPsnrDb = psnrAgainstConvergedFromPair(v.pairPsnrDb);
    return v;
  }
};

double meanLuminance(const ImageRGBA& image, const ImageRGBA& mask) {
  double sum = 0.0;
  long n = 0;
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      if (mask.at(i, j)[3] < 0.999f) continue;
      const float* p = image.at(i, j);
      sum += luminance<double>(p);
      ++n;
    }
  return n ? sum / static_cast<double>(n) : 0.0;
}

RealisticRendering withTracing(RealisticRendering setup, int diffuse, int glossy) {
  setup.tracing.diffuseBounces = diffuse;
  setup.tracing.glossyBounces = glossy;
  return setup;
}

bool convergesLike(const RealisticRendering& a, const RealisticRendering& b) {
  return a.lampDiameter == b.lampDiameter && a.tracing == b.tracing;
}

// Converged references, rendered once per setup that differs in what it converges to.
class ReferenceCache {
 public:
  const std::vector<ImageRGBA>& get(Study& study, const RealisticRendering& setup, int size, int spp) {
    for (const auto& [known, images] : cached_)
      if (convergesLike(known, setup)) return images;
    cached_.emplace_back(setup, study.render(setup, size, spp, kReferenceSeed, setup.name));
    return cached_.back().second;
  }

 private:
  std::list<std::pair<RealisticRendering, std::vector<ImageRGBA>>> cached_;  // a list: references stay valid
};

std::vector<PathVariant> diagnosePaths(Study& study) {
  const RealisticRendering before = realisticRenderingBefore();
  std::vector<PathVariant> paths;
  const RealisticRendering physical = realisticRenderingPhysical();
  const char* const physicalWords = "lamps of real size, mirror seen by camera rays only, unfiltered";
  paths.push_back(study.pair("before", "point lamps, everything traced (until issue #20)", before));
  if (!study.options.everyPath) {
    paths.push_back(study.pair("physical", physicalWords, physical));
    return paths;
  }
  paths.push_back(study.pair("before_direct", "point lamps, direct light only (no bounce but the mirror's)",
                             withTracing(before, 0, 1)));
  paths.push_back(study.pair("before_glossy", "point lamps, direct light and glossy bounces, no diffuse bounce",
                             withTracing(before, 0, before.tracing.glossyBounces)));
  paths.push_back(study.pair("before_one_diffuse", "point lamps, at most 1 diffuse bounce",
                             withTracing(before, 1, before.tracing.glossyBounces)));
  RealisticRendering hidden = before;
  hidden.tracing.mirrorSeenByIndirectRays = false;
  paths.push_back(study.pair("before_mirror_hidden", "point lamps, the mirror hidden from bounces", hidden));
  for (size_t k = 0; k < study.hall.lights.size(); ++k) {
    Scene one = study.hall;
    one.lights = {study.hall.lights[k]};
    paths.push_back(study.pair("before_lamp_" + std::to_string(k), "point lamps, only " + quote(study.hall.lights[k].name) + " on",
                               before, &one));
  }
  paths.push_back(study.pair("physical_direct", "lamps of real size, direct light only", withTracing(physical, 0, 1)));
  paths.push_back(study.pair("physical", physicalWords, physical));
  RealisticRendering clamped = physical;
  clamped.tracing.clampIndirect = kClampIndirect;
  paths.push_back(study.pair("physical_clamped", std::string(physicalWords) + ", indirect samples clamped at " + fixedDecimals(kClampIndirect, 1),
                             clamped));
  return paths;
}

void writeCsv(const ConvergenceResults& r, const fs::path& out) {
  std::ostringstream ladder;
  ladder << "setup,pose,spp,psnr_db,outlier_share\n";
  for (const ConvergencePoint& p : r.ladder)
    ladder << p.setup << ',' << p.pose << ',' << p.spp << ',' << p.noise.psnrDb << ',' << p.noise.outlierShare << '\n';
  writeTextAtomically((out / "data/convergence.csv").string(), ladder.str());
  std::ostringstream paths;
  paths << "variant,pair_psnr_db,estimated_psnr_db,outlier_share\n";
  for (const PathVariant& v : r.paths)
    paths << v.name << ',' << v.pairPsnrDb << ',' << v.estimatedPsnrDb << ',' << v.outlierShare << '\n';
  writeTextAtomically((out / "data/paths.csv").string(), paths.str());
}


// The renders the study makes, for its progress: each distinct converged reference (a filtered
// setup shares its unfiltered twin's), the ladder, the clamp's bias, the path variants' seed
// pairs and the check at the experiment's size.
int renderCount(const ConvergenceOptions& o, const Scene& hall, const std::vector<RealisticRendering>& setups) {
  int references = 0;
  for (size_t k = 0; k < setups.size(); ++k) {
    const RealisticRendering reference = convergedReferenceOf(setups[k]);
    bool seen = false;
    for (size_t e = 0; e < k; ++e) seen = seen || convergesLike(convergedReferenceOf(setups[e]), reference);
    references += seen ? 0 : 1;
  }
  const int variants = o.everyPath ? 8 + static_cast<int>(hall.lights.size()) : 2;
  return references + static_cast<int>(setups.size() * o.ladder.size()) + 1 + 2 * variants + 2;
}

// Each setup at each rung of the ladder against its converged reference; the first pose's
// frames into frames/.
void measureLadder(Study& study, ReferenceCache& cache, const std::vector<RealisticRendering>& setups, const fs::path& out,
                   ConvergenceResults& r) {
  const ConvergenceOptions& o = study.options;
  for (const RealisticRendering& setup : setups) {
    r.setups.push_back(setup.name);
    r.setupDescriptions.push_back(setup.describe());
    const std::vector<ImageRGBA>& reference = cache.get(study, convergedReferenceOf(setup), o.size, o.referenceSpp);
    writeImageAtomic((out / ("frames/" + setup.name + "_reference.png")).string(), reference.front());
    for (size_t rung = 0; rung < o.ladder.size(); ++rung) {
      const int spp = o.ladder[rung];
      const std::vector<ImageRGBA> frames = study.render(setup, o.size, spp, rungSeed(rung), setup.name);
      writeImageAtomic((out / ("frames/" + setup.name + "_" + std::to_string(spp) + "spp.png")).string(), frames.front());
      for (size_t p = 0; p < frames.size(); ++p)
        r.ladder.push_back({setup.name, o.poseIndices[p], spp, measureRenderNoise(frames[p], reference[p])});
    }
  }
}

// The clamp's bias: the physical setup's converged frames clamped against unclamped, averaged over the poses.
void measureClampBias(Study& study, ReferenceCache& cache, ConvergenceResults& r) {
  const ConvergenceOptions& o = study.options;
  RealisticRendering clamped = realisticRenderingPhysical();
  const std::vector<ImageRGBA>& unclamped = cache.get(study, convergedReferenceOf(clamped), o.size, o.referenceSpp);
  clamped.name = "physical_clamped";
  clamped.tracing.clampIndirect = kClampIndirect;
  r.clampIndirect = kClampIndirect;
  const std::vector<ImageRGBA> clampedReference = study.render(clamped, o.size, o.referenceSpp, kReferenceSeed, "clamp bias");
  for (size_t p = 0; p < unclamped.size(); ++p) {
    const double n = static_cast<double>(unclamped.size());
    r.clampBiasPsnrDb += measureRenderNoise(clampedReference[p], unclamped[p]).psnrDb / n;
    const double luminance = meanLuminance(unclamped[p], unclamped[p]);
    if (luminance > 0.0)
      r.clampBiasLuminancePercent += 100.0 * (meanLuminance(clampedReference[p], unclamped[p]) - luminance) / luminance / n;
  }
}

// Today's setup at the experiment's own size and spp against an unfiltered reference.
void checkAtExperimentSize(Study& study, ConvergenceResults& r) {
  const ConvergenceOptions& o = study.options;
  const RealisticRendering today = realisticRendering();
  r.experimentSize = o.experimentSize;
  r.quick = o.quickRun;
  r.experimentSpp = today.spp;
  r.experimentReferenceSpp = o.experimentReferenceSpp;
  const std::vector<ImageRGBA> reference =
      study.render(convergedReferenceOf(today), o.experimentSize, o.experimentReferenceSpp, kReferenceSeed, "experiment size");
  const std::vector<ImageRGBA> frames = study.render(today, o.experimentSize, today.spp, kPairSeeds[0], "experiment size");
  for (size_t p = 0; p < frames.size(); ++p) r.experimentPsnrDb.push_back(measureRenderNoise(frames[p], reference[p]).psnrDb);
}

}  // namespace

ConvergenceResults runRealisticConvergence(const ConvergenceOptions& o, const std::string& plotScript,
                                           const ExperimentProgress& progress) {
  const auto started = std::chrono::steady_clock::now();
  if (o.size < 16 || o.experimentSize < 16 || o.ladder.empty() || o.referenceSpp < 1 || o.diagnosisSpp < 1 ||
      o.poseIndices.empty() || o.labPhoto.empty())
    throw InputError("realistic convergence: sizes >= 16, a ladder, spp >= 1, >= 1 pose and the lab photo");
  const fs::path out(o.outDir);
  makeRunFolders(o.outDir, {"arenas", "data", "frames"}, !plotScript.empty());
  HallOptions hallOptions;
  hallOptions.fieldScene = o.fieldScene;
  hallOptions.photos = {o.labPhoto};
  writeHallArena(hallOptions, (out / "arenas/hall-textured.json").string());
  const Scene hall = loadScene((out / "arenas/hall-textured.json").string());
  const CameraPath* loop = hall.findPath("thesis-loop");
  if (!loop) throw InputError(showPath(o.fieldScene) + ": paths: no \"thesis-loop\"");

  Study study{o, hall, {}, progress};
  for (int index : o.poseIndices) {
    if (index < 0 || static_cast<size_t>(index) >= loop->poses.size())
      throw InputError("realistic convergence: thesis-loop has no pose " + std::to_string(index));
    study.poses.push_back(loop->poses[static_cast<size_t>(index)]);
  }
  const std::vector<RealisticRendering> setups = {realisticRenderingBefore(), realisticRenderingPhysical(), realisticRendering()};
  study.total = renderCount(o, hall, setups);

  ConvergenceResults r;
  r.size = o.size;
  r.referenceSpp = o.referenceSpp;
  ReferenceCache cache;
  measureLadder(study, cache, setups, out, r);
  measureClampBias(study, cache, r);
  r.paths = diagnosePaths(study);
  checkAtExperimentSize(study, r);

  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  writeCsv(r, out);
  writeTextAtomically((out / "convergence.json").string(), convergenceJson(r).dump(2) + "\n");
  if (!plotScript.empty()) runPlotScript(plotScript, out.string());
  return r;
}

}  // namespace omnicam
