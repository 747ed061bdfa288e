#include "path_convergence.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "atomic_file.h"
#include "blender_renderer.h"
#include "errors.h"
#include "fast_renderer.h"
#include "hall_arena.h"
#include "image.h"
#include "render_noise.h"
#include "render_request.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "sha256.h"
#include "sidecar.h"
#include "number_format.h"

namespace omnicam {

namespace fs = std::filesystem;

PathConvergenceOptions PathConvergenceOptions::quick() {
  PathConvergenceOptions o;
  o.size = 48;
  o.referenceSpp = 64;
  o.fastConvergedSpp = 64;
  o.fastConvergedSeeds = 1;
  o.chosenSpp = 4;
  o.cyclesSpp = 4;
  o.measureFloor = false;
  o.fastLadder = {1, 4};
  o.cyclesLadder = {4};
  return o;
}

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct StudyScene {
  std::string name;
  Scene scene;
  std::vector<RobotPose> poses;
};

RenderSettings pathSettings(const Scene& scene, int size, int spp, bool denoise, uint64_t seed = 0) {
  return requestedSettings(scene.rig.resized(size), {{RequestField::Spp, int64_t{spp}},
                                                     {RequestField::Shading, "path"},
                                                     {RequestField::Denoise, denoise},
                                                     {RequestField::Seed, static_cast<int64_t>(seed)}});
}

ImageRGBA meanOf(const std::vector<ImageRGBA>& frames) {
  ImageRGBA sum = frames.front();
  for (size_t f = 1; f < frames.size(); ++f)
    for (size_t p = 0; p < sum.pixels.size(); p += 4)
      for (size_t c = 0; c < 3; ++c) sum.pixels[p + c] += frames[f].pixels[p + c];
  for (size_t p = 0; p < sum.pixels.size(); p += 4)
    for (size_t c = 0; c < 3; ++c) sum.pixels[p + c] /= static_cast<float>(frames.size());
  return sum;
}

std::vector<ImageRGBA> fastSeeds(const FastRenderer& renderer, const RobotPose& pose, const RenderSettings& base, int seeds) {
  std::vector<ImageRGBA> frames;
  for (int s = 0; s < seeds; ++s) {
    RenderSettings settings = base;
    settings.seed = 1000 + static_cast<uint64_t>(s);
    frames.push_back(renderer.render(pose, settings));
  }
  return frames;
}

// Mean squared difference of 8-bit sRGB levels, from a PSNR; and back.
double squaredLevels(double psnrDb) { return 255.0 * 255.0 * std::pow(10.0, -psnrDb / 10.0); }
double psnrOf(double squared) { return squared > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / squared) : 99.0; }

double meanInside(const ImageRGBA& image, const ImageRGBA& mask) {
  double sum = 0.0;
  for (size_t p = 0; p < image.pixels.size(); p += 4)
    if (mask.pixels[p + 3] >= 0.999f) sum += image.pixels[p] + image.pixels[p + 1] + image.pixels[p + 2];
  return sum;
}

BlenderOptions blenderOptions(double timeoutSeconds, int seed) {
  BlenderOptions options;
  options.timeoutSeconds = timeoutSeconds;
  options.seed = seed;
  return options;
}

BlenderFrames blenderFrames(const Scene& scene, const std::vector<RobotPose>& poses, const RenderSettings& settings,
                            const PathConvergenceOptions& o, int seed) {
  return renderWithBlenderTimed(scene, std::vector<CameraPlacement>(poses.begin(), poses.end()), settings,
                                blenderOptions(o.blenderTimeoutSeconds, seed));
}

// Cycles' frames of one scene cost minutes each: they are kept in outDir/data/ with what they
// were rendered from (the scene's SHA-256, the poses, size, spp, seed, denoising), and a run that
// asks for the same frames reads them back instead of rendering them again (the fast renderer's
// side is always rendered). Seconds are a frame's in the session (BlenderTimings).
struct CyclesFrames {
  std::vector<ImageRGBA> frames;
  double secondsPerFrame = 0.0, startupSeconds = 0.0;
};

}  // namespace

