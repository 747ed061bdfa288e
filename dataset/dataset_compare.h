#pragma once
// Dataset against dataset, frame by frame (omnicam compare DIR_A DIR_B): the RGB of every frame
// and camera of A against the same frame and camera of B. Frames are matched by manifest — the
// same frame indices, cameras and poses, or an InputError saying what differs. B may also be a
// folder without a manifest (a user's own simulator, rendered at the poses of A's poses.tum):
// its images are then found at A's relative paths, as .png or .exr.
#include <optional>
#include <string>
#include <vector>

#include "image_compare.h"

namespace omnicam {

struct DatasetCompareOptions {
  CompareOptions image;
  CompareThresholds thresholds;  // each frame is checked against them; none given: nothing is checked
  int worstFrames = 6;           // shown with heat maps in the report
  double diffScale = 0.05;
  // Compare only the frames both datasets hold (a ground truth of fewer frames, a run stopped
  // early), noting how many were left out; by default the frames must be the same.
  bool commonFramesOnly = false;
};

struct FrameComparison {
  int index = 0;
  std::string camera, fileA, fileB;  // relative paths
  bool layeredA = false, layeredB = false;  // the file is a multilayer frame (its R, G, B, A compared)
  CompareResult result;
  bool failed = false;
};

struct DatasetCompareResult {
  std::vector<FrameComparison> frames;  // in frame, then camera order
  int failures = 0;
  // meanPsnrDb is over the frames whose colour differs (an identical colour's PSNR is infinite;
  // `identical` counts those frames).
  double meanPsnrDb = 0.0, minPsnrDb = 0.0, meanSsim = 0.0, maxAbs = 0.0, maxAbsAlpha = 0.0;
  int identical = 0;
  int alphaCompared = 0;  // image pairs (frame × camera) that both have alpha: maxAbsAlpha is over these
  // What the two manifests say differs beside the pixels: the cameras' rigs (the frames are then
  // images of different cameras, which a study of a rig's change means and a regression check
  // does not). One line each, for people.
  std::vector<std::string> notes;
};

DatasetCompareResult compareDatasets(const std::string& dirA, const std::string& dirB,
                                     const DatasetCompareOptions& options);
// The largest difference of alpha over the pairs that both have it, as text, or why there is none.
std::string datasetAlphaText(const DatasetCompareResult& result);

// The folder beside an HTML report that holds its images ("<stem>_files").
std::string reportAssetsFolder(const std::string& reportPath);
// An HTML page: summary, worst frames with A, B and the difference heat map, every frame's row.
// Images go to reportAssetsFolder(reportPath).
void writeDatasetCompareReport(const std::string& reportPath, const std::string& dirA, const std::string& dirB,
                               const DatasetCompareResult& result, const DatasetCompareOptions& options);
// JUnit XML: one test case per frame and camera, failing as options.thresholds say; without a
// threshold every case is skipped (nothing was checked), not passed.
std::string datasetCompareJUnit(const std::string& dirA, const std::string& dirB, const DatasetCompareResult& result,
                                const DatasetCompareOptions& options);

}  // namespace omnicam
