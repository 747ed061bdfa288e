#pragma once
// The calibration study (docs/calibration-study.md): what misalignment does to a calibrated
// central model, measured against the exact rig. For each misalignment of the sweep (the
// pinhole moved across or along the axis, tilted; with and without a lens's distortion) and each
// seed, a user's calibration is repeated: an AprilGrid waved in front of the robot, its corners
// exact, detected in clean renders and detected in a recording camera's noisy frames,
// cv::omnidir::calibrate on each. Every calibrated model is then measured where no board was:
// held-out reprojection and ray errors at several distances, triangulation from two robot poses,
// and the thesis' EKF self-localisation with bearings from the calibrated model.
#include <functional>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiment_progress.h"
#include "omnidir_fit.h"
#include "recording_camera.h"
#include "rig.h"

namespace omnicam {

// results.json's "study": which experiment's folder this is (experiment_folder.h).
inline constexpr const char* kCalibrationStudy = "calibration";

struct CalibrationStudyOptions {
  std::string outDir;
  std::string fieldScene;  // the RoboCup field: its beacons and thesis-loop for the EKF
  int size = 720, spp = 4;
  int views = 20;          // board poses a calibration sees
  std::vector<double> offsetsMm{0.25, 0.5, 1.0, 2.0, 5.0};  // lateral (x) and axial (z)
  std::vector<double> tiltsDeg{0.25, 0.5, 1.0, 2.0};         // about the camera's x axis
  LensDistortion typicalLens{-0.08, 0.015, 0.0004, -0.0003, 0.0};
  bool distortedLens = true;  // the sweep again with typicalLens
  int seeds = 3;
  std::vector<double> heldOutDistancesM{0.2, 0.5, 1.0, 5.0};
  double triangulationDistanceM = 1.0, triangulationBaselineM = 0.25;
  RecordingCamera recording = RecordingCamera::webcam();
  // The sweep at its smallest: the ideal rig and 2 mm across and along the axis, one seed of
  // twelve views (720 px: AprilTag finds too few corners at 360 px).
  bool reduced = false;  // quick(): too few rigs and seeds for the study's numbers (the report says so)
  static CalibrationStudyOptions quick();
};

// One rig of the sweep.
struct Misalignment {
  std::string kind;  // "ideal", "lateral", "axial", "tilt"
  double amount = 0.0;  // mm or degrees
  bool distorted = false;
  RigSpec rig(const RigSpec& nominal, const LensDistortion& lens) const;
  std::string label() const;  // "lateral 2 mm", "ideal, lens"
};

enum class CornerSource { Exact, Detected, DetectedNoisy };
const char* cornerSourceName(CornerSource source);   // in results.json
const char* cornerSourceTitle(CornerSource source);  // in the report

struct TriangulationError {
  double medianMm = 0.0, p90Mm = 0.0;
  int points = 0;
};

// Points `distanceM` from F' on the true rays of a pixel grid, seen again after the robot drove
// `baselineM` forward: each triangulated (midpoint of the closest points) from the two rays
// `model` gives their pixels, against the truth. Points whose true rays meet at less than 5°
// (almost along the baseline) are left out.
TriangulationError triangulationError(const Camera& camera, const CentralApproximation& model, double distanceM, double baselineM);

// One calibration: a seed's views with one source of corners.
struct CalibrationRun {
  CornerSource source = CornerSource::Exact;
  int seed = 0;
  int views = 0, corners = 0;  // views with at least four corners, and their corners
  OmnidirCalibration fit;      // converged false: failed (initialisation, or diverged)
  bool diverged = false;       // OpenCV converged to a training RMS no user would keep
  std::optional<CentralApproximation> model;  // when it converged: placed by its own extrinsics
  std::vector<HeldOutError> heldOut;  // one per options.heldOutDistancesM
  TriangulationError triangulation;
};

// The EKF along thesis-loop, bearings and ranges from a model of the camera (cm).
struct EkfComparison {
  double odometryCm = 0.0;
  double trueRaysCm = 0.0;      // the rig's exact rays
  double nominalCm = 0.0;       // the ideal rig's model, as if nothing were misaligned
  double nominalUsedShare = 0.0;  // of its measurements, the share the EKF's gate let in
  double calibratedCm = 0.0;    // seed 1's calibration from noisy detected corners (NaN: it failed)
  double calibratedExactCm = 0.0;  // seed 1's calibration from exact corners (NaN: it failed)
  int measurements = 0;
};

struct RigOutcome {
  Misalignment misalignment;
  // The best a central model can do: the ideal rig's closed form, or the best-fit central model.
  MeiIntrinsics truth;
  std::vector<HeldOutError> bestFitHeldOut;
  std::vector<CalibrationRun> runs;
  EkfComparison ekf;
};

struct CalibrationStudyResults {
  std::vector<RigOutcome> rigs;
  int width = 0;
  double seconds = 0.0;
};

// Runs the sweep, writes outDir/results.json, data/ (residual maps) and, with a plot script,
// figures/ (matplotlib).
CalibrationStudyResults runCalibrationStudy(const CalibrationStudyOptions& options, const std::string& plotScript,
                                            const ExperimentProgress& progress);

nlohmann::json calibrationStudyJson(const CalibrationStudyResults& results, const CalibrationStudyOptions& options);
// The tables and the headline (Markdown; with `figures`, the figures under figures/, relative to
// the document; without, a note where each would be).
std::string calibrationStudyMarkdown(const CalibrationStudyResults& results, const CalibrationStudyOptions& options,
                                     const std::string& command, bool figures = true);

}  // namespace omnicam
