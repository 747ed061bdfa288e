#pragma once
// Does the fast renderer's path shading converge to Cycles' frame, and how fast? (issue #35,
// docs/path-tracing.md). Three scenes (the plain hall, the textured hall, the tiled room with its
// lamp) at three poses each, 360 px:
//   - converged fast frames (unfiltered, fastConvergedSpp × seeds) against converged Cycles frames
//     (unfiltered, referenceSpp), with the references' own noise measured on one scene (a second
//     reference of another seed);
//   - the filter's bias: fast frames filtered at fastConvergedSpp against the unfiltered converged
//     fast frame;
//   - the frames datasets use (filtered, chosenSpp) and Cycles' realistic frames (filtered,
//     cyclesSpp) against the Cycles reference, with the time each took;
//   - time to error, on the first pose of the textured hall: each engine's PSNR and seconds over a
//     ladder of spp, one after the other in one run, against the converged fast frame.
// PSNR is 8-bit sRGB inside the mirror disc (render_noise.h).
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiment_progress.h"
#include "image.h"
#include "render_settings.h"
#include "rig.h"
#include "scene.h"

namespace omnicam {

struct PathConvergenceOptions {
  std::string outDir, fieldScene, labPhoto, tiledRoom;
  int size = 360;
  int referenceSpp = 1024;     // Cycles, unfiltered
  int fastConvergedSpp = 1024;  // per seed
  int fastConvergedSeeds = 2;
  int chosenSpp = kPathDatasetSpp;  // the fast frames datasets use (filtered)
  int cyclesSpp = 36;          // the realistic frames of the texture-realism experiment (filtered)
  bool measureFloor = true;    // a second Cycles reference per pose (the references' own noise) ...
  std::string floorScene;      // ... of this scene only ("textured hall", say); empty: of every scene
  std::vector<int> fastLadder = {1, 4, 9, 16, 36, 64}, cyclesLadder = {4, 16, 36, 64};
  double blenderTimeoutSeconds = 3600.0;
  static PathConvergenceOptions quick();  // small images, few samples: for tests
};

struct PathFrameResult {
  std::string scene;
  RobotPose pose;
  double convergedPsnrDb = 0.0;     // converged fast vs the Cycles reference
  double referenceNoiseDb = 0.0;    // the reference's own noise: vs a converged frame (0: not measured)
  double fastNoiseDb = 0.0;         // the converged fast frame's own noise, likewise
  // What is left of the difference once both frames' own noise is taken out: the two engines'
  // disagreement (infinite within the noise).
  double disagreementDb = 0.0;     // 0: not known (a noise not measured)
  double filterBiasPsnrDb = 0.0;    // filtered fast vs unfiltered fast, both converged
  double chosenPsnrDb = 0.0, chosenSeconds = 0.0;  // fast, filtered, chosenSpp
  // Cycles, filtered, cyclesSpp: a frame's seconds in a session of the scene's poses, and the
  // session's start-up (Blender's, the glTF import, the scene's set-up) apart.
  double cyclesPsnrDb = 0.0, cyclesSeconds = 0.0, cyclesStartupSeconds = 0.0;
  double meanRatio = 0.0;           // mean radiance inside the disc, converged fast / Cycles
};

// One rung: an engine's seconds per frame of a sequence (Cycles: in one Blender session, its
// start-up in startupSeconds), and the first pose's PSNR.
struct LadderPoint {
  std::string engine;  // "fast" or "blender"
  int spp = 0;
  bool filtered = false;
  double seconds = 0.0, psnrDb = 0.0;
  double startupSeconds = 0.0;
};

struct PathConvergenceResults {
  PathConvergenceOptions options;
  std::vector<PathFrameResult> frames;
  std::vector<LadderPoint> ladder;
  // Seconds for each engine to reach `target` dB on the ladder (log-linear between rungs; 0 when
  // its ladder never gets there), and their ratio.
  struct TimeToError {
    double targetDb = 0.0, fastSeconds = 0.0, cyclesSeconds = 0.0;
  };
  std::vector<TimeToError> timeToError;
  double seconds = 0.0;
};

// Time to error on the first of `poses`: the fast engine over `fastLadder` (unfiltered and
// denoised) and Cycles over `cyclesLadder` (denoised), one after the other, against `converged`
// (that pose's); with the seconds each engine needs for 35, 38 and 40 dB. Each engine is timed
// per frame of a sequence of `poses`, as a dataset renders them: the fast renderer's frames after
// a warm-up frame, Cycles' frames after the first of one Blender session (docs/performance.md).
void measureTimeToError(const Scene& scene, const std::vector<RobotPose>& poses, const ImageRGBA& converged,
                        const PathConvergenceOptions& options, PathConvergenceResults& results,
                        const ExperimentProgress& progress);
// What Cycles' kept frames of `scene` at `poses` were rendered from (outDir/data/): the scene and
// the files it reads, size, spp, seed, denoising, shading and the Blender driver's bytes. A kept
// frame whose key differs is rendered again.
nlohmann::json cyclesFramesKey(const Scene& scene, const std::vector<RobotPose>& poses, const RenderSettings& settings,
                               int seed);
// The halls' three poses (the study's, the first the time-to-error pose).
std::vector<RobotPose> hallPoses();
// The mean of `seeds` unfiltered fast frames of `spp` each (seeds 1000, 1001, …).
ImageRGBA convergedFastFrame(const Scene& scene, const RobotPose& pose, int size, int spp, int seeds);

// Writes outDir/path-convergence.json and frames/ (the first pose of each scene: converged fast,
// Cycles reference, the fast dataset frame). InputError for bad options, ExternalError when
// Blender fails.
PathConvergenceResults runPathConvergence(const PathConvergenceOptions& options, const ExperimentProgress& progress);

nlohmann::json pathConvergenceJson(const PathConvergenceResults& results);
std::string pathConvergenceMarkdown(const PathConvergenceResults& results, const std::string& command);

}  // namespace omnicam