nlohmann::json cyclesFramesKey(const Scene& scene, const std::vector<RobotPose>& poses, const RenderSettings& settings,
                               int seed) {
  nlohmann::json key = {{"scene_sha256", scene.sha256}, {"size", settings.rig.imageWidth()}, {"spp", settings.spp},
                        {"seed", seed}, {"denoise", settings.denoise}, {"shading", shadingName(settings.shading)},
                        {"poses", nlohmann::json::array()}};
  for (const RobotPose& p : poses) key["poses"].push_back({p.x, p.y, p.yawDeg});
  // A scene is also the files it reads (a texture changed under its name is another scene).
  if (!scene.inputDigests.empty()) key["scene_inputs"] = sceneInputsToJson(scene.inputDigests);
  // What Cycles is given (the job's files for a robot at the origin, the driver's bytes): a changed
  // exporter or driver (the linear textures of 2026-12) renders anew.
  key["blender_job_sha256"] = blenderJobDigest(scene, CameraPlacement(RobotPose{}), settings, blenderOptions(0.0, seed));
  return key;
}

namespace {

CyclesFrames cachedBlenderFrames(const Scene& scene, const std::string& stem, const std::vector<RobotPose>& poses,
                                 const RenderSettings& settings, const PathConvergenceOptions& o, int seed) {
  const fs::path data = fs::path(o.outDir) / "data";
  const std::string name = stem + "_cycles_" + std::to_string(settings.spp) + "spp" + (settings.denoise ? "_denoised" : "") +
                           "_seed" + std::to_string(seed);
  const nlohmann::json key = cyclesFramesKey(scene, poses, settings, seed);
  const fs::path keyFile = data / (name + ".json");
  const auto frameFile = [&](size_t k) { return data / (name + "_" + std::to_string(k) + ".exr"); };
  // Only plain files are read back: a link planted in the folder is not followed.
  const auto plainFile = [](const fs::path& path) { return fs::is_regular_file(fs::symlink_status(path)); };
  bool complete = plainFile(keyFile);
  for (size_t k = 0; k < poses.size(); ++k) complete = complete && plainFile(frameFile(k));
  if (complete) {
    try {
      std::ifstream in(keyFile);
      const nlohmann::json kept = nlohmann::json::parse(in);
      if (kept.at("key") == key) {
        // Frames kept before Cycles was timed per frame of its session (#48) are reused; their
        // seconds, a session over its frames, are not this run's measure: shown as unknown (0).
        const bool timedPerFrame = kept.contains("startup_seconds");
        CyclesFrames cached{{}, timedPerFrame ? kept.at("seconds_per_frame").get<double>() : 0.0,
                            timedPerFrame ? kept.at("startup_seconds").get<double>() : 0.0};
        for (size_t k = 0; k < poses.size(); ++k) cached.frames.push_back(readImage(frameFile(k).string()));
        return cached;
      }
    } catch (const std::exception&) {
      // Unreadable or another run's: rendered again below.
    }
  }
  // The key goes before the frames are replaced, and comes back after them: a run stopped between
  // leaves no key over frames of another.
  std::error_code ec;
  fs::remove(keyFile, ec);
  BlenderFrames session = blenderFrames(scene, poses, settings, o, seed);
  CyclesFrames rendered{std::move(session.images), session.timings.batchedFrameSeconds(), session.timings.startupSeconds()};
  for (size_t k = 0; k < poses.size(); ++k) writeImageAtomic(frameFile(k).string(), rendered.frames[k]);
  writeTextAtomically(keyFile.string(), nlohmann::json{{"key", key},
                                                       {"seconds_per_frame", rendered.secondsPerFrame},
                                                       {"startup_seconds", rendered.startupSeconds}}
                                                .dump(2) + "\n");
  return rendered;
}

std::vector<StudyScene> studyScenes(const PathConvergenceOptions& o) {
  const fs::path scenes = fs::path(o.outDir) / "scenes";
  std::vector<StudyScene> out;
  HallOptions hall;
  hall.fieldScene = o.fieldScene;
  writeHallArena(hall, (scenes / "hall_plain.json").string());
  hall.photos = {o.labPhoto};
  writeHallArena(hall, (scenes / "hall_textured.json").string());
  out.push_back({"plain hall", loadScene((scenes / "hall_plain.json").string()), hallPoses()});
  out.push_back({"textured hall", loadScene((scenes / "hall_textured.json").string()), hallPoses()});
  out.push_back({"tiled room", loadScene(o.tiledRoom), {{0.0, 0.0, 0.0}, {0.8, -0.5, 45.0}, {-1.0, 0.7, 200.0}}});
  return out;
}

void saveFrame(const fs::path& folder, const std::string& name, const ImageRGBA& image) {
  writeImageAtomic((folder / name).string(), image);
}

std::string fileStem(const std::string& scene) {
  std::string stem = scene;
  std::replace(stem.begin(), stem.end(), ' ', '_');
  return stem;
}

}  // namespace

