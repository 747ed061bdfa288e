// omnicam experiment texture-realism -o DIR [--quick] [--doc PATH]
// omnicam experiment calibration -o DIR [--quick] [--doc PATH]
// omnicam arena hall [--photo IMG] [--random-photos --photo IMG... --seed S] -o SCENE.json
// omnicam arena mapping [--seed S] -o SCENE.json
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "atomic_file.h"
#include "calibration_study.h"
#include "cli_util.h"
#include "number_format.h"
#include "commands.h"
#include "data_files.h"
#include "errors.h"
#include "experiment_folder.h"
#include "hall_arena.h"
#include "json_text.h"
#include "markup.h"
#include "mapping_arena.h"
#include "path_convergence.h"
#include "realistic_convergence.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "texture_realism.h"
#include "texture_realism_report.h"

namespace omnicam::cli {

namespace {

// Debian's blender-data: eight CC0 360° photos (Greg Zaal); "interior" plays the thesis' lab.
const char* kStudioLights = "/usr/share/blender/datafiles/studiolights/world/";
const char* kOtherPhotos[] = {"city.exr", "courtyard.exr", "forest.exr", "night.exr", "studio.exr", "sunrise.exr", "sunset.exr"};

std::string experimentsDir() {
  if (const char* env = std::getenv("OMNICAM_EXPERIMENTS")) return env;
  return dataFile("experiments").string();
}

struct ExperimentArgs {
  std::string name, out, doc, convergence, noiseScene;
  std::vector<std::string> testCameras;
  bool quick = false, noFigures = false;
  double theta = 1.0;
  int bins = 32, medianPx = 1, minBlobArea = 2;
  bool noAblation = false;
};

// Progress bars, one per stage.
struct StageProgress {
  std::string stage;
  std::unique_ptr<Progress> bar;
  // `done` of `total`: within the stage, or from the first stage on when the stages share one total
  // (the convergence study's renders).
  void operator()(const std::string& s, int done, int total) {
    if (s != stage) {
      if (bar) bar->finish();
      stage = s;
      // A stage named by what it counts ("calibrations", "paths") counts those; a longer one, steps.
      // The bar starts when the stage's first step is reported done: that step is not timed.
      bar = std::make_unique<Progress>(s, total, done, s.find(' ') == std::string::npos ? s : "steps");
    }
    bar->advanceTo(done);
  }
  void finish() {
    if (bar) bar->finish();
    bar.reset();
  }
  ~StageProgress() { finish(); }
};

// The flags only texture-realism takes, refused by the other experiments.
void refuseTextureRealismFlags(const CLI::App& cmd) {
  for (const char* flag : {"--convergence", "--theta", "--bins", "--test-camera", "--median", "--min-blob-area", "--no-ablation"})
    refuseUnless(cmd, flag, false, "experiment texture-realism");
}

// Before any work, the files an experiment ends with: each name in an existing -o folder free to
// take (a file or nothing: checkOutputFile), --doc too and apart from the folder, and the figures/
// folder beside --doc a folder or nothing. A run of minutes must not be refused at its end.
void checkFinalFiles(const ExperimentArgs& a, const std::vector<std::string>& files) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(a.out, ec))
    for (const std::string& file : files) checkOutputFile((fs::path(a.out) / file).string(), "-o");
  if (a.doc.empty()) return;
  checkOutputFile(a.doc, "--doc");
  if (namesSameFile(a.doc, a.out))
    throw InputError("--doc: " + showPath(a.doc) + " is the -o folder: give the document a file name");
  const fs::path docFolder = fs::path(a.doc).parent_path();
  const EntryKind figures = entryInside(docFolder.empty() ? "." : docFolder.string(), "figures");
  if (figures != EntryKind::Missing && figures != EntryKind::Folder)
    throw InputError("--doc: " + showPath((docFolder / "figures").string()) +
                     " is not a folder (a link is not followed): the document's figures go there");
}

