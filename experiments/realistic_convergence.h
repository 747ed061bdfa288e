#pragma once
// The realistic frames' render noise, measured (docs/texture-realism.md, "Are the realistic frames
// converged?"): Blender renders of the textured hall at 16…4096 spp against a converged reference
// for three poses of thesis-loop, per rendering setup; which paths carry the noise (per lamp, per
// bounce, with and without the mirror seen by bounces); the bias of the clamp; and a check at the
// experiment's own image size and sample count. A filtered setup is measured against its unfiltered
// converged reference, so the filter's bias counts against it.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiment_progress.h"
#include "realistic_rendering.h"
#include "render_noise.h"

namespace omnicam {

struct ConvergenceOptions {
  std::string outDir, fieldScene, labPhoto;
  int size = 64;                                // the ladder's images (noise per pixel does not depend on size)
  std::vector<int> ladder = {16, 64, 256, 1024, 4096};  // above 1024: independent 1024-spp renders averaged
  int referenceSpp = 8192;
  int diagnosisSpp = 64;
  int experimentSize = 360;                     // the check at the experiment's size and spp ...
  int experimentReferenceSpp = 1024;            // ... against an unfiltered reference of this many spp
  std::vector<int> poseIndices = {0, 33, 66};  // of thesis-loop
  bool everyPath = true;                        // false: of the path variants only "before" and "physical"
  double blenderTimeoutSeconds = 3600.0;
  bool quickRun = false;                        // quick(): its report judges no target
  static ConvergenceOptions quick();            // tiny images, short ladder: for tests
};

struct ConvergencePoint {
  std::string setup;
  int pose = 0, spp = 0;
  RenderNoise noise;
};

// Two seeds of the same render: their noise without a reference (render_noise.h).
struct PathVariant {
  std::string name, description;
  double pairPsnrDb = 0.0, estimatedPsnrDb = 0.0, outlierShare = 0.0;  // means over the poses
};

struct ConvergenceResults {
  std::vector<std::string> setups;            // names, in the order rendered
  std::vector<std::string> setupDescriptions;
  std::vector<ConvergencePoint> ladder;
  std::vector<PathVariant> paths;
  // Clamping indirect samples at `clampIndirect`: its bias (the physical setup's converged frames clamped,
  // against unclamped; its noise at the diagnosis spp is in `paths`).
  double clampIndirect = 0.0, clampBiasPsnrDb = 0.0, clampBiasLuminancePercent = 0.0;
  // At the experiment's size and spp, per pose: the experiment's frame against an unfiltered
  // reference of experimentReferenceSpp (a lower bound: the reference's own noise counts too).
  int experimentSize = 0, experimentSpp = 0, experimentReferenceSpp = 0;
  std::vector<double> experimentPsnrDb;
  int size = 0, referenceSpp = 0;
  double seconds = 0.0;
  bool quick = false;  // a --quick run: smaller than the experiment's frames, its check judges no target
};

// Writes outDir/convergence.json, data/convergence.csv, frames/ (pose 0 at every rung) and
// figures/convergence.svg (by `plotScript`; empty: none). InputError for bad options.
ConvergenceResults runRealisticConvergence(const ConvergenceOptions& options, const std::string& plotScript,
                                           const ExperimentProgress& progress);

nlohmann::json convergenceJson(const ConvergenceResults& results);
// Reads what convergenceJson wrote; InputError naming `file` otherwise.
ConvergenceResults convergenceFromJson(const nlohmann::json& json, const std::string& file);
// The section of docs/texture-realism.md; `figure` is the plot's path relative to the document.
std::string convergenceMarkdown(const ConvergenceResults& results, const std::string& figure);

}  // namespace omnicam