std::vector<RobotPose> hallPoses() { return {{2.7, -1.8, 180.0}, {0.0, 0.0, 30.0}, {-1.5, 1.0, -60.0}}; }

ImageRGBA convergedFastFrame(const Scene& scene, const RobotPose& pose, int size, int spp, int seeds) {
  const FastRenderer renderer(scene);
  return meanOf(fastSeeds(renderer, pose, pathSettings(scene, size, spp, false), seeds));
}

namespace {

// Seconds at which a ladder (ascending spp) first reaches `target` dB, log-linear in seconds
// between the rungs around it; 0 when it never does.
double secondsToReach(const std::vector<LadderPoint>& ladder, const std::string& engine, double target) {
  const LadderPoint* previous = nullptr;
  for (const LadderPoint& p : ladder) {
    if (p.engine != engine || !p.filtered) continue;
    if (p.psnrDb >= target) {
      if (!previous || previous->psnrDb >= target) return p.seconds;
      const double t = (target - previous->psnrDb) / (p.psnrDb - previous->psnrDb);
      return std::exp(std::log(previous->seconds) + t * (std::log(p.seconds) - std::log(previous->seconds)));
    }
    previous = &p;
  }
  return 0.0;
}

}  // namespace

void measureTimeToError(const Scene& scene, const std::vector<RobotPose>& poses, const ImageRGBA& converged,
                        const PathConvergenceOptions& o, PathConvergenceResults& r, const ExperimentProgress& progress) {
  const FastRenderer renderer(scene);
  const std::vector<CameraPlacement> placements(poses.begin(), poses.end());
  int done = 0;
  const int total = static_cast<int>(2 * o.fastLadder.size() + o.cyclesLadder.size());
  for (int spp : o.fastLadder)
    for (bool filtered : {false, true}) {
      const RenderSettings settings = pathSettings(scene, o.size, spp, filtered, 77);
      renderer.render(placements.back(), settings);  // warm: the sample table is built once per spp
      ImageRGBA first;
      const auto start = Clock::now();
      for (const CameraPlacement& placement : placements) {
        ImageRGBA frame = renderer.render(placement, settings);
        if (first.pixels.empty()) first = std::move(frame);
      }
      const double perFrame = secondsSince(start) / static_cast<double>(placements.size());
      r.ladder.push_back({"fast", spp, filtered, perFrame, measureRenderNoise(first, converged).psnrDb, 0.0});
      progress("time to error", ++done, total);
    }
  for (int spp : o.cyclesLadder) {
    const BlenderFrames session = blenderFrames(scene, poses, pathSettings(scene, o.size, spp, true), o, 77);
    r.ladder.push_back({"blender", spp, true, session.timings.batchedFrameSeconds(),
                        measureRenderNoise(session.images.front(), converged).psnrDb, session.timings.startupSeconds()});
    progress("time to error", ++done, total);
  }
  for (double target : {35.0, 38.0, 40.0})
    r.timeToError.push_back({target, secondsToReach(r.ladder, "fast", target), secondsToReach(r.ladder, "blender", target)});
}