void runConvergence(const ExperimentArgs& a, const CLI::App& cmd) {
  refuseTextureRealismFlags(cmd);
  refuseUnless(cmd, "--doc", false, "experiment texture-realism, calibration or path-convergence");
  refuseUnless(cmd, "--noise-scene", false, "experiment path-convergence");
  checkOutputFolder(a.out, "-o");
  checkFinalFiles(a, {"convergence.json", "convergence.md"});
  checkExperimentFolder(a.out, a.name);
  ConvergenceOptions options = a.quick ? ConvergenceOptions::quick() : ConvergenceOptions();
  options.outDir = a.out;
  options.fieldScene = scenesDir() + "/robocup2006.json";
  options.labPhoto = kLabPhoto;
  if (!std::filesystem::exists(options.labPhoto))
    throw InputError(showPath(options.labPhoto) + ": missing (Debian's blender-data ships it; run make deps)");
  ensureDirectory(a.out, "-o");
  markExperimentFolder(a.out, a.name);
  StageProgress progress;
  const ConvergenceResults r = runRealisticConvergence(
      options, a.noFigures ? "" : experimentsDir() + "/plot_convergence.py",
      std::ref(progress));
  progress.finish();
  const std::string markdown = convergenceMarkdown(r, a.noFigures ? "" : "figures/convergence.svg");
  writeTextAtomically(a.out + "/convergence.md", markdown);
  std::printf("%s", markdown.c_str());
  std::printf("wrote %s and %s (%.0f s)\n", showPath(a.out + "/convergence.json").c_str(), showPath(a.out + "/convergence.md").c_str(),
              r.seconds);
}

// Replaces the generated section of `doc` (from "## Measured" to the next "## " heading) with
// `section`, or appends it; the prose around it is kept.
void replaceGeneratedSection(const std::string& doc, const std::string& section) {
  std::string text;
  if (std::filesystem::exists(doc)) {
    const std::filesystem::path path(doc);
    text = readFileInside(path.parent_path().empty() ? "." : path.parent_path().string(), path.filename().string(), 4 << 20);
  }
  const size_t begin = text.find("## Measured\n");
  if (begin == std::string::npos) {
    writeTextAtomically(doc, text + (text.empty() || text.back() == '\n' ? "" : "\n") + "\n" + section);
    return;
  }
  const size_t next = text.find("\n## ", begin + 1);
  const std::string after = next == std::string::npos ? "" : text.substr(next + 1);
  writeTextAtomically(doc, text.substr(0, begin) + section + (after.empty() ? "" : "\n" + after));
}

void runPathStudy(const ExperimentArgs& a, const CLI::App& cmd) {
  refuseTextureRealismFlags(cmd);
  refuseUnless(cmd, "--no-figures", false, "experiment texture-realism");
  if (!a.noiseScene.empty() && a.noiseScene != "plain_hall" && a.noiseScene != "textured_hall" && a.noiseScene != "tiled_room")
    throw InputError("--noise-scene: must be plain_hall, textured_hall or tiled_room (got " + quote(a.noiseScene) + ")");
  checkOutputFolder(a.out, "-o");
  checkFinalFiles(a, {"path-convergence.json", "path-convergence.md"});
  checkExperimentFolder(a.out, a.name);
  PathConvergenceOptions options = a.quick ? PathConvergenceOptions::quick() : PathConvergenceOptions();
  options.outDir = a.out;
  options.fieldScene = scenesDir() + "/robocup2006.json";
  options.tiledRoom = scenesDir() + "/tiled-room.json";
  if (!a.noiseScene.empty()) {
    options.floorScene = a.noiseScene;
    std::replace(options.floorScene.begin(), options.floorScene.end(), '_', ' ');
  }
  options.labPhoto = kLabPhoto;
  if (!std::filesystem::exists(options.labPhoto))
    throw InputError(showPath(options.labPhoto) + ": missing (Debian's blender-data ships it; run make deps)");
  ensureDirectory(a.out, "-o");
  markExperimentFolder(a.out, a.name);
  StageProgress progress;
  const PathConvergenceResults r = runPathConvergence(
      options, std::ref(progress));
  progress.finish();
  std::string command = "omnicam experiment path-convergence -o DIR";
  if (a.quick) command += " --quick";
  if (!a.doc.empty()) command += " --doc " + shellPath(a.doc);
  const std::string markdown = pathConvergenceMarkdown(r, command);
  writeTextAtomically(a.out + "/path-convergence.md", markdown);
  if (!a.doc.empty()) replaceGeneratedSection(a.doc, markdown);
  std::printf("%swrote %s (%.0f s)\n", markdown.c_str(), showPath(a.out + "/path-convergence.json").c_str(), r.seconds);
}

