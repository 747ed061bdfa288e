#pragma once
// What the texture-realism experiment is asked (its options) and what it finds: shared by the
// runner (texture_realism.h) and the report that writes it (texture_realism_report.h).
#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "beacon_detector.h"
#include "footprint_detector.h"
#include "realistic_rendering.h"
#include "recording_camera_spec.h"
#include "render_settings.h"

namespace omnicam {

// The training cameras' ranges: each frame one of the presets (webcam, machine_vision, phone), its
// values drawn from that preset's ranges.
RecordingCameraSpec trainingRecordingMix(uint64_t seed);

// Leave-one-preset-out validation: fold p's training cameras never draw the mix's preset p, and its
// validation cameras always do, so a fold validates on cameras of a kind its training never saw,
// as a test camera is. Each preset keeps its own ranges. The mix must draw one of several presets.
struct PresetFold {
  RecordingCameraSpec training, validation;
};
std::vector<PresetFold> presetFolds(const RecordingCameraSpec& mix);

struct TextureRealismOptions {
  std::string outDir;
  std::string fieldScene;                  // scenes/robocup2006.json
  std::string labPhoto;                    // the textured (test) walls
  std::vector<std::string> randomPhotos;   // the random_textures training walls
  int size = 360;
  int spp = 16;                // fast renders
  int pathSpp = kPathDatasetSpp;  // fast path-traced renders (denoised): the "path" sets
  RealisticRendering realistic = realisticRendering();
  int testStride = 1;          // every k-th of the 100 thesis-loop poses
  int trainFrames = 24;        // per train set
  int randomHalls = 6;         // random_textures: frames spread over this many halls
  int bins = 32;
  DetectorOptions detector;
  RecordingCamera recording = RecordingCamera::webcam();  // the realistic frames' camera (fixed)
  // Training through a range of cameras (domain randomisation): each path / plain training frame
  // recorded `recordingDraws` times, each with a camera drawn from `trainingRecording` — the three
  // presets' ranges, fixed before any result and never fitted to a test camera.
  RecordingCameraSpec trainingRecording = trainingRecordingMix(2008);
  int recordingDraws = 4;
  bool ablation = true;  // the path + recording condition once per stage held neutral
  // Extra realistic test sets: the same Cycles frames through cameras the user supplies.
  struct TestCamera {
    std::string file;                  // where it was read from (shown in the report)
    RecordingCameraSpec recording;
  };
  std::vector<TestCamera> testCameras;
  uint64_t seed = 2008;
  // The EKF drives thesis-loop this many times, each with its own odometry noise, and reports
  // the mean error: one drive's error is a draw, and bars compare conditions by their ratio.
  int ekfDrives = 16;
  double matchRadiusPx = 8.0;  // at 360 px; scaled with the image size
  double blenderTimeoutSeconds = 3600.0;
  // A reduced run (quick()): fewer frames and samples than the full run whose numbers the
  // report quotes from earlier runs, so the report leaves those comparisons out.
  bool reduced = false;