PathConvergenceResults runPathConvergence(const PathConvergenceOptions& o, const ExperimentProgress& progress) {
  if (o.size < 16 || o.referenceSpp < 1 || o.fastConvergedSpp < 1 || o.fastConvergedSeeds < 1 || o.chosenSpp < 1 ||
      o.cyclesSpp < 1)
    throw InputError("path convergence: size >= 16 and every spp and seed count >= 1");
  const auto started = Clock::now();
  PathConvergenceResults r;
  r.options = o;
  // Its folders are made without following a link planted there: what it writes stays inside.
  makeAllFoldersInside(o.outDir, {"data", "scenes", "frames"});
  const std::vector<StudyScene> scenes = studyScenes(o);
  const int total = static_cast<int>(scenes.size() * 3);
  int done = 0;
  for (const StudyScene& s : scenes) {
    const FastRenderer renderer(s.scene);
    // Cycles: the converged references of the three poses in one session, and the realistic
    // frames' setup (filtered) timed per session of three.
    const std::string stem = fileStem(s.name);
    const std::vector<ImageRGBA> references =
        cachedBlenderFrames(s.scene, stem, s.poses, pathSettings(s.scene, o.size, o.referenceSpp, false), o, 0).frames;
    std::vector<ImageRGBA> floors;
    if (o.measureFloor && (o.floorScene.empty() || o.floorScene == s.name))
      floors = cachedBlenderFrames(s.scene, stem, s.poses, pathSettings(s.scene, o.size, o.referenceSpp, false), o, 1).frames;
    const CyclesFrames realistic = cachedBlenderFrames(s.scene, stem, s.poses, pathSettings(s.scene, o.size, o.cyclesSpp, true), o, 5);
    const std::vector<ImageRGBA>& cycles = realistic.frames;
    const double cyclesSeconds = realistic.secondsPerFrame;
    for (size_t k = 0; k < s.poses.size(); ++k) {
      PathFrameResult f;
      f.scene = s.name;
      f.pose = s.poses[k];
      const std::vector<ImageRGBA> seeds =
          fastSeeds(renderer, f.pose, pathSettings(s.scene, o.size, o.fastConvergedSpp, false), o.fastConvergedSeeds);
      const ImageRGBA converged = meanOf(seeds);
      const ImageRGBA filtered = renderer.render(f.pose, pathSettings(s.scene, o.size, o.fastConvergedSpp, true, 7));
      const RenderSettings chosenSettings = pathSettings(s.scene, o.size, o.chosenSpp, true);
      renderer.render(f.pose, chosenSettings);  // warm: the sample table
      const auto chosenStart = Clock::now();
      const ImageRGBA chosen = renderer.render(f.pose, chosenSettings);
      f.chosenSeconds = secondsSince(chosenStart);
      f.convergedPsnrDb = measureRenderNoise(converged, references[k]).psnrDb;
      // Two frames of independent noise σ² differ by 2σ²; the mean of n seeds has σ²/n.
      const double referenceNoise =
          floors.empty() ? 0.0 : squaredLevels(measureRenderNoise(floors[k], references[k]).psnrDb) / 2.0;
      const double fastNoise =
          seeds.size() < 2 ? 0.0 : squaredLevels(measureRenderNoise(seeds[0], seeds[1]).psnrDb) / 2.0 / seeds.size();
      if (referenceNoise > 0.0) f.referenceNoiseDb = psnrOf(referenceNoise);
      if (fastNoise > 0.0) f.fastNoiseDb = psnrOf(fastNoise);
      // Only where both noises were measured: otherwise what is left still holds the other's noise.
      if (referenceNoise > 0.0 && fastNoise > 0.0)
        f.disagreementDb = psnrOf(std::max(0.0, squaredLevels(f.convergedPsnrDb) - referenceNoise - fastNoise));
      f.filterBiasPsnrDb = measureRenderNoise(filtered, converged).psnrDb;
      f.chosenPsnrDb = measureRenderNoise(chosen, references[k]).psnrDb;
      f.cyclesPsnrDb = measureRenderNoise(cycles[k], references[k]).psnrDb;
      f.cyclesSeconds = cyclesSeconds;
      f.cyclesStartupSeconds = realistic.startupSeconds;
      f.meanRatio = meanInside(converged, references[k]) / meanInside(references[k], references[k]);
      r.frames.push_back(f);
      if (k == 0) {
        const fs::path frames = fs::path(o.outDir) / "frames";
        saveFrame(frames, stem + "_cycles_converged.png", references[k]);
        saveFrame(frames, stem + "_fast_converged.png", converged);
        saveFrame(frames, stem + "_fast_dataset.png", chosen);
        saveFrame(frames, stem + "_cycles_realistic.png", cycles[k]);
        if (s.name == "textured hall") measureTimeToError(s.scene, s.poses, converged, o, r, progress);
      }
      progress("frames", ++done, total);
    }
  }
  r.seconds = secondsSince(started);
  writeTextAtomically((fs::path(o.outDir) / "path-convergence.json").string(), pathConvergenceJson(r).dump(2) + "\n");
  return r;
}

