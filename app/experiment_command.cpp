// omnicam experiment texture-realism -o DIR [--quick] [--doc PATH]
// omnicam arena hall [--photo IMG]... [--random-photos] [--seed S] -o SCENE.json
// omnicam arena mapping [--seed S] -o SCENE.json
#include <cstdio>
#include <filesystem>

#include "atomic_file.h"
#include "cli_util.h"
#include "commands.h"
#include "errors.h"
#include "hall_arena.h"
#include "mapping_arena.h"
#include "texture_realism.h"

namespace omnicam::cli {

namespace {

// Debian's blender-data: eight CC0 360° photos (Greg Zaal); "interior" plays the thesis' lab.
const char* kStudioLights = "/usr/share/blender/datafiles/studiolights/world/";
const char* kLabPhoto = "interior.exr";
const char* kOtherPhotos[] = {"city.exr", "courtyard.exr", "forest.exr", "night.exr", "studio.exr", "sunrise.exr", "sunset.exr"};

std::string experimentsDir() {
  if (const char* env = std::getenv("OMNICAM_EXPERIMENTS")) return env;
  return OMNICAM_EXPERIMENTS_DIR;
}

struct ExperimentArgs {
  std::string name, out, doc;
  bool quick = false, noFigures = false;
  double theta = 1.0;
  int bins = 32;
};

void runExperiment(const ExperimentArgs& a) {
  if (a.name != "texture-realism") throw InputError("experiment: unknown experiment " + quote(a.name) + " (texture-realism)");
  if (a.out.empty()) throw InputError("-o: give the folder for the results");
  ensureDirectory(a.out, "-o");
  TextureRealismOptions options = a.quick ? TextureRealismOptions::quick() : TextureRealismOptions();
  options.outDir = a.out;
  if (!(a.theta > 0.0 && a.theta < 1e6)) throw InputError("--theta: must be in (0, 1e6)");
  if (a.bins < 2 || a.bins > 256) throw InputError("--bins: must be in [2, 256]");
  options.detector.theta = a.theta;
  options.bins = a.bins;
  options.fieldScene = scenesDir() + "/robocup2006.json";
  options.labPhoto = std::string(kStudioLights) + kLabPhoto;
  for (const char* photo : kOtherPhotos) options.randomPhotos.push_back(std::string(kStudioLights) + photo);
  for (const std::string& photo : options.randomPhotos)
    if (!std::filesystem::exists(photo))
      throw InputError(showPath(photo) + ": missing (Debian's blender-data ships it; run make deps)");
  std::string stage;
  std::unique_ptr<Progress> bar;
  const TextureRealismResults results = runTextureRealism(
      options, a.noFigures ? "" : experimentsDir() + "/plot_texture_realism.py",
      [&](const std::string& s, int /*done*/, int total) {
        if (s != stage) {
          if (bar) bar->finish();
          stage = s;
          bar = std::make_unique<Progress>(s, total);
        }
        bar->step();
      });
  if (bar) bar->finish();
  for (const ConditionOutcome& c : results.conditions)
    std::printf("%-30s %3d frames  TP %4d  FP %5d  missed %3d  error %.2f px\n", c.key().c_str(), c.frames,
                c.truePositives, c.falsePositives, c.missed, c.meanLocalisationErrorPx);
  for (const EkfOutcome& e : results.ekf)
    std::printf("EKF %-26s odometry %.1f cm  EKF %.1f cm  improvement %.1f cm\n", e.condition.c_str(),
                e.meanErrorOdometryCm, e.meanErrorEkfCm, e.meanErrorOdometryCm - e.meanErrorEkfCm);
  std::string command = std::string("omnicam experiment texture-realism -o DIR") + (a.quick ? " --quick" : "");
  if (a.theta != 1.0) command += " --theta " + std::to_string(a.theta);
  if (a.bins != 32) command += " --bins " + std::to_string(a.bins);
  if (!a.doc.empty()) command += " --doc " + a.doc;
  const std::string markdown = textureRealismMarkdown(results, options, command);
  writeTextAtomically(a.out + "/texture-realism.md", markdown);
  if (!a.doc.empty()) writeTextAtomically(a.doc, markdown);
  std::printf("wrote %s/results.json, %s/report.html (%.0f s)\n", a.out.c_str(), a.out.c_str(), results.seconds);
}

struct ArenaArgs {
  std::string kind, out;
  std::vector<std::string> photos;
  bool randomPhotos = false;
  uint64_t seed = 1;
};

void runArena(const ArenaArgs& a, const CLI::App& cmd) {
  if (a.kind != "hall" && a.kind != "mapping") throw InputError("arena: unknown arena " + quote(a.kind) + " (hall, mapping)");
  if (a.out.empty() || std::filesystem::path(a.out).extension() != ".json") throw InputError("-o: give the scene file to write (.json)");
  if (a.kind == "mapping") {
    refuseUnless(cmd, "--photo", false, "arena hall");
    refuseUnless(cmd, "--random-photos", false, "arena hall");
    MappingOptions options;
    options.seed = a.seed;
    const MappingArena arena = generateMappingArena(options);
    const std::filesystem::path parent = std::filesystem::path(a.out).parent_path();
    if (!parent.empty()) ensureDirectory(parent.string(), "-o");
    writeTextAtomically(a.out, arena.scene.dump(1) + "\n");
    std::printf("wrote %s (mapping maze %dx%d cells, seed %llu: %zu objects, %d victims)\n", a.out.c_str(), options.cellsX,
                options.cellsY, static_cast<unsigned long long>(a.seed), arena.scene["objects"].size(), options.victims);
    return;
  }
  if (a.randomPhotos && a.photos.empty()) throw InputError("--random-photos: give photos with --photo");
  HallOptions options;
  options.fieldScene = scenesDir() + "/robocup2006.json";
  options.photos = a.photos;
  options.randomPhotos = a.randomPhotos;
  options.seed = a.seed;
  const std::filesystem::path parent = std::filesystem::path(a.out).parent_path();
  if (!parent.empty()) checkOutputFolder(parent.string(), "-o");  // created once the photos have been read
  const std::vector<std::string> textures = writeHallArena(options, a.out);
  std::printf("wrote %s (%s walls, %zu textures)\n", a.out.c_str(), a.photos.empty() ? "plain" : "textured", textures.size());
}

}  // namespace

void addExperimentCommands(CLI::App& app) {
  auto args = std::make_shared<ExperimentArgs>();
  CLI::App* cmd = app.add_subcommand("experiment", "Run one of the thesis' experiments (docs/texture-realism.md)");
  cmd->add_option("name", args->name, "texture-realism")->required();
  cmd->add_option("-o,--output", args->out, "Folder for results.json, report.html, figures/ and data/")->required();
  cmd->add_flag("--quick", args->quick, "A few frames, small images and low spp (minutes, for tests)");
  cmd->add_option("--doc", args->doc, "Also write the Markdown summary here (docs/texture-realism.md)");
  cmd->add_flag("--no-figures", args->noFigures, "Skip the matplotlib figures");
  cmd->add_option("--theta", args->theta, "Likelihood-ratio threshold of the classifiers (Eq. 3.10; default 1)");
  cmd->add_option("--bins", args->bins, "Histogram bins per RGB channel (default 32)");
  cmd->callback([args] { runExperiment(*args); });

  auto arena = std::make_shared<ArenaArgs>();
  CLI::App* arenaCmd = app.add_subcommand("arena", "Generate an arena scene: hall (robocup2006 inside walls and a "
                                                   "ceiling) or mapping (a seeded rescue maze with victims)");
  arenaCmd->add_option("kind", arena->kind, "hall or mapping")->required();
  arenaCmd->add_option("-o,--output", arena->out, "Scene file to write; textures go beside it")->required();
  arenaCmd->add_option("--photo", arena->photos,
                       "360-degree photo for the walls (repeatable): an equirectangular image, or an omni image "
                       "unwrapped with `omnicam view IMG --as panorama` (its sidecar beside it)");
  arenaCmd->add_flag("--random-photos", arena->randomPhotos, "Each wall a photo and a turn drawn from --seed");
  arenaCmd->add_option("--seed", arena->seed, "Seed of the maze (mapping) or of --random-photos (hall)");
  arenaCmd->callback([arena, arenaCmd] { runArena(*arena, *arenaCmd); });
}

}  // namespace omnicam::cli