  static TextureRealismOptions quick();  // a few frames, small images, low spp: for tests
};

// The detectors a condition can run: the thesis' pixel detector (beacon_detector.h), and the one
// that scores whole beacon footprints (footprint_detector.h), whose keys end in "_footprints".
enum class DetectorKind { Pixels, Footprints };

// A condition's name in results.json, data/ and the report: "<train>_to_<test>", and
// "_footprints" after it for the footprint detector.
inline std::string conditionKey(const std::string& train, const std::string& test, DetectorKind detector) {
  return train + "_to_" + test + (detector == DetectorKind::Footprints ? "_footprints" : "");
}

// Beacons by their true range from the robot, in whole metres: 0–1 m, 1–2 m, …, the last bucket
// everything from kRangeBuckets − 1 m on.
inline constexpr int kRangeBuckets = 6;
inline int rangeBucket(double rangeM) { return rangeM < 0.0 ? 0 : std::min(kRangeBuckets - 1, static_cast<int>(rangeM)); }

struct ConditionOutcome {
  std::string train, test;
  DetectorKind detector = DetectorKind::Pixels;
  int frames = 0, truePositives = 0, falsePositives = 0, missed = 0, falsePositiveBlobs = 0;
  int falsePositiveBlobsOnHall = 0;  // of those, on the hall's walls, ceiling and floor: the textures' share
  int offBandBandsOfFoundBeacons = 0;  // not false positives: footprint bands of right answers lying mostly off their band
  int falseIdentifications() const { return falsePositives - falsePositiveBlobs; }
  // Means over the true positives: none without one (a condition that found nothing has no error).
  std::optional<double> meanLocalisationErrorPx, meanRangeErrorCm, meanBearingErrorDeg;
  // A far beacon's range from a pixel off near the horizon errs by metres: the mean of the range
  // errors follows a few of them, the median the typical sighting.
  std::optional<double> medianRangeErrorCm;
  // The objects the false-positive blobs lie on, most frequent first (at most five).
  std::vector<std::pair<std::string, int>> falsePositiveSources;
  // Visible beacons and true positives per range bucket (rangeBucket).
  std::array<int, kRangeBuckets> visibleByRange{}, truePositivesByRange{};
  std::string key() const { return conditionKey(train, test, detector); }
};

// The EKF along thesis-loop fed by a condition's detections, over every drive (options.ekfDrives):
// the means over drives, and each drive's mean error. Measurements used and gated are the first
// drive's, whose per-pose trace data/ekf_<condition>.csv holds.
// Not a condition: the EKF fed every visible beacon's true range and bearing, its floor.
inline constexpr const char* kExactMeasurements = "exact_measurements";

struct EkfOutcome {
  std::string condition;
  double meanErrorOdometryCm = 0.0, meanErrorEkfCm = 0.0;
  std::vector<double> odometryErrorCmPerDrive, ekfErrorCmPerDrive;
  int measurementsUsed = 0, measurementsGated = 0;
};

// A realistic test set's camera as the report shows it: its name in condition keys, where it came
// from, and its values in words (by parameter).
struct TestCameraSummary {
  std::string set;    // "realistic", "realistic_camera_1", …
  std::string label;  // "webcam (fixed)", a file name
  std::vector<std::pair<std::string, std::string>> values;
  // Its parameters no training camera has (parametersBeyond); none for a drawn test camera.
  std::optional<std::vector<std::string>> beyondTraining;
};

// One setting tried for the footprint detector on the validation frames (path frames at poses no
// training frame has), leave one preset out: every validation frame recorded, once per fold,
// through that fold's held-out preset at draws no training frame used, and detected with
// classifiers trained on the path frames through the other presets; never a test camera. A setting is a colour resolution
// and a FootprintRule: how a footprint's score weighs its size, and how far one band's evidence
// may fall short.
struct FootprintTrial {
  int medianPx = 1;  // the median filter on the frames, in training and detection (1: none)
  int bins = 0;
  FootprintRule rule;
  int visibleBeacons = 0, truePositives = 0, falsePositives = 0;
  int validationScore() const { return truePositives - falsePositives; }
};

struct TextureRealismResults {
  std::vector<ConditionOutcome> conditions;
  std::vector<TestCameraSummary> testCameras;
  std::vector<std::pair<std::string, std::string>> trainingRanges;  // by parameter, in words
  std::vector<std::string> ablatedStages;
  ImageRGBA comparison;  // one pose: plain, path, path + one drawn recording, realistic
  std::vector<EkfOutcome> ekf;
  // The footprint detector's conditions use classifiers trained through a median filter of
  // `footprintMedianPx`, coarsened to `footprintBins`, and `footprintRule`: the tried setting with
  // the best validation score (the first tried on a tie).
  std::vector<FootprintTrial> footprintTrials;
  int footprintMedianPx = 1;
  int footprintBins = 0;
  FootprintRule footprintRule;
  double seconds = 0.0;
  int cyclesFramesRendered = 0, cyclesFramesReused = 0;  // Cycles' frames, rendered now or kept from an earlier run
};

}  // namespace omnicam