nlohmann::json pathConvergenceJson(const PathConvergenceResults& r) {
  nlohmann::json frames = nlohmann::json::array(), ladder = nlohmann::json::array(), times = nlohmann::json::array();
  for (const PathFrameResult& f : r.frames)
    frames.push_back({{"scene", f.scene},
                      {"pose", {f.pose.x, f.pose.y, f.pose.yawDeg}},
                      {"converged_psnr_db", f.convergedPsnrDb},
                      {"reference_noise_db", f.referenceNoiseDb},
                      {"fast_noise_db", f.fastNoiseDb},
                      {"disagreement_db", f.disagreementDb},
                      {"filter_bias_psnr_db", f.filterBiasPsnrDb},
                      {"dataset_frame_psnr_db", f.chosenPsnrDb},
                      {"dataset_frame_seconds", f.chosenSeconds},
                      {"cycles_realistic_psnr_db", f.cyclesPsnrDb},
                      {"cycles_realistic_seconds", f.cyclesSeconds},
                      {"cycles_startup_seconds", f.cyclesStartupSeconds},
                      {"mean_ratio", f.meanRatio}});
  for (const LadderPoint& p : r.ladder)
    ladder.push_back({{"engine", p.engine}, {"spp", p.spp}, {"filtered", p.filtered}, {"seconds", p.seconds},
                      {"startup_seconds", p.startupSeconds}, {"psnr_db", p.psnrDb}});
  for (const auto& t : r.timeToError)
    times.push_back({{"target_db", t.targetDb}, {"fast_seconds", t.fastSeconds}, {"blender_seconds", t.cyclesSeconds}});
  const PathConvergenceOptions& o = r.options;
  return {{"size", o.size},
          {"reference_spp", o.referenceSpp},
          {"fast_converged_spp", o.fastConvergedSpp * o.fastConvergedSeeds},
          {"dataset_spp", o.chosenSpp},
          {"cycles_realistic_spp", o.cyclesSpp},
          {"frames", frames},
          {"ladder", ladder},
          {"time_to_error", times},
          {"seconds", r.seconds}};
}