// A figure's bytes into figures/ beside the document `doc`.
void writeFigureBeside(const std::string& doc, const std::string& name, const std::string& bytes) {
  const std::filesystem::path docFolder = std::filesystem::path(doc).parent_path();
  makeFoldersInside(docFolder.empty() ? "." : docFolder.string(), "figures");
  writeTextAtomically((docFolder / "figures" / name).string(), bytes);
}

// The study's folder as read: its results, and its figure when it has one.
struct ConvergenceFolder {
  ConvergenceResults results;
  std::optional<std::string> svg;
};

// What in an SVG could act when a document shows it — a script, an event handler (on…=), a link
// out of the figure (an href not to one of its own #ids or an embedded data:image) — or "" when
// nothing does. `lower` is the SVG's text in lower case. matplotlib writes none of these.
std::string activeSvgContent(const std::string& lower) {
  for (const char* element : {"<script", "javascript:", "<foreignobject", "<iframe", "<embed", "<object"})
    if (lower.find(element) != std::string::npos) return element;
  const auto isName = [](char c) { return c >= 'a' && c <= 'z'; };
  const auto skipSpaces = [&](size_t at) {
    while (at < lower.size() && std::isspace(static_cast<unsigned char>(lower[at]))) ++at;
    return at;
  };
  for (size_t at = lower.find("on"); at != std::string::npos; at = lower.find("on", at + 1)) {
    const char before = at ? lower[at - 1] : ' ';
    if (!(std::isspace(static_cast<unsigned char>(before)) || before == '/' || before == '"' || before == '\'')) continue;
    size_t end = at + 2;
    while (end < lower.size() && isName(lower[end])) ++end;
    if (end > at + 2 && skipSpaces(end) < lower.size() && lower[skipSpaces(end)] == '=') return lower.substr(at, end - at) + "=";
  }
  for (size_t at = lower.find("href"); at != std::string::npos; at = lower.find("href", at + 1)) {
    size_t value = skipSpaces(at + 4);
    if (value >= lower.size() || lower[value] != '=') continue;
    value = skipSpaces(value + 1);
    if (value < lower.size() && (lower[value] == '"' || lower[value] == '\'')) value = skipSpaces(value + 1);
    if (lower.compare(value, 1, "#") != 0 && lower.compare(value, 11, "data:image/") != 0) return lower.substr(at, value + 24 - at);
  }
  return "";
}

