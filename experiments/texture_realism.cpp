#include "texture_realism.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <opencv2/imgproc.hpp>
#include <random>
#include <sstream>

#include "atomic_file.h"
#include "cycles_frame_cache.h"
#include "engines.h"
#include "errors.h"
#include "fast_renderer.h"
#include "footprint_detector.h"
#include "frame_sequence.h"
#include "hall_arena.h"
#include "landmark_annotations.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "statistics.h"
#include "texture_realism_frames.h"
#include "texture_realism_report.h"

namespace omnicam {

namespace fs = std::filesystem;
using namespace texture_realism;  // its frames: rendered, trained on, scored

TextureRealismOptions TextureRealismOptions::quick() {
  TextureRealismOptions o;
  o.size = 360;
  o.spp = 4;
  o.realistic.spp = 4;
  o.testStride = 25;
  o.trainFrames = 6;
  o.randomHalls = 2;
  o.pathSpp = 4;
  o.recordingDraws = 2;
  o.reduced = true;
  return o;
}

std::vector<PresetFold> presetFolds(const RecordingCameraSpec& mix) {
  if (!mix.preset || mix.preset->kind != ParameterDraw::Kind::Choice || mix.preset->values.size() < 2)
    throw std::logic_error("texture-realism: the training cameras do not draw one of several presets");
  std::vector<PresetFold> folds;
  for (size_t p = 0; p < mix.preset->values.size(); ++p) {
    PresetFold fold{mix, mix};
    fold.training.preset->values.erase(fold.training.preset->values.begin() + static_cast<std::ptrdiff_t>(p));
    fold.validation.preset->values = {mix.preset->values[p]};
    folds.push_back(std::move(fold));
  }
  return folds;
}

RecordingCameraSpec trainingRecordingMix(uint64_t seed) {
  RecordingCameraSpec spec;
  spec.preset = ParameterDraw{ParameterDraw::Kind::Choice, 0, 0, {}};
  for (size_t k = 0; k < recordingPresetNames().size(); ++k) spec.preset->values.push_back(static_cast<double>(k));
  spec.seed = seed;
  return spec;
}

namespace {

// The plain, textured and random-photo halls of the run, in its arenas/ folder.
void writeArenas(const TextureRealismOptions& o, const fs::path& out) {
  HallOptions hall;
  hall.fieldScene = o.fieldScene;
  hall.lampDiameter = o.realistic.lampDiameter;
  writeHallArena(hall, (out / "arenas/hall-plain.json").string());
  hall.photos = {o.labPhoto};
  writeHallArena(hall, (out / "arenas/hall-textured.json").string());
  hall.photos = o.randomPhotos;
  hall.randomPhotos = true;
  for (int k = 0; k < o.randomHalls; ++k) {
    hall.seed = o.seed + 1000 + static_cast<uint64_t>(k);
    writeHallArena(hall, (out / ("arenas/hall-random-" + std::to_string(k) + ".json")).string());
  }
}

using Classifiers = std::map<std::string, std::map<std::string, ColourHistogramClassifier>>;

// A new training set's classifiers, one per beacon colour, untrained.
std::map<std::string, ColourHistogramClassifier>& freshClassifiers(Classifiers& trained, const std::string& set, int bins) {
  auto& classifiers = trained[set];
  for (const char* colour : {"cyan", "magenta", "yellow"}) classifiers.emplace(colour, ColourHistogramClassifier(bins));
  return classifiers;
}

// Train sets (plain; random_textures, spread over the random halls): labels from the fast
// renderer's instance masks.
std::string testCameraSet(size_t k) { return "realistic_camera_" + std::to_string(k + 1); }

// Frames as `recording` records them (frame k drawn and seeded with index k), masks and poses kept.
std::vector<Frame> recordedFrames(const std::vector<Frame>& frames, const std::vector<ImageRGBA>& linear,
                                  const RecordingCameraSpec& recording) {
  std::vector<Frame> recorded;
  for (size_t k = 0; k < frames.size(); ++k)
    recorded.push_back({frames[k].pose, recordFrame(recording.draw(k), linear[k], k), frames[k].instance});
  return recorded;
}

// Which drawn camera records a frame: training frame k's d-th draw is k × draws + d; the figure's
// and the validation frames' draws start far above any training draw.
constexpr uint64_t kFigureDraws = 1000000, kValidationDraws = 2000000;
uint64_t drawIndex(uint64_t first, size_t frame, int draw, int draws) {
  return first + frame * static_cast<uint64_t>(draws) + static_cast<uint64_t>(draw);
}

// Trains `classifiers` on `frames`, each recorded o.recordingDraws times through a camera drawn
// from `recording` (draw index frame × draws + d), with `neutralStage` (if any) held neutral, the
// detector's input filtered as `detector` says: one recorded frame in memory at a time.
void trainOnRecorded(std::map<std::string, ColourHistogramClassifier>& classifiers, const std::vector<Frame>& frames,
                     const RecordingCameraSpec& recording, const TextureRealismOptions& o, const std::string& neutralStage,
                     const std::vector<std::string>& bandColour, const DetectorOptions& detector) {
  for (size_t k = 0; k < frames.size(); ++k)
    for (int d = 0; d < o.recordingDraws; ++d) {
      const uint64_t index = drawIndex(0, k, d, o.recordingDraws);
      RecordingCamera camera = recording.draw(index);
      if (!neutralStage.empty()) camera = withStageNeutral(camera, neutralStage);
      trainOn(classifiers, {Frame{frames[k].pose, recordFrame(camera, frames[k].image, index), frames[k].instance}}, bandColour, detector);
    }
}

// The training sets' names: path and plain frames recorded through drawn cameras, and the ablation's
// sets (one stage held neutral each).
std::string recordedSet(const std::string& frames) { return frames + "_recorded"; }
std::string ablationSet(const std::string& stage) { return "path_recorded_without_" + stage; }

// The frames every training set is trained on, rendered once: the pixel detector's sets and the
// footprint detector's (whose input filter validation may choose otherwise) train on the same.
struct TrainingFrames {
  std::vector<Frame> plain;
  std::vector<std::vector<Frame>> randomHalls;  // one share of the random poses per random hall
  std::vector<Frame> path;
  std::vector<Frame> realistic;  // Cycles' frames at the path frames' poses, through the webcam
};

TrainingFrames renderTrainingFrames(const TextureRealismOptions& o, const fs::path& out, const Scene& plain,
                                    const Scene& textured, const std::function<void()>& step, CyclesCount& cycles) {
  TrainingFrames frames;
  // plain and random_textures keep the poses they always had; path and realistic share theirs.
  frames.plain = renderFast(plain, randomFieldPoses(o.trainFrames, o.seed + 1), o.size, o.spp, step);
  const std::vector<RobotPose> randomPoses = randomFieldPoses(o.trainFrames, o.seed + 2);
  for (int k = 0; k < o.randomHalls; ++k) {
    std::vector<RobotPose> share;
    for (size_t p = static_cast<size_t>(k); p < randomPoses.size(); p += static_cast<size_t>(o.randomHalls)) share.push_back(randomPoses[p]);
    const Scene scene = loadScene((out / ("arenas/hall-random-" + std::to_string(k) + ".json")).string());
    frames.randomHalls.push_back(renderFast(scene, share, o.size, o.spp, step));
  }
  const std::vector<RobotPose> sharedPoses = randomFieldPoses(o.trainFrames, o.seed + 3);
  frames.path = renderFast(textured, sharedPoses, o.size, o.pathSpp, step, Shading::Path);
  const std::vector<Frame> masks = renderFast(textured, sharedPoses, o.size, 1, [] {});
  std::vector<RobotPose> poses;
  for (const Frame& mask : masks) poses.push_back(mask.pose);
  frames.realistic = recordedFrames(masks, cyclesFrames(o, textured, poses, step, cycles), fixedRecordingCameraSpec(o.recording));
  return frames;
}

// Every training set, its classifiers trained with the detector's input filtered as `detector`
// says; `step` after the recorded sets and after each ablation set.
Classifiers trainSets(const TrainingFrames& frames, const TextureRealismOptions& o, const DetectorOptions& detector,
                      const std::vector<std::string>& bandColour, const std::function<void()>& step) {
  Classifiers trained;
  auto fresh = [&](const std::string& set) -> std::map<std::string, ColourHistogramClassifier>& {
    return freshClassifiers(trained, set, o.bins);
  };
  trainOn(fresh("plain"), frames.plain, bandColour, detector);
  auto& randomTextures = fresh("random_textures");
  for (const std::vector<Frame>& hall : frames.randomHalls) trainOn(randomTextures, hall, bandColour, detector);
  trainOn(fresh("path"), frames.path, bandColour, detector);
  trainOn(fresh("realistic"), frames.realistic, bandColour, detector);
  // Domain randomisation of the camera: path and plain frames through drawn cameras, and the ablation.
  trainOnRecorded(fresh(recordedSet("path")), frames.path, o.trainingRecording, o, "", bandColour, detector);
  trainOnRecorded(fresh(recordedSet("plain")), frames.plain, o.trainingRecording, o, "", bandColour, detector);
  step();
  if (o.ablation)
    for (const std::string& stage : recordingStages()) {
      trainOnRecorded(fresh(ablationSet(stage)), frames.path, o.trainingRecording, o, stage, bandColour, detector);
      step();
    }
  return trained;
}

// The detector's options with its input filtered by a median of `medianPx` pixels a side.
DetectorOptions withMedian(DetectorOptions detector, int medianPx) {
  detector.medianPx = medianPx;
  return detector;
}

// The median filters validation tries for the footprint detector (pixels a side; 1: none), fewest
// first: none, 3 × 3 — which takes most of a pixel's noise off its colour and keeps a band two
// pixels tall — and the one the pixel detector was given. A camera noisier than any in training
// scatters unfiltered colours beyond what the histograms saw; whether filtering pays for the
// thin bands it blurs is for validation to tell.
std::vector<int> footprintMedians(const DetectorOptions& detector) {
  std::vector<int> medians = {1, 3, detector.medianPx};
  std::sort(medians.begin(), medians.end());
  medians.erase(std::unique(medians.begin(), medians.end()), medians.end());
  return medians;
}

// One fold of leave-one-preset-out validation: the path frames' classifiers through its training
// cameras, one set per median filter tried, beside the cameras its validation frames are recorded
// through.
struct ValidationFold {
  std::map<int, std::map<std::string, ColourHistogramClassifier>> classifiersByMedian;
  RecordingCameraSpec validation;
};

std::vector<ValidationFold> trainFolds(const TextureRealismOptions& o, const std::vector<Frame>& pathFrames,
                                       const std::vector<PresetFold>& folds, const std::vector<std::string>& bandColour,
                                       const std::function<void()>& step) {
  std::vector<ValidationFold> trained;
  for (const PresetFold& fold : folds) {
    ValidationFold v{{}, fold.validation};
    for (const int median : footprintMedians(o.detector)) {
      Classifiers unnamed;
      auto& classifiers = freshClassifiers(unnamed, "", o.bins);
      trainOnRecorded(classifiers, pathFrames, fold.training, o, "", bandColour, withMedian(o.detector, median));
      v.classifiersByMedian.emplace(median, std::move(classifiers));
    }
    trained.push_back(std::move(v));
    step();
  }
  return trained;
}

// Test sets along thesis-loop: plain and textured by the fast renderer, realistic by Blender (one
// session per batch of poses) on the textured hall, whose instance masks hold for them too, through
// the webcam and through each test camera (realistic_camera_1, …).
std::map<std::string, std::vector<Frame>> renderTestSets(const TextureRealismOptions& o, const Scene& plain, const Scene& textured,
                                                         const std::vector<RobotPose>& testPoses,
                                                         const std::function<void()>& step, CyclesCount& cycles) {
  std::map<std::string, std::vector<Frame>> tests;
  tests["plain"] = renderFast(plain, testPoses, o.size, o.spp, step);
  tests["textured"] = renderFast(textured, testPoses, o.size, o.spp, step);
  tests["path"] = renderFast(textured, testPoses, o.size, o.pathSpp, step, Shading::Path);
  const std::vector<ImageRGBA> linear = cyclesFrames(o, textured, testPoses, step, cycles);
  tests["realistic"] = recordedFrames(tests["textured"], linear, fixedRecordingCameraSpec(o.recording));
  for (size_t k = 0; k < o.testCameras.size(); ++k)
    tests[testCameraSet(k)] = recordedFrames(tests["textured"], linear, o.testCameras[k].recording);
  return tests;
}

// A condition's totals, its most frequent false-positive sources, its EKF runs (one per drive) and its example
// frame (the one with the most visible beacons, first of them), from its frames' evaluations.
void summariseCondition(ConditionReport& condition, const std::vector<Frame>& frames, const std::vector<Drive>& drives,
                        int testStride) {
  ConditionOutcome& c = condition.outcome;
  std::vector<double> pixels, ranges, bearings;
  for (const FrameEvaluation& f : condition.frames) {
    c.truePositives += f.truePositives;
    c.falsePositiveBlobs += f.falsePositiveBlobs;
    c.offBandBandsOfFoundBeacons += f.offBandBandsOfFoundBeacons;
    c.falsePositives += f.falsePositives();
    c.missed += f.visibleBeacons - f.truePositives;
    for (const double range : f.visibleRangesM) ++c.visibleByRange[static_cast<size_t>(rangeBucket(range))];
    for (const double range : f.foundRangesM) ++c.truePositivesByRange[static_cast<size_t>(rangeBucket(range))];
    pixels.insert(pixels.end(), f.localisationErrorsPx.begin(), f.localisationErrorsPx.end());
    ranges.insert(ranges.end(), f.rangeErrorsCm.begin(), f.rangeErrorsCm.end());
    bearings.insert(bearings.end(), f.bearingErrorsDeg.begin(), f.bearingErrorsDeg.end());
  }
  std::map<std::string, int> sources;
  for (const FrameEvaluation& f : condition.frames)
    for (const FalseBlob& b : f.falseBlobs) {
      ++sources[b.object.empty() ? "(nothing)" : b.object];
      c.falsePositiveBlobsOnHall += b.object.starts_with("hall_");
    }
  c.falsePositiveSources.assign(sources.begin(), sources.end());
  std::sort(c.falsePositiveSources.begin(), c.falsePositiveSources.end(),
            [](auto& a, auto& b) { return a.second != b.second ? a.second > b.second : a.first < b.first; });
  if (c.falsePositiveSources.size() > 5) c.falsePositiveSources.resize(5);
  c.frames = static_cast<int>(frames.size());
  c.meanLocalisationErrorPx = meanOf(pixels);
  c.meanRangeErrorCm = meanOf(ranges);
  c.medianRangeErrorCm = medianOf(ranges);
  c.meanBearingErrorDeg = meanOf(bearings);
  const size_t stride = static_cast<size_t>(testStride);
  condition.ekf = runEkfOnDrives(drives, [&](size_t k) -> const std::vector<Measurement>* {
    return k % stride == 0 && k / stride < condition.frames.size() ? &condition.frames[k / stride].measurements : nullptr;
  });
  size_t example = 0;
  for (size_t k = 0; k < condition.frames.size(); ++k)
    if (condition.frames[k].visibleBeacons > condition.frames[example].visibleBeacons) example = k;
  condition.exampleFrame = example;
  condition.exampleImage = frames[example].image;
}

constexpr const char* kOracleSet = "realistic_test_frames";

// The validation frames that choose the footprint detector's setting: path frames at poses no
// training frame has. tryFootprintSettings records each through every fold's held-out preset, at
// draws no training frame (nor the figure) uses; no test camera is seen.
std::vector<Frame> validationFrames(const TextureRealismOptions& o, const Scene& textured, const std::function<void()>& step) {
  return renderFast(textured, randomFieldPoses(o.trainFrames, o.seed + 4), o.size, o.pathSpp, step, Shading::Path);
}

// One training set's classifiers at `bins` per channel (coarsened from the trained ones).
std::map<std::string, ColourHistogramClassifier> coarsenedSet(const std::map<std::string, ColourHistogramClassifier>& set, int bins) {
  std::map<std::string, ColourHistogramClassifier> out;
  for (const auto& [colour, classifier] : set) out.emplace(colour, classifier.coarsened(bins));
  return out;
}

// The coarsest colour resolution validation tries for the footprint detector, and the band
// tolerances it tries (FootprintRule; in units of log likelihood ratio, the evidence clamped to ±5).
constexpr int kSmallestFootprintBins = 8;
constexpr double kBandTolerances[] = {0.0, 1.0, 2.0};

// What scoring a frame needs besides the detections.
struct Scoring {
  const std::vector<std::string>& bandColour;
  const std::vector<std::string>& objectNames;
  double matchRadiusPx;
};

// Every setting validation tries: each median filter, fewest pixels first; within it each colour
// resolution from the trained one down, finest first; within that each score, then each band
// tolerance.
std::vector<FootprintTrial> footprintSettings(int bins, const std::vector<int>& medians) {
  std::vector<FootprintTrial> trials;
  for (const int median : medians)
    for (const int b : resolutionAndHalvings(bins, kSmallestFootprintBins))
      for (const FootprintScore score : footprintScores())
        for (const double tolerance : kBandTolerances) {
          trials.push_back({});
          trials.back().medianPx = median;
          trials.back().bins = b;
          trials.back().rule = {score, tolerance};
        }
  return trials;
}

// The footprint detector's setting, by leave-one-preset-out validation (presetFolds): in each fold
// every validation frame is recorded o.recordingDraws times through the fold's validation cameras
// and detected by every setting with the fold's classifiers (trained through the same median
// filter), one recorded frame in memory at a time (its evidence computed once per filter and
// colour resolution). Each trial sums over the folds.
std::vector<FootprintTrial> tryFootprintSettings(const TextureRealismOptions& o, const std::vector<ValidationFold>& folds,
                                                 const std::vector<Frame>& validation,
                                                 const std::vector<std::vector<GroundTruthBeacon>>& truth,
                                                 const FootprintDetector& detector, const Scoring& s,
                                                 const ExperimentProgress& progress) {
  std::vector<FootprintTrial> trials = footprintSettings(o.bins, footprintMedians(o.detector));
  using ByBins = std::map<int, std::map<std::string, ColourHistogramClassifier>>;
  std::vector<std::map<int, ByBins>> classifiers(folds.size());  // by fold, median, bins
  for (size_t fold = 0; fold < folds.size(); ++fold)
    for (const auto& [median, trained] : folds[fold].classifiersByMedian)
      for (const int bins : resolutionAndHalvings(o.bins, kSmallestFootprintBins))
        classifiers[fold][median][bins] = coarsenedSet(trained, bins);
  for (size_t k = 0; k < validation.size(); ++k) {
    for (size_t fold = 0; fold < folds.size(); ++fold)
      for (int d = 0; d < o.recordingDraws; ++d) {
        const uint64_t index = drawIndex(kValidationDraws, k, d, o.recordingDraws);
        const Frame recorded{validation[k].pose, recordFrame(folds[fold].validation.draw(index), validation[k].image, index),
                             validation[k].instance};
        for (const auto& [median, byBins] : classifiers[fold])
          for (const auto& [bins, classifiersAtBins] : byBins) {
            const BandEvidence evidence = detector.evidence(recorded.image, classifiersAtBins, withMedian(o.detector, median));
            for (FootprintTrial& t : trials) {
              if (t.medianPx != median || t.bins != bins) continue;
              const DetectionResult detected = detector.detect(evidence, o.detector.theta, t.rule);
              const FrameEvaluation e = evaluateFrame(recorded, detected, truth[k], s.bandColour, s.objectNames, s.matchRadiusPx);
              t.visibleBeacons += e.visibleBeacons;
              t.truePositives += e.truePositives;
              t.falsePositives += e.falsePositives();
            }
          }
      }
    progress("choosing the footprint detector's filter, colour resolution, score and band tolerance", static_cast<int>(k + 1),
             static_cast<int>(validation.size()));
  }
  return trials;
}

// The best TP − FP; on a tie the first tried: the smaller filter, the finer resolution, the score
// listed first, the smaller tolerance.
const FootprintTrial& chosenSetting(const std::vector<FootprintTrial>& trials) {
  const FootprintTrial* best = &trials.front();
  for (const FootprintTrial& t : trials)
    if (t.validationScore() > best->validationScore()) best = &t;
  return *best;
}

struct ConditionToRun {
  std::string train, test;
  DetectorKind detector;
};

// Every train → test pair the run evaluates: the thesis' and earlier ones, training through drawn
// cameras, the ablation, and each test camera against the training sets that matter for it — by
// the thesis' pixel detector; then the pairs that ask whether frames transfer again by the
// footprint detector. realistic → realistic (trained on the test camera's own frames, at other
// poses) and the oracle (trained on the test frames themselves) are ceilings on the realistic
// frames, not conditions a user could run.
std::vector<ConditionToRun> conditionsOf(const TextureRealismOptions& o) {
  std::vector<std::pair<std::string, std::string>> thesis = {
      {"plain", "plain"}, {"plain", "textured"}, {"plain", "realistic"}, {"random_textures", "realistic"},
      {"path", "realistic"}, {"realistic", "path"}, {"realistic", "realistic"}, {kOracleSet, "realistic"},
      {recordedSet("path"), "realistic"}, {recordedSet("plain"), "realistic"}};
  std::vector<std::pair<std::string, std::string>> transfer = {
      {"plain", "plain"}, {"plain", "realistic"}, {"path", "realistic"}, {"realistic", "realistic"},
      {kOracleSet, "realistic"}, {recordedSet("path"), "realistic"}, {recordedSet("plain"), "realistic"}};
  std::vector<std::pair<std::string, std::string>> extra;
  if (o.ablation)
    for (const std::string& stage : recordingStages()) extra.emplace_back(ablationSet(stage), "realistic");
  for (size_t k = 0; k < o.testCameras.size(); ++k)
    for (const std::string& train : {std::string("plain"), std::string("path"), recordedSet("path"), recordedSet("plain")})
      extra.emplace_back(train, testCameraSet(k));
  std::vector<ConditionToRun> list;
  for (const auto& [train, test] : thesis) list.push_back({train, test, DetectorKind::Pixels});
  for (const auto& [train, test] : extra) list.push_back({train, test, DetectorKind::Pixels});
  for (const auto& [train, test] : transfer) list.push_back({train, test, DetectorKind::Footprints});
  for (const auto& [train, test] : extra) list.push_back({train, test, DetectorKind::Footprints});
  return list;
}

// The cameras the report shows: the training ranges, the webcam and each test camera's values.
void describeCameras(const TextureRealismOptions& o, TextureRealismResults& results) {
  results.trainingRanges = describeRanges(o.trainingRecording);
  results.testCameras.push_back({"realistic", "webcam (fixed; the realistic frames)", describeValues(o.recording),
                                 parametersBeyond(o.trainingRecording, o.recording)});
  for (size_t k = 0; k < o.testCameras.size(); ++k) {
    const RecordingCameraSpec& camera = o.testCameras[k].recording;
    // A drawn test camera is shown by its ranges; only a fixed one's values can be beyond training's.
    results.testCameras.push_back({testCameraSet(k), "camera " + std::to_string(k + 1) + ": " + fs::path(o.testCameras[k].file).filename().string(),
                                   camera.randomised() ? describeRanges(camera) : describeValues(camera.draw(0)),
                                   camera.randomised() ? std::nullopt : std::optional(parametersBeyond(o.trainingRecording, camera.draw(0)))});
  }
  if (o.ablation) results.ablatedStages = recordingStages();
}

// One test pose side by side, labelled, each panel at most 240 px (the figure the document shows):
// plain, path, path through one drawn training camera, realistic.
ImageRGBA recordingComparison(const TextureRealismOptions& o, const std::map<std::string, std::vector<Frame>>& tests, size_t pose) {
  const ImageRGBA& path = tests.at("path")[pose].image;
  const uint64_t draw = kFigureDraws + pose;  // a draw no training frame used
  const ImageRGBA panels[] = {tests.at("plain")[pose].image, path, recordFrame(o.trainingRecording.draw(draw), path, draw),
                              tests.at("realistic")[pose].image};
  const char* const labels[] = {"plain", "path", "path + drawn camera", "realistic"};
  const int side = std::min(240, path.width);
  cv::Mat strip(side, 4 * side, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int k = 0; k < 4; ++k) {
    cv::Mat codes(path.height, path.width, CV_8UC3);
    for (int j = 0; j < path.height; ++j)
      for (int i = 0; i < path.width; ++i) {
        const Rgb8 code = rgb8FromPixel(panels[k].at(i, j));
        codes.at<cv::Vec3b>(j, i) = cv::Vec3b(code[0], code[1], code[2]);
      }
    cv::Mat panel = strip(cv::Rect(k * side, 0, side, side));
    cv::resize(codes, panel, panel.size(), 0, 0, cv::INTER_AREA);
    cv::putText(panel, labels[k], cv::Point(6, side - 8), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
  ImageRGBA figure(strip.cols, strip.rows);
  for (int j = 0; j < strip.rows; ++j)
    for (int i = 0; i < strip.cols; ++i) {
      float* to = figure.at(i, j);
      for (int c = 0; c < 3; ++c) to[c] = srgbToLinear(strip.at<cv::Vec3b>(j, i)[c] / 255.0f);
      to[3] = 1.0f;
    }
  return figure;
}

// The EKF's mean position errors along the loop, odometry alone and filtered (cm).
EkfOutcome ekfOutcome(const std::string& name, const EkfDrives& drives) {
  EkfOutcome e;
  e.condition = name;
  e.odometryErrorCmPerDrive = drives.odometryErrorCm;
  e.ekfErrorCmPerDrive = drives.ekfErrorCm;
  e.meanErrorOdometryCm = meanOf(drives.odometryErrorCm).value();
  e.meanErrorEkfCm = meanOf(drives.ekfErrorCm).value();
  e.measurementsUsed = drives.first.used;
  e.measurementsGated = drives.first.gated;
  return e;
}

// The EKF's floor: every beacon visible from a test pose measured at its true range and bearing.
EkfOutcome exactMeasurementsEkf(const std::vector<std::vector<GroundTruthBeacon>>& truth, const std::vector<Drive>& drives,
                                int testStride) {
  std::vector<std::vector<Measurement>> exact(truth.size());
  for (size_t k = 0; k < truth.size(); ++k)
    for (const GroundTruthBeacon& b : truth[k])
      if (b.visible) exact[k].push_back({b.beacon->position(), RangeBearing(b.rangeM, b.bearingRad)});
  const size_t stride = static_cast<size_t>(testStride);
  return ekfOutcome(kExactMeasurements, runEkfOnDrives(drives, [&](size_t k) -> const std::vector<Measurement>* {
                      return k % stride == 0 && k / stride < exact.size() ? &exact[k / stride] : nullptr;
                    }));
}

}  // namespace

TextureRealismResults runTextureRealism(const TextureRealismOptions& o, const std::string& plotScript,
                                        const ExperimentProgress& progress) {
  const auto started = std::chrono::steady_clock::now();
  if (o.size < 64 || o.spp < 1 || o.realistic.spp < 1 || o.testStride < 1 || o.trainFrames < 1 || o.randomHalls < 1 ||
      o.randomPhotos.empty() || o.labPhoto.empty())
    throw InputError("texture-realism: size ≥ 64, spp ≥ 1, stride ≥ 1, ≥ 1 training frame and hall, and photos");
  if (o.recordingDraws < 1 || static_cast<uint64_t>(o.trainFrames) * static_cast<uint64_t>(o.recordingDraws) >= kFigureDraws)
    throw InputError("texture-realism: 1 to " + std::to_string(kFigureDraws - 1) + " training recordings (frames × draws)");
  if (o.ekfDrives < 1) throw InputError("texture-realism: at least one EKF drive");
  const fs::path out(o.outDir);
  // Its folders are made without following a link planted there: what it writes stays inside.
  makeAllFoldersInside(o.outDir, {"arenas", "data", "frames", "figures"});

  writeArenas(o, out);
  const Scene plain = loadScene((out / "arenas/hall-plain.json").string());
  const Scene textured = loadScene((out / "arenas/hall-textured.json").string());
  const std::vector<Beacon> beacons = beaconsOf(plain);
  const std::vector<std::string> bandColour = bandColourOfObjects(plain);
  const std::vector<std::string> objectNames = objectNamesOf(plain);
  const CameraPath* loop = plain.findPath("thesis-loop");
  if (!loop) throw InputError(showPath(o.fieldScene) + ": paths: no \"thesis-loop\"");
  std::vector<RobotPose> testPoses;
  for (size_t k = 0; k < loop->poses.size(); k += static_cast<size_t>(o.testStride)) testPoses.push_back(loop->poses[k]);

  const std::vector<PresetFold> folds = presetFolds(o.trainingRecording);
  const int trainTotal = 5 * o.trainFrames + 1 + (o.ablation ? static_cast<int>(recordingStages().size()) : 0) +
                         static_cast<int>(folds.size());  // the footprint detector's own sets, if any, counted apart
  const int testTotal = 4 * static_cast<int>(testPoses.size());
  int done = 0;
  const std::function<void()> step = [&] { progress("rendering and training", ++done, trainTotal + testTotal); };
  CyclesCount cycles;
  const TrainingFrames trainingFrames = renderTrainingFrames(o, out, plain, textured, step, cycles);
  Classifiers trained = trainSets(trainingFrames, o, o.detector, bandColour, step);
  const std::vector<ValidationFold> validationFolds = trainFolds(o, trainingFrames.path, folds, bandColour, step);
  const std::map<std::string, std::vector<Frame>> tests = renderTestSets(o, plain, textured, testPoses, step, cycles);
  // The oracle: classifiers trained on the realistic test frames themselves. What no training set
  // can beat with these classifiers: whether the bands' colours survive the test camera at all.
  trainOn(freshClassifiers(trained, kOracleSet, o.bins), tests.at("realistic"), bandColour, o.detector);
  const std::vector<Frame> validation = validationFrames(o, textured, step);

  // Detection and evaluation.
  const FastRenderer geometry(plain);
  RigSpec rig = plain.rig;
  rig.mirrorRig().imageSize = o.size;
  const double matchRadius = o.matchRadiusPx * o.size / 360.0;
  std::vector<std::vector<GroundTruthBeacon>> truth;
  for (const RobotPose& pose : testPoses) truth.push_back(groundTruth(plain, geometry.rays(), rig, pose, beacons));
  const FootprintDetector footprints(rig, beacons);
  std::vector<std::vector<GroundTruthBeacon>> validationTruth;
  for (const Frame& frame : validation) validationTruth.push_back(groundTruth(plain, geometry.rays(), rig, frame.pose, beacons));
  const std::vector<FootprintTrial> trials = tryFootprintSettings(o, validationFolds, validation, validationTruth,
                                                                  footprints, {bandColour, objectNames, matchRadius}, progress);
  const FootprintTrial& chosen = chosenSetting(trials);
  const int footprintBins = chosen.bins;
  const FootprintRule footprintRule = chosen.rule;
  const DetectorOptions footprintOptions = withMedian(o.detector, chosen.medianPx);
  // The footprint detector's sets: the pixel detector's when their input filters agree, otherwise
  // every set trained again on the same frames through the chosen filter; at footprintBins.
  Classifiers filtered;
  if (footprintOptions.medianPx != o.detector.medianPx) {
    int trainedSoFar = 0;
    const int setsToTrain = 1 + (o.ablation ? static_cast<int>(recordingStages().size()) : 0);
    filtered = trainSets(trainingFrames, o, footprintOptions, bandColour, [&] {
      progress("training the footprint detector's classifiers through its median filter", ++trainedSoFar, setsToTrain);
    });
    trainOn(freshClassifiers(filtered, kOracleSet, o.bins), tests.at("realistic"), bandColour, footprintOptions);
  }
  const Classifiers& footprintSets = footprintOptions.medianPx != o.detector.medianPx ? filtered : trained;
  Classifiers coarsened;  // every set at footprintBins, when that is not the trained resolution
  if (footprintBins != o.bins)
    for (const auto& [set, classifiers] : footprintSets) coarsened[set] = coarsenedSet(classifiers, footprintBins);
  const Classifiers& forFootprints = footprintBins != o.bins ? coarsened : footprintSets;
  std::vector<Drive> drives;  // the same noise for every condition; the first drive's seed as ever
  for (int d = 0; d < o.ekfDrives; ++d) drives.push_back(makeDrive(loop->poses, o.seed + 7 + static_cast<uint64_t>(d)));
  ReportData report;
  report.options = &o;
  report.testPoses = testPoses;
  for (const ConditionToRun& run : conditionsOf(o)) {
    ConditionReport condition;
    condition.outcome.train = run.train;
    condition.outcome.test = run.test;
    condition.outcome.detector = run.detector;
    const std::vector<Frame>& frames = tests.at(run.test);
    const auto& classifiers = (run.detector == DetectorKind::Footprints ? forFootprints : trained).at(run.train);
    for (size_t k = 0; k < frames.size(); ++k) {
      const DetectionResult detected = run.detector == DetectorKind::Footprints
                                           ? footprints.detect(frames[k].image, classifiers, footprintOptions, footprintRule)
                                           : detectBeacons(frames[k].image, classifiers, beacons, rig, o.detector);
      condition.frames.push_back(evaluateFrame(frames[k], detected, truth[k], bandColour, objectNames, matchRadius));
      progress("detecting " + condition.outcome.key(), static_cast<int>(k + 1), static_cast<int>(frames.size()));
    }
    summariseCondition(condition, frames, drives, o.testStride);
    report.conditions.push_back(std::move(condition));
  }
  for (const auto& [set, classifiers] : trained) report.classifiers[set] = &classifiers;

  TextureRealismResults results;
  describeCameras(o, results);
  results.footprintTrials = trials;
  results.footprintBins = footprintBins;
  results.footprintRule = footprintRule;
  results.footprintMedianPx = footprintOptions.medianPx;
  results.cyclesFramesRendered = cycles.rendered;
  results.cyclesFramesReused = cycles.reused;
  results.comparison = recordingComparison(o, tests, report.conditions.front().exampleFrame);
  for (const ConditionReport& c : report.conditions) {
    results.conditions.push_back(c.outcome);
    results.ekf.push_back(ekfOutcome(c.outcome.key(), c.ekf));
  }
  results.ekf.push_back(exactMeasurementsEkf(truth, drives, o.testStride));
  results.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  writeTextureRealismReport(report, results, plotScript);
  return results;
}

DetectionFrame texturedHallDetectionFrame(const std::string& fieldScene, const std::string& labPhoto,
                                          const std::string& arenaDir, int size, int spp, int trainFrames) {
  fs::create_directories(arenaDir);
  HallOptions hall;
  hall.fieldScene = fieldScene;
  writeHallArena(hall, (fs::path(arenaDir) / "hall-plain.json").string());
  hall.photos = {labPhoto};
  writeHallArena(hall, (fs::path(arenaDir) / "hall-textured.json").string());
  const Scene plain = loadScene((fs::path(arenaDir) / "hall-plain.json").string());
  const Scene textured = loadScene((fs::path(arenaDir) / "hall-textured.json").string());
  const std::vector<Beacon> beacons = beaconsOf(plain);
  const std::vector<std::string> bandColour = bandColourOfObjects(plain);
  std::map<std::string, ColourHistogramClassifier> classifiers;
  for (const char* colour : {"cyan", "magenta", "yellow"}) classifiers.emplace(colour, ColourHistogramClassifier(32));
  trainOn(classifiers, renderFast(plain, randomFieldPoses(trainFrames, 2009), size, spp, [] {}), bandColour, DetectorOptions{});
  const CameraPath* loop = plain.findPath("thesis-loop");
  if (!loop) throw InputError(showPath(fieldScene) + ": paths: no \"thesis-loop\"");
  // Mid-way along the field's long edge: several beacons in view.
  DetectionFrame result;
  result.poseIndex = static_cast<int>(loop->poses.size() / 8);
  const RobotPose pose = loop->poses[static_cast<size_t>(result.poseIndex)];
  const Frame frame = std::move(renderFast(textured, {pose}, size, spp, [] {}).front());
  RigSpec rig = plain.rig;
  rig.mirrorRig().imageSize = size;
  const FastRenderer geometry(plain);
  const FrameEvaluation e =
      evaluateFrame(frame, detectBeacons(frame.image, classifiers, beacons, rig, DetectorOptions{}),
                    groundTruth(plain, geometry.rays(), rig, pose, beacons), bandColour, objectNamesOf(plain),
                    8.0 * size / 360.0);
  result.drawn = drawDetections(frame.image, e);
  result.visibleBeacons = e.visibleBeacons;
  result.truePositives = e.truePositives;
  result.falsePositives = e.falsePositives();
  return result;
}

}  // namespace omnicam