std::string pathConvergenceMarkdown(const PathConvergenceResults& r, const std::string& command) {
  const PathConvergenceOptions& o = r.options;
  std::ostringstream md;
  md << "## Measured\n\n<!-- Generated by `" << command << "`; do not edit by hand. -->\n\n"
     << o.size << "×" << o.size << " px; PSNR in 8-bit sRGB inside the mirror disc (experiments/render_noise.h). "
     << "Cycles reference: " << o.referenceSpp << " spp, unfiltered. Converged fast frame: "
     << o.fastConvergedSpp * o.fastConvergedSeeds << " spp, unfiltered. Dataset frame: fast, " << o.chosenSpp
     << " spp, denoised. Cycles realistic frame: " << o.cyclesSpp << " spp, denoised (the texture-realism experiment's). "
     << "Took " << fixedDecimals(r.seconds / 60.0, 0) << " min.\n\n"
     << "| scene | pose | converged fast vs Cycles dB | Cycles' own noise dB | fast's own noise dB | disagreement dB | "
        "mean ratio | filter bias dB | dataset frame dB | its s | Cycles realistic dB | its s | Cycles start-up s |\n"
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  const auto orDash = [](double v) { return v > 0.0 ? fixedDecimals(v, 2) : std::string("–"); };
  for (const PathFrameResult& f : r.frames)
    md << "| " << f.scene << " | (" << fixedDecimals(f.pose.x, 1) << ", " << fixedDecimals(f.pose.y, 1) << ", " << fixedDecimals(f.pose.yawDeg, 0)
       << "°) | " << fixedDecimals(f.convergedPsnrDb, 2) << " | " << orDash(f.referenceNoiseDb) << " | " << orDash(f.fastNoiseDb)
       << " | " << (f.disagreementDb >= 99.0 ? std::string("within the noise") : orDash(f.disagreementDb))
       << " | " << fixedDecimals(f.meanRatio, 4) << " | " << fixedDecimals(f.filterBiasPsnrDb, 2) << " | " << fixedDecimals(f.chosenPsnrDb, 2)
       << " | " << fixedDecimals(f.chosenSeconds, 3) << " | " << fixedDecimals(f.cyclesPsnrDb, 2) << " | " << orDash(f.cyclesSeconds) << " | " << orDash(f.cyclesStartupSeconds)
       << " |\n";
  md << "\nOwn noise: a frame's PSNR against its own converged frame, from the difference of two frames of "
        "other seeds (two frames of noise σ² differ by 2σ²). Disagreement: the squared difference of the converged "
        "frames less both frames' own noise, as a PSNR — what the engines disagree on beyond the noise. The filter "
        "bias: the fast frame denoised at "
     << o.fastConvergedSpp << " spp against the unfiltered converged one.\n\n"
     << "Time to error (textured hall, first pose, against the converged fast frame; one run, one engine after the "
        "other; seconds per frame of a sequence of the scene's poses, as a dataset renders them: the fast renderer's "
        "after a warm-up frame, Cycles' after the first frame of one Blender session, whose start-up — Blender's, the "
        "glTF import, the scene's set-up — is its own column):\n\n"
        "| engine | spp | denoised | seconds per frame | start-up s | PSNR dB |\n|---|---:|---|---:|---:|---:|\n";
  for (const LadderPoint& p : r.ladder)
    md << "| " << p.engine << " | " << p.spp << " | " << (p.filtered ? "yes" : "no") << " | " << fixedDecimals(p.seconds, 3)
       << " | " << (p.engine == "fast" ? std::string("–") : fixedDecimals(p.startupSeconds, 1)) << " | "
       << fixedDecimals(p.psnrDb, 2) << " |\n";
  md << "\n| target dB | fast s per frame | Cycles s per frame | ratio |\n|---:|---:|---:|---:|\n";
  for (const auto& t : r.timeToError)
    md << "| " << fixedDecimals(t.targetDb, 0) << " | " << (t.fastSeconds > 0 ? fixedDecimals(t.fastSeconds, 3) : "not reached") << " | "
       << (t.cyclesSeconds > 0 ? fixedDecimals(t.cyclesSeconds, 1) : "not reached") << " | "
       << (t.fastSeconds > 0 && t.cyclesSeconds > 0 ? fixedDecimals(t.cyclesSeconds / t.fastSeconds, 0) + "×" : "–") << " |\n";
  return md.str();
}

}  // namespace omnicam