// The study's figure, checked: it goes into documents others open, so what could act there is
// refused, not copied.
std::optional<std::string> readConvergenceFigure(const std::string& folder) {
  if (entryInside(folder, "figures/convergence.svg") != EntryKind::File) return std::nullopt;
  const std::string svg = readFileInside(folder, "figures/convergence.svg", 4 << 20);
  if (svg.find("<svg") == std::string::npos)
    throw InputError(showPath(folder + "/figures/convergence.svg") + ": not the study's SVG figure");
  std::string lower(svg.size(), ' ');
  std::transform(svg.begin(), svg.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (const std::string active = activeSvgContent(lower); !active.empty())
    throw InputError(showPath(folder + "/figures/convergence.svg") + ": holds " + quote(active) +
                     ", which the study's figure never does: not copied into the documents");
  return svg;
}

// The study's results and figure, read before anything is written (an output folder is untrusted input).
ConvergenceFolder readConvergence(const std::string& folder) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    throw InputError("--convergence: " + showPath(folder) + (std::filesystem::exists(folder, ec) ? ": not a folder" : ": no such folder") +
                     " (give the -o folder of `omnicam experiment realistic-convergence`)");
  if (entryInside(folder, "convergence.json") == EntryKind::Missing)
    throw InputError("--convergence: " + showPath(folder) + ": not a realistic-convergence folder (it holds no convergence.json; give the -o "
                     "folder of `omnicam experiment realistic-convergence`)");
  const std::string file = folder + "/convergence.json";
  return {convergenceFromJson(parseJsonText(readFileInside(folder, "convergence.json", 64 << 20), file), file),
          readConvergenceFigure(folder)};
}

// The study's section for the documents; the study's figure is copied beside each that shows it
// (the run's own texture-realism.md in `out`, and --doc's).
std::string convergenceSection(const ConvergenceFolder& study, const std::string& out, const std::string& doc) {
  if (!study.svg) return convergenceMarkdown(study.results, "");
  writeFigureBeside((std::filesystem::path(out) / "texture-realism.md").string(), "realistic_convergence.svg", *study.svg);
  if (!doc.empty()) writeFigureBeside(doc, "realistic_convergence.svg", *study.svg);
  return convergenceMarkdown(study.results, "figures/realistic_convergence.svg");
}

// Without --convergence, the study's section an earlier run wrote into the document (its figure
// already beside it) is carried over as it was: the study's data did not change. "" if none.
std::string keptConvergenceSection(const std::string& doc) {
  if (doc.empty() || !std::filesystem::is_regular_file(doc)) return "";
  const std::filesystem::path path(doc);
  const std::string text = readFileInside(path.parent_path().empty() ? "." : path.parent_path().string(), path.filename().string(), 4 << 20);
  const size_t begin = text.find("## Are the realistic frames converged?\n");
  const size_t end = text.find("\nWhere the numbers differ from the thesis:", begin);
  if (begin == std::string::npos || end == std::string::npos) return "";
  return text.substr(begin, end - begin);
}

// The figures of a run, copied beside the document that shows them (its figures/ folder).
void copyFigures(const std::string& folder, const std::string& doc, const std::vector<std::string>& figures) {
  for (const std::string& figure : figures) writeFigureBeside(doc, figure, readFileInside(folder, "figures/" + figure, 16 << 20));
}

void runCalibration(const ExperimentArgs& a, const CLI::App& cmd) {
  refuseTextureRealismFlags(cmd);
  refuseUnless(cmd, "--noise-scene", false, "experiment path-convergence");
  if (!a.doc.empty() && a.noFigures) throw InputError("--doc: the document shows the figures; leave out --no-figures");
  checkOutputFolder(a.out, "-o");
  checkFinalFiles(a, {"results.json", "calibration-study.md"});
  checkExperimentFolder(a.out, a.name);
  CalibrationStudyOptions options = a.quick ? CalibrationStudyOptions::quick() : CalibrationStudyOptions();
  options.outDir = a.out;
  options.fieldScene = scenesDir() + "/robocup2006.json";
  ensureDirectory(a.out, "-o");
  markExperimentFolder(a.out, a.name);
  StageProgress progress;
  const CalibrationStudyResults r = runCalibrationStudy(
      options, a.noFigures ? "" : experimentsDir() + "/plot_calibration_study.py",
      std::ref(progress));
  progress.finish();
  std::string command = std::string("omnicam experiment calibration -o DIR") + (a.quick ? " --quick" : "") + (a.noFigures ? " --no-figures" : "");
  if (!a.doc.empty()) command += " --doc " + shellPath(a.doc);
  const std::string markdown = calibrationStudyMarkdown(r, options, command, !a.noFigures);
  writeTextAtomically(a.out + "/calibration-study.md", markdown);
  if (!a.doc.empty()) {
    copyFigures(a.out, a.doc, {"calibration_study_error.svg", "calibration_study_residuals.png"});
    writeTextAtomically(a.doc, markdown);
  }
  std::printf("%swrote %s, %s%s (%.0f s)\n", markdown.c_str(), showPath(a.out + "/results.json").c_str(),
              showPath(a.out + "/calibration-study.md").c_str(), a.doc.empty() ? "" : (", " + showPath(a.doc)).c_str(), r.seconds);
}

