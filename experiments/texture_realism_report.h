#pragma once
// What the texture-realism experiment records per frame and condition, and how it is written:
// results.json, data/ (CSV, JSON), frames/ with detections drawn, figures/ (matplotlib, from
// data/), report.html and the Markdown that docs/texture-realism.md is made from.
#include <map>
#include <string>
#include <vector>

#include "ekf_drive.h"
#include "texture_realism_results.h"

namespace omnicam {

struct DrawnDetection {
  Vec2 raster;
  bool correct;
};

// A colour blob that lies mostly off the bands of its colour (by the instance mask), unless it is
// a footprint detector's band of a beacon named rightly, and what it lies on.
struct FalseBlob {
  std::string colour;
  Vec2 centroid;
  int area = 0;
  std::string object;  // the scene object most of its pixels show ("" = nothing: beyond the hall)
};

struct FrameEvaluation {
  int visibleBeacons = 0, truePositives = 0, falseIdentifications = 0, falsePositiveBlobs = 0;
  std::vector<double> localisationErrorsPx, rangeErrorsCm, bearingErrorsDeg;
  std::vector<Measurement> measurements;
  std::vector<DrawnDetection> drawn;
  std::vector<Vec2> truth;  // visible beacons' projected band boundaries
  std::vector<double> visibleRangesM, foundRangesM;  // the true ranges of visible beacons, and of those found
  std::vector<FalseBlob> falseBlobs;
  // A footprint detector's bands of beacons named rightly that lie mostly off their band (a far
  // band's footprint rounded to whole pixels): part of a right answer, so no false positive, and
  // counted apart. A classified blob in that place is a false positive.
  int offBandBandsOfFoundBeacons = 0;
  // False positives: the off-band blobs above (falseBlobs) plus beacons named where they are not.
  int falsePositives() const { return falsePositiveBlobs + falseIdentifications; }
};

struct ConditionReport {
  ConditionOutcome outcome;
  std::vector<FrameEvaluation> frames;
  EkfDrives ekf;
  size_t exampleFrame = 0;
  ImageRGBA exampleImage;
};

struct ReportData {
  const TextureRealismOptions* options = nullptr;
  std::vector<RobotPose> testPoses;
  std::vector<ConditionReport> conditions;
  std::map<std::string, const std::map<std::string, ColourHistogramClassifier>*> classifiers;
};

// Draws detections on a copy of `image`: visible beacons' true positions as green crosses,
// correct detections as yellow circles, wrong ones as red circles.
ImageRGBA drawDetections(const ImageRGBA& image, const FrameEvaluation& frame);

void writeTextureRealismReport(const ReportData& data, const TextureRealismResults& results, const std::string& plotScript);

// results.json's "study": which experiment's folder this is (experiment_folder.h).
inline constexpr const char* kTextureRealismStudy = "texture-realism";
nlohmann::json textureRealismResultsJson(const TextureRealismResults& results);
// The run's operating point, for results.json's "settings": sizes, samples, the detector's Θ, bins,
// median and blob area, the recording draws, the test cameras' files, the seed.
nlohmann::json textureRealismSettingsJson(const TextureRealismOptions& options);

// The section on training through drawn recording cameras (texture_realism_recording_report.cpp);
// `figure`: the comparison strip's path relative to the document, or "" for none.
std::string recordingSectionMarkdown(const TextureRealismResults& results, const TextureRealismOptions& options,
                                     const std::string& figure);
// The strip of one pose (plain, path, path through a drawn camera, realistic), in figures/.
inline constexpr const char* kRecordingFigure = "texture_realism_recording.png";

// The measured table beside the thesis' numbers, with which findings reproduce (Markdown);
// `convergence`, when given, is the realistic-convergence study's section (its figure at
// `convergenceFigure`, relative to the document).
std::string textureRealismMarkdown(const TextureRealismResults& results, const TextureRealismOptions& options,
                                   const std::string& command, const std::string& convergence = "");

}  // namespace omnicam
