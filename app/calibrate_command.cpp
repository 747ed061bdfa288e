// omnicam calibrate: a calibration sequence's camera calibrated with cv::omnidir as a user would,
// and measured against its true rays (dataset/calibrate_dataset.h).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "atomic_file.h"
#include "calibrate_dataset.h"
#include "calibration_files.h"
#include "cli_util.h"
#include "commands.h"
#include "errors.h"
#include "number_format.h"

namespace omnicam::cli {

namespace {

struct CalibrateArgs {
  std::string dir, camera, out;
  bool exactCorners = false, fixDistortion = false, json = false;
};

nlohmann::json resultJson(const DatasetCalibration& c, bool exactCorners) {
  nlohmann::json j = {{"camera", c.camera},
                      {"target", c.target},
                      {"frames", c.frames},
                      {"views", c.views},
                      {"corners", c.corners},
                      {"corners_from", exactCorners ? "exact" : "detected"},
                      {"converged", c.fit.converged},
                      {"truth", c.truth}};
  if (c.cornersDetected > 0)
    j["detection"] = {{"corners", c.cornersDetected}, {"median_px", c.detectionMedianPx}, {"max_px", c.detectionMaxPx}};
  if (!c.fit.converged) {
    j["failure"] = c.fit.failure;
    return j;
  }
  j["fit"] = {{"rms_px", c.fit.rms},
              {"views_used", c.fit.usedViews.size()},
              {"xi", c.fit.xi},
              {"gamma_x", c.fit.gammaX},
              {"gamma_y", c.fit.gammaY},
              {"skew", c.fit.skew},
              {"cx", c.fit.cx},
              {"cy", c.fit.cy},
              {"distortion", c.fit.distortion}};
  nlohmann::json heldOut = nlohmann::json::array();
  for (const HeldOutError& e : c.heldOut)
    heldOut.push_back({{"distance_m", e.distanceM}, {"median_px", e.medianPx}, {"rms_px", e.rmsPx}, {"max_px", e.maxPx},
                       {"unmodelled_share", e.unmodelledShare}});
  j["held_out"] = heldOut;
  return j;
}

void printResult(const DatasetCalibration& c, const CalibrateArgs& a) {
  std::printf("camera %s: %d views of target %s from %d frames (a view: a frame with 4 corners or more; %d corners, %s)\n",
              c.camera.c_str(), c.views, c.target.c_str(), c.frames, c.corners, a.exactCorners ? "exact" : "detected");
  if (c.cornersDetected > 0)
    std::printf("detected corners from the exact ones: median %s px, max %s px\n", shortNumber(c.detectionMedianPx).c_str(),
                shortNumber(c.detectionMaxPx).c_str());
  if (!c.fit.converged) {
    std::printf("cv::omnidir::calibrate failed: %s\n", c.fit.failure.c_str());
    return;
  }
  const auto d = c.fit.distortion;
  std::printf("cv::omnidir::calibrate: RMS %s px over %zu of the %d views (its initialisation keeps the views it can start "
              "from)\n",
              shortNumber(c.fit.rms).c_str(), c.fit.usedViews.size(), c.views);
  std::printf("  xi %.6f  gamma %.4f %.4f  centre (%.4f, %.4f)  k1 %.3g k2 %.3g p1 %.3g p2 %.3g\n", c.fit.xi, c.fit.gammaX,
              c.fit.gammaY, c.fit.cx, c.fit.cy, d[0], d[1], d[2], d[3]);
  const nlohmann::json& t = c.truth;
  // The manifest's unified model: the ideal rig's closed form, a physical rig's best central fit.
  const bool physical = t.contains("central_approximation") && t["central_approximation"].is_object();
  const nlohmann::json& mei = physical ? t["central_approximation"] : t;
  const auto number = [&mei](const char* key) { return mei.contains(key) && mei[key].is_number() ? mei[key].get<double>() : std::nan(""); };
  if (mei.contains("model") && mei["model"] == "mei_unified")
    std::printf("  %s: xi %.6f  gamma %.4f %.4f  centre (%.4f, %.4f)\n",
                physical ? "the manifest's best central fit of the physical rig" : "the manifest's intrinsics (exact)", number("xi"),
                number("gamma_x"), number("gamma_y"), number("cx"), number("cy"));
  std::printf("error on points it never saw, along the camera's true rays:\n");
  for (const HeldOutError& e : c.heldOut)
    std::printf("  at %s m: median %s px, RMS %s px, max %s px%s\n", shortNumber(e.distanceM).c_str(), shortNumber(e.medianPx).c_str(),
                shortNumber(e.rmsPx).c_str(), shortNumber(e.maxPx).c_str(),
                e.unmodelledShare > 0 ? (", " + shortNumber(100.0 * e.unmodelledShare) + " % of the pixels unmodelled").c_str() : "");
}

void runCalibrate(const CalibrateArgs& a) {
  if (!a.out.empty()) {
    const std::string extension = std::filesystem::path(a.out).extension().string();
    if (extension != ".yml" && extension != ".yaml")
      throw InputError("-o: " + showPath(a.out) + ": must end in .yml or .yaml (the calibration is OpenCV YAML)");
    checkOutputFile(a.out, "-o");
    checkOutputIsOutsideFolder(a.out, "-o", a.dir, "the dataset");
  }
  DatasetCalibrationOptions options;
  options.camera = a.camera;
  options.exactCorners = a.exactCorners;
  options.fixDistortion = a.fixDistortion;
  std::optional<Progress> progress;
  if (!a.exactCorners)  // the exact corners are read, not found
    options.progress = [&](int done, int total) {
      if (!progress) progress.emplace("finding corners", total, 0, "frames");
      progress->advanceTo(done);
    };
  const DatasetCalibration c = calibrateDatasetCamera(a.dir, options);
  if (progress) progress->finish();
  if (a.json)
    std::printf("%s\n", resultJson(c, a.exactCorners).dump(1).c_str());
  else
    printResult(c, a);
  if (!c.fit.converged) throw ExternalError("calibrate: no calibration (" + c.fit.failure + ")");
  if (!a.out.empty()) {
    writeTextAtomically(a.out, omnidirCalibrationYaml(c.fit, c.camera, c.width, c.height, true));
    if (!a.json) std::printf("wrote %s\n", showPath(a.out).c_str());
  }
}

}  // namespace

void addCalibrateCommand(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "Calibrate a calibration sequence's mirror camera with cv::omnidir and measure it against the true rays");
  cmd->add_option("dataset", args->dir, "A calibration sequence's dataset folder (docs/calibration.md)")->required();
  cmd->add_option("--camera", args->camera, "The camera to calibrate (default: the first mirror camera)");
  cmd->add_flag("--exact-corners", args->exactCorners,
                "Fit the exact corners the dataset records (corners.json) instead of the detectors' (OpenCV, AprilTag)");
  cmd->add_flag("--fix-distortion", args->fixDistortion, "Hold k1, k2, p1, p2 at zero (the ideal rig's model has none)");
  cmd->add_option("-o,--output", args->out, "Write the calibration as OpenCV YAML (camera_matrix, xi, distortion_coefficients)");
  cmd->add_flag("--json", args->json, "Print the result as JSON");
  cmd->callback([args] { runCalibrate(*args); });
}

}  // namespace omnicam::cli