// A --test-camera FILE: one camera in the recording format, its fields at the top level.
RecordingCameraSpec readTestCamera(const std::string& file) {
  constexpr const char* kFormat = "a test camera is a JSON file of the recording's fields, e.g. examples/recording/cool_noisy.json";
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    const std::vector<std::string>& presets = recordingPresetNames();
    const bool preset = std::find(presets.begin(), presets.end(), file) != presets.end();
    throw InputError("--test-camera: " + showPath(file) + ": no such file (" + kFormat +
                     (preset ? "; a preset goes in such a file: {\"preset\": \"" + file + "\"})" : ")"));
  }
  const nlohmann::json j = readJsonFile(file);
  if (j.is_object() && j.contains("recording"))  // a dataset spec, or a camera wrapped as in one
    throw InputError("--test-camera: " + showPath(file) + ": recording: give the recording's fields at the file's top level, not "
                     "inside \"recording\" (" + kFormat + ")");
  return recordingCameraSpecFromJson(j, file, "");
}

void runExperiment(const ExperimentArgs& a, const CLI::App& cmd) {
  if (a.name != "texture-realism" && a.name != "realistic-convergence" && a.name != "path-convergence" && a.name != "calibration")
    throw InputError("experiment: unknown experiment " + quote(a.name) +
                     " (texture-realism, realistic-convergence, path-convergence, calibration)");
  if (a.out.empty()) throw InputError("-o: give the folder for the results");
  if (a.name == "realistic-convergence") return runConvergence(a, cmd);
  if (a.name == "path-convergence") return runPathStudy(a, cmd);
  if (a.name == "calibration") return runCalibration(a, cmd);
  refuseUnless(cmd, "--noise-scene", false, "experiment path-convergence");
  std::optional<ConvergenceFolder> convergence;
  if (!a.convergence.empty()) convergence = readConvergence(a.convergence);
  checkOutputFolder(a.out, "-o");
  checkFinalFiles(a, {"results.json", "report.html", "texture-realism.md"});
  checkExperimentFolder(a.out, a.name);
  TextureRealismOptions options = a.quick ? TextureRealismOptions::quick() : TextureRealismOptions();
  options.outDir = a.out;
  options.detector.theta = a.theta;
  options.detector.medianPx = a.medianPx;
  options.detector.minBlobArea = a.minBlobArea;
  options.ablation = !a.noAblation;
  options.bins = a.bins;
  options.fieldScene = scenesDir() + "/robocup2006.json";
  options.labPhoto = kLabPhoto;
  for (const char* photo : kOtherPhotos) options.randomPhotos.push_back(std::string(kStudioLights) + photo);
  for (const std::string& file : a.testCameras)  // read before anything is written: a bad one writes nothing
    options.testCameras.push_back({file, readTestCamera(file)});
  for (const std::string& photo : options.randomPhotos)
    if (!std::filesystem::exists(photo))
      throw InputError(showPath(photo) + ": missing (Debian's blender-data ships it; run make deps)");
  ensureDirectory(a.out, "-o");  // every option checked: only now is anything created
  markExperimentFolder(a.out, a.name);
  StageProgress progress;
  const TextureRealismResults results = runTextureRealism(
      options, a.noFigures ? "" : experimentsDir() + "/plot_texture_realism.py",
      std::ref(progress));
  progress.finish();
  for (const ConditionOutcome& c : results.conditions)
    std::printf("%-30s %3d frames  TP %4d  FP %5d  missed %3d  error %s px\n", c.key().c_str(), c.frames, c.truePositives,
                c.falsePositives, c.missed,
                c.meanLocalisationErrorPx ? fixedDecimals(*c.meanLocalisationErrorPx, 2).c_str() : "-");
  for (const EkfOutcome& e : results.ekf)
    std::printf("EKF %-26s odometry %.1f cm  EKF %.1f cm  improvement %.1f cm\n", e.condition.c_str(),
                e.meanErrorOdometryCm, e.meanErrorEkfCm, e.meanErrorOdometryCm - e.meanErrorEkfCm);
  std::string command = std::string("omnicam experiment texture-realism -o DIR") + (a.quick ? " --quick" : "");
  if (a.theta != 1.0) command += " --theta " + roundTrip(a.theta);
  if (a.bins != 32) command += " --bins " + std::to_string(a.bins);
  if (a.medianPx != 1) command += " --median " + std::to_string(a.medianPx);
  if (a.minBlobArea != 2) command += " --min-blob-area " + std::to_string(a.minBlobArea);
  if (a.noAblation) command += " --no-ablation";
  if (!a.doc.empty()) command += " --doc " + shellPath(a.doc);
  if (!a.convergence.empty()) command += " --convergence CONVERGENCE_DIR";
  for (const std::string& file : a.testCameras) command += " --test-camera " + shellPath(file);
  const std::string section = convergence ? convergenceSection(*convergence, a.out, a.doc) : keptConvergenceSection(a.doc);
  const std::string markdown = textureRealismMarkdown(results, options, command, section);
  writeTextAtomically(a.out + "/texture-realism.md", markdown);
  if (!a.doc.empty()) {
    if (!results.comparison.pixels.empty()) copyFigures(a.out, a.doc, {kRecordingFigure});
    writeTextAtomically(a.doc, markdown);
  }
  std::printf("wrote %s, %s (%.0f s)\n", showPath(a.out + "/results.json").c_str(), showPath(a.out + "/report.html").c_str(), results.seconds);
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
    std::printf("wrote %s (mapping maze %dx%d cells, seed %llu: %zu objects, %d victims)\n", showPath(a.out).c_str(), options.cellsX,
                options.cellsY, static_cast<unsigned long long>(a.seed), arena.scene["objects"].size(), options.victims);
    return;
  }
  if (a.randomPhotos && a.photos.empty()) throw InputError("--random-photos: give photos with --photo");
  if (!a.randomPhotos && a.photos.size() > 1)
    throw InputError("--photo: the hall's walls show one photo; give several with --random-photos (a photo per wall, drawn)");
  refuseUnless(cmd, "--seed", a.randomPhotos, "arena mapping, or arena hall --random-photos (the hall draws nothing else)");
  HallOptions options;
  options.fieldScene = scenesDir() + "/robocup2006.json";
  options.photos = a.photos;
  options.randomPhotos = a.randomPhotos;
  options.seed = a.seed;
  const std::filesystem::path parent = std::filesystem::path(a.out).parent_path();
  if (!parent.empty()) checkOutputFolder(parent.string(), "-o");  // created once the photos have been read
  const std::vector<std::string> textures = writeHallArena(options, a.out);
  std::printf("wrote %s (%s walls, %zu textures)\n", showPath(a.out).c_str(), a.photos.empty() ? "plain" : "textured", textures.size());
}

}  // namespace

void addExperimentCommands(CLI::App& app) {
  auto args = std::make_shared<ExperimentArgs>();
  CLI::App* cmd = app.add_subcommand("experiment", "Run one of the thesis' experiments (docs/experiments.md)");
  cmd->add_option("name", args->name,
                  "texture-realism, realistic-convergence (how converged its Blender frames are), path-convergence (the "
                  "fast renderer's path shading against Cycles, docs/path-tracing.md), or calibration (what misalignment "
                  "does to a calibrated camera, docs/calibration-study.md)")
      ->required();
  cmd->add_option("-o,--output", args->out, "Folder for the results (JSON), the report, figures/ and data/ (docs/experiments.md lists each experiment's files)")->required();
  cmd->add_flag("--quick", args->quick, "A few frames, small images and low spp (minutes, for tests)");
  cmd->add_option("--doc", args->doc,
                  "Also write the Markdown report here, its figures beside it (the repository's: docs/texture-realism.md, "
                  "docs/calibration-study.md, docs/path-tracing.md)");
  cmd->add_flag("--no-figures", args->noFigures, "Skip the matplotlib figures");
  cmd->add_option("--theta", args->theta, "Likelihood-ratio threshold of the classifiers (Eq. 3.10; default 1)")
      ->check(numberIn(0, 1e6, true));
  cmd->add_option("--bins", args->bins, "Histogram bins per RGB channel (default 32)")->check(integerIn(2, 256));
  cmd->add_option("--median", args->medianPx,
                  "texture-realism: median filter of N×N pixels on the frames before classifying, in training and "
                  "detection, for the thesis' pixel detector (odd, 1 = none; default 1); the footprint detector's is "
                  "chosen by validation among none, 3×3 and this")
      ->check(CLI::IsMember({1, 3, 5, 7}));
  cmd->add_option("--min-blob-area", args->minBlobArea, "texture-realism: smallest colour blob kept, in pixels (default 2)")
      ->check(integerIn(1, 10000));
  cmd->add_flag("--no-ablation", args->noAblation, "texture-realism: skip the ablation of the recording camera's stages");
  cmd->add_option("--convergence", args->convergence,
                  "texture-realism: include the study `experiment realistic-convergence -o DIR` wrote in DIR (without it, "
                  "--doc keeps the study's section the document already has)");
  cmd->add_option("--test-camera", args->testCameras,
                  "texture-realism: an extra realistic test set, the Cycles frames recorded through this camera "
                  "(JSON in a dataset's `recording` format; repeatable; training never sees it)");
  cmd->add_option("--noise-scene", args->noiseScene,
                  "path-convergence: measure the Cycles references' own noise on this scene only (plain_hall, "
                  "textured_hall or tiled_room; default every scene, which doubles Cycles' share of the run)");
  cmd->callback([args, cmd] { runExperiment(*args, *cmd); });

  auto arena = std::make_shared<ArenaArgs>();
  CLI::App* arenaCmd = app.add_subcommand("arena", "Generate an arena scene: hall (robocup2006 inside walls and a "
                                                   "ceiling) or mapping (a seeded rescue maze with victims)");
  arenaCmd->add_option("kind", arena->kind, "hall or mapping")->required();
  arenaCmd->add_option("-o,--output", arena->out, "Scene file to write; textures go beside it")->required();
  arenaCmd->add_option("--photo", arena->photos,
                       "360-degree photo for the walls (several with --random-photos): an equirectangular image, or an omni image "
                       "unwrapped with `omnicam view IMG --as panorama` (its sidecar beside it)");
  arenaCmd->add_flag("--random-photos", arena->randomPhotos, "Each wall a photo and a turn drawn from --seed");
  arenaCmd->add_option("--seed", arena->seed, "Seed of the maze (mapping) or of --random-photos (hall)")
      ->check(integerIn(0, UINT64_MAX));
  arenaCmd->callback([arena, arenaCmd] { runArena(*arena, *arenaCmd); });
}

}  // namespace omnicam::cli
