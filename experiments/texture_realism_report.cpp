#include "texture_realism_report.h"

#include "plot_script.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <set>
#include <sstream>

#include "atomic_file.h"
#include "errors.h"
#include "experiment_folder.h"
#include "external_process.h"
#include "markdown_html.h"
#include "markup.h"
#include "texture_realism_tables.h"
#include "number_format.h"
#include "safe_files.h"

namespace omnicam {

namespace fs = std::filesystem;

ImageRGBA drawDetections(const ImageRGBA& image, const FrameEvaluation& frame) {
  const int w = image.width, h = image.height;
  cv::Mat canvas(h, w, CV_8UC3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const float* p = image.at(i, j);
      for (int c = 0; c < 3; ++c)
        canvas.at<cv::Vec3b>(j, i)[c] = static_cast<unsigned char>(std::lround(std::clamp(linearToSrgb(p[c]), 0.0f, 1.0f) * 255));
    }
  const int scale = std::max(1, w / 180);
  // OpenCV draws at integer pixel indices: raster − 0.5 (pixel centres at +0.5 in rasters).
  auto at = [](const Vec2& raster) { return cv::Point(static_cast<int>(std::lround(raster.x() - 0.5)),
                                                      static_cast<int>(std::lround(raster.y() - 0.5))); };
  for (const Vec2& t : frame.truth)
    cv::drawMarker(canvas, at(t), cv::Scalar(0, 255, 0), cv::MARKER_CROSS, 6 * scale, 1);
  for (const DrawnDetection& d : frame.drawn)
    cv::circle(canvas, at(d.raster), 5 * scale, d.correct ? cv::Scalar(255, 255, 0) : cv::Scalar(255, 0, 0), 1,
               cv::LINE_AA);
  ImageRGBA out(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      float* p = out.at(i, j);
      for (int c = 0; c < 3; ++c) p[c] = srgbToLinear(canvas.at<cv::Vec3b>(j, i)[c] / 255.0f);
      p[3] = 1.0f;
    }
  return out;
}

nlohmann::json textureRealismSettingsJson(const TextureRealismOptions& o) {
  nlohmann::json testCameras = nlohmann::json::array();
  for (const TextureRealismOptions::TestCamera& camera : o.testCameras) testCameras.push_back(camera.file);
  return {{"size", o.size},
          {"spp", o.spp},
          {"path_spp", o.pathSpp},
          {"test_stride", o.testStride},
          {"train_frames", o.trainFrames},
          {"bins", o.bins},
          {"theta", o.detector.theta},
          {"median_px", o.detector.medianPx},
          {"min_blob_area", o.detector.minBlobArea},
          {"recording_draws", o.recordingDraws},
          {"ablation", o.ablation},
          {"test_cameras", testCameras},
          {"seed", o.seed}};
}

nlohmann::json textureRealismResultsJson(const TextureRealismResults& results) {
  nlohmann::json j;
  j["study"] = kTextureRealismStudy;
  j["conditions"] = nlohmann::json::object();
  for (const ConditionOutcome& c : results.conditions)
    j["conditions"][c.key()] = {{"frames", c.frames},
                                {"true_positives", c.truePositives},
                                {"false_positives", c.falsePositives},
                                {"false_positive_blobs", c.falsePositiveBlobs},
                                {"false_positive_blobs_on_hall", c.falsePositiveBlobsOnHall},
                                {"false_identifications", c.falseIdentifications()},
                                {"off_band_bands_of_found_beacons", c.offBandBandsOfFoundBeacons},
                                {"missed", c.missed},
                                {"mean_localisation_error_px", jsonOrNull(c.meanLocalisationErrorPx)},
                                {"mean_range_error_cm", jsonOrNull(c.meanRangeErrorCm)},
                                {"median_range_error_cm", jsonOrNull(c.medianRangeErrorCm)},
                                {"mean_bearing_error_deg", jsonOrNull(c.meanBearingErrorDeg)},
                                {"false_positive_sources", c.falsePositiveSources},
                                {"visible_by_range_m", c.visibleByRange},
                                {"true_positives_by_range_m", c.truePositivesByRange}};
  j["ekf"] = nlohmann::json::object();
  for (const EkfOutcome& e : results.ekf)
    j["ekf"][e.condition] = {{"mean_error_odometry_cm", e.meanErrorOdometryCm},
                             {"mean_error_ekf_cm", e.meanErrorEkfCm},
                             {"mean_improvement_cm", e.meanErrorOdometryCm - e.meanErrorEkfCm},
                             {"drives", e.ekfErrorCmPerDrive.size()},
                             {"odometry_error_cm_per_drive", e.odometryErrorCmPerDrive},
                             {"ekf_error_cm_per_drive", e.ekfErrorCmPerDrive},
                             {"measurements_used", e.measurementsUsed},
                             {"measurements_gated", e.measurementsGated}};
  j["beyond_training"] = nlohmann::json::object();  // per fixed test camera: its parameters no training camera has
  for (const TestCameraSummary& t : results.testCameras)
    if (t.beyondTraining) j["beyond_training"][t.set] = *t.beyondTraining;
  j["footprint_median_px"] = results.footprintMedianPx;
  j["footprint_bins"] = results.footprintBins;
  j["footprint_score"] = footprintScoreName(results.footprintRule.score);
  j["footprint_band_tolerance"] = results.footprintRule.bandTolerance;
  j["footprint_trials"] = nlohmann::json::array();
  for (const FootprintTrial& t : results.footprintTrials)
    j["footprint_trials"].push_back({{"median_px", t.medianPx},
                                     {"bins_per_channel", t.bins},
                                     {"score", footprintScoreName(t.rule.score)},
                                     {"band_tolerance", t.rule.bandTolerance},
                                     {"visible_beacons", t.visibleBeacons},
                                     {"true_positives", t.truePositives},
                                     {"false_positives", t.falsePositives}});
  j["seconds"] = results.seconds;
  return j;
}

namespace {

// Scene object names are the user's: quoted, with inner quotes doubled (RFC 4180).
std::string csvField(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

void writeData(const ReportData& data, const fs::path& out) {
  std::ostringstream detections;
  detections << "condition,frame,pose_index,visible_beacons,true_positives,false_identifications,false_positive_blobs,"
                "mean_error_px\n";
  for (const ConditionReport& c : data.conditions)
    for (size_t k = 0; k < c.frames.size(); ++k) {
      const FrameEvaluation& f = c.frames[k];
      std::string error;  // empty: no true positive in the frame
      if (!f.localisationErrorsPx.empty()) {
        double sum = 0.0;
        for (double e : f.localisationErrorsPx) sum += e / static_cast<double>(f.localisationErrorsPx.size());
        error = roundTrip(sum);
      }
      detections << c.outcome.key() << ',' << k << ',' << k * static_cast<size_t>(data.options->testStride) << ','
                 << f.visibleBeacons << ',' << f.truePositives << ',' << f.falseIdentifications << ','
                 << f.falsePositiveBlobs << ',' << error << '\n';
    }
  writeTextAtomically((out / "data/detections.csv").string(), detections.str());

  // What the false-positive blobs lie on: which textures fool the classifiers.
  std::ostringstream blobs;
  blobs << "condition,frame,colour,area_px,u,v,object\n";
  for (const ConditionReport& c : data.conditions)
    for (size_t k = 0; k < c.frames.size(); ++k)
      for (const FalseBlob& b : c.frames[k].falseBlobs)
        blobs << c.outcome.key() << ',' << k << ',' << b.colour << ',' << b.area << ',' << b.centroid.x() << ','
              << b.centroid.y() << ',' << csvField(b.object.empty() ? "(nothing)" : b.object) << '\n';
  writeTextAtomically((out / "data/false_positive_blobs.csv").string(), blobs.str());

  for (const ConditionReport& c : data.conditions) {
    std::ostringstream ekf;
    ekf << std::setprecision(9)
        << "frame,true_x,true_y,true_theta,odometry_x,odometry_y,ekf_x,ekf_y,ekf_theta,p_xx,p_xy,p_yy,p_thth\n";
    for (size_t k = 0; k < c.ekf.first.rows.size(); ++k) {
      const EkfRow& r = c.ekf.first.rows[k];
      ekf << k << ',' << r.truth.x() << ',' << r.truth.y() << ',' << r.truth.z() << ',' << r.odometry.x() << ','
          << r.odometry.y() << ',' << r.estimate.x() << ',' << r.estimate.y() << ',' << r.estimate.z() << ','
          << r.covariance(0, 0) << ',' << r.covariance(0, 1) << ',' << r.covariance(1, 1) << ',' << r.covariance(2, 2)
          << '\n';
    }
    writeTextAtomically((out / ("data/ekf_" + c.outcome.key() + ".csv")).string(), ekf.str());
  }

  // The trained histograms: each occupied bin's centre colour and its counts (Figs. 4.4/4.5).
  nlohmann::json histograms = nlohmann::json::object();
  for (const auto& [set, classifiers] : data.classifiers)
    for (const auto& [colour, classifier] : *classifiers) {
      const int bins = classifier.binsPerChannel();
      nlohmann::json positive = nlohmann::json::array(), negative = nlohmann::json::array();
      for (int r = 0; r < bins; ++r)
        for (int g = 0; g < bins; ++g)
          for (int b = 0; b < bins; ++b) {
            auto centre = [&](int bin) { return static_cast<uint8_t>(std::min(255, (2 * bin + 1) * 128 / bins)); };
            const Rgb8 code{centre(r), centre(g), centre(b)};
            if (const uint64_t n = classifier.positiveCount(code)) positive.push_back({code[0], code[1], code[2], n});
            if (const uint64_t n = classifier.negativeCount(code)) negative.push_back({code[0], code[1], code[2], n});
          }
      histograms[set][colour] = {{"bins_per_channel", bins},
                                 {"positive_total", classifier.positiveTotal()},
                                 {"negative_total", classifier.negativeTotal()},
                                 {"positive", positive},
                                 {"negative", negative}};
    }
  writeTextAtomically((out / "data/histograms.json").string(), histograms.dump() + "\n");
}

void writeFindings(std::ostringstream& md, const TextureRealismResults& results, bool reduced);

// What every EKF error in the report is: a mean over drives with their own odometry noise.
std::string ekfDrivesText(const TextureRealismResults& results) {
  const size_t drives = results.ekf.empty() ? 0 : results.ekf.front().ekfErrorCmPerDrive.size();
  return "EKF errors here and below are means over " + std::to_string(drives) +
         " drives along thesis-loop, each with its own odometry noise and the same detections (one drive's error is a "
         "draw: the spread shows how far); the per-pose traces (data/ekf_<condition>.csv) and the EKF figures are the "
         "first drive's.";
}

// "2.0–2.6": the smallest and largest of a condition's per-drive errors.
std::string spreadText(const std::vector<double>& perDrive) {
  if (perDrive.empty()) return "–";
  const auto [lo, hi] = std::minmax_element(perDrive.begin(), perDrive.end());
  return fixedDecimals(*lo, 1) + "–" + fixedDecimals(*hi, 1);
}

void writeHtml(const ReportData& data, const TextureRealismResults& results, const fs::path& out, bool figures) {
  std::ostringstream html;
  html << "<!doctype html><html><head><meta charset=\"utf-8\"><title>omnicam texture-realism</title>"
          "<style>body{font-family:sans-serif;max-width:1100px;margin:auto}table{border-collapse:collapse}"
          "td,th{border:1px solid #999;padding:3px 8px;text-align:right}figure{display:inline-block;margin:6px}"
          "</style></head><body><h1>Texture realism: colour-histogram beacon detection and EKF</h1>"
       << "<p>" << data.testPoses.size() << " thesis-loop frames per test set, " << data.options->size << "&times;"
       << data.options->size << " px; fast renders " << data.options->spp << " spp, Blender Cycles "
       << data.options->realistic.spp << " spp for the realistic set (through the recording-camera model: a stand-in "
       << "for the thesis' real ISLA images). Run time " << fixedDecimals(results.seconds, 1) << " s.</p>"
       << "<h2>Detection</h2><table><tr><th>train &rarr; test</th><th>frames</th><th>true positives</th>"
          "<th>false positives</th><th>(blobs)</th><th>true/false</th><th>missed</th><th>error px</th>"
          "<th>range error cm (median)</th><th>bearing error &deg;</th></tr>";
  for (const ConditionOutcome& c : results.conditions)
    html << "<tr><td>" << escapeMarkup(c.key()) << "</td><td>" << c.frames << "</td><td>" << c.truePositives
         << "</td><td>" << c.falsePositives << "</td><td>" << c.falsePositiveBlobs << "</td><td>"
         << (c.falsePositives ? fixedDecimals(static_cast<double>(c.truePositives) / c.falsePositives, 4) : "&infin;")
         << "</td><td>" << c.missed << "</td><td>" << decimalsOrDash(c.meanLocalisationErrorPx, 2) << "</td><td>"
         << decimalsOrDash(c.medianRangeErrorCm, 1) << "</td><td>" << decimalsOrDash(c.meanBearingErrorDeg, 2) << "</td></tr>";
  html << "</table><h2>EKF self-localisation</h2><p>" << escapeMarkup(ekfDrivesText(results)) << "</p>"
       << "<table><tr><th>condition</th><th>odometry cm</th><th>EKF cm</th><th>EKF cm, drives (min&ndash;max)</th>"
          "<th>improvement cm</th><th>measurements used / gated (first drive)</th></tr>";
  for (const EkfOutcome& e : results.ekf)
    html << "<tr><td>" << escapeMarkup(e.condition) << "</td><td>" << fixedDecimals(e.meanErrorOdometryCm, 1) << "</td><td>"
         << fixedDecimals(e.meanErrorEkfCm, 1) << "</td><td>" << spreadText(e.ekfErrorCmPerDrive) << "</td><td>"
         << fixedDecimals(e.meanErrorOdometryCm - e.meanErrorEkfCm, 1) << "</td><td>" << e.measurementsUsed << " / "
         << e.measurementsGated << "</td></tr>";
  // The verdicts, the transfer tables, the validation's choice, the ablation and the strip of one pose, as in the .md.
  std::ostringstream findings;
  writeFindings(findings, results, data.options->reduced);
  html << "</table>" << htmlFromMarkdown(findings.str())
       << htmlFromMarkdown(recordingSectionMarkdown(results, *data.options,
                                                    results.comparison.width > 0 ? std::string("figures/") + kRecordingFigure : ""));
  html << "<h2>Frames with detections</h2><p>Green crosses: visible beacons (projected). Yellow circles: "
          "correct detections; red: wrong identity or position.</p>";
  for (const ConditionReport& c : data.conditions)
    html << "<figure><img src=\"frames/" << escapeMarkup(c.outcome.key()) << ".png\" width=\"300\"><figcaption>"
         << escapeMarkup(c.outcome.key()) << ", frame " << c.exampleFrame << "</figcaption></figure>";
  if (figures)
    for (const char* figure : {"detections_per_frame", "histograms", "ekf_path", "ekf_covariance"})
      html << "<h2>" << figure << "</h2><img src=\"figures/" << figure << ".png\" style=\"max-width:100%\">";
  html << "</body></html>\n";
  writeTextAtomically((out / "report.html").string(), html.str());
}

// An earlier run into the folder may have had conditions this one lacks (another set of test
// cameras, no ablation): their example frames go, so the folder shows this run only. Only the
// names that run wrote are removed, never a link.
void removeFramesOfOtherConditions(const std::string& out, const nlohmann::json& earlier, const TextureRealismResults& results) {
  if (!earlier.contains("conditions") || !earlier["conditions"].is_object()) return;
  std::set<std::string> now;
  for (const ConditionOutcome& c : results.conditions) now.insert(c.key());
  for (const auto& [key, value] : earlier["conditions"].items()) {
    const bool ours = !key.empty() && std::all_of(key.begin(), key.end(), [](char ch) {
      return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_';
    });
    if (ours && !now.count(key)) removeFileInside(out, "frames/" + key + ".png");
  }
}

}  // namespace

void writeTextureRealismReport(const ReportData& data, const TextureRealismResults& results, const std::string& plotScript) {
  const fs::path out(data.options->outDir);
  const std::optional<nlohmann::json> earlier = earlierExperimentResults(out.string(), kTextureRealismStudy);
  writeData(data, out);
  for (const ConditionReport& c : data.conditions)
    writeImageAtomic((out / ("frames/" + c.outcome.key() + ".png")).string(),
                     drawDetections(c.exampleImage, c.frames[c.exampleFrame]));
  if (earlier) removeFramesOfOtherConditions(out.string(), *earlier, results);
  if (results.comparison.width > 0) writeImageAtomic((out / "figures" / kRecordingFigure).string(), results.comparison);
  nlohmann::json json = textureRealismResultsJson(results);
  json["settings"] = textureRealismSettingsJson(*data.options);
  writeTextAtomically((out / "results.json").string(), json.dump(2) + "\n");
  bool figures = false;
  if (!plotScript.empty()) {
    runPlotScript(plotScript, out.string());
    figures = true;
  }
  writeHtml(data, results, out, figures);
}

}  // namespace omnicam

namespace omnicam {

namespace {

struct ThesisRow {
  const char* condition;
  const char* thesisSetting;
  const char* truePositives;
  const char* falsePositives;
  const char* errorPx;
  const char* ratio;
};


}  // namespace

namespace {

// The runs before issue #20 made the realistic frames converge, for the comparison the document
// states: docs/texture-realism.md of 2026-11-23 (Cycles at 16 spp, point lamps) and of 2026-11-24
// (lamps of real size, 100 spp unfiltered: about 33 dB against converged frames).
struct BeforeRow {
  const char* condition;
  int truePositives, falsePositives;
  double ekfErrorCm;
  int truePositivesUnfiltered, falsePositivesUnfiltered;
  double ekfErrorCmUnfiltered;
};
constexpr BeforeRow kBeforeConvergence[] = {{"plain_to_plain", 287, 402, 4.2, 287, 402, 4.2},
                                            {"plain_to_textured", 242, 877, 4.6, 242, 877, 4.6},
                                            {"plain_to_realistic", 10, 7064, 20.4, 3, 5705, 51.6},
                                            {"random_textures_to_realistic", 18, 511, 15.9, 6, 893, 30.8}};

// The experiment's setup, and its detections beside the thesis' counts.
void writeSetupAndDetections(std::ostringstream& md, const TextureRealismResults& results, const TextureRealismOptions& o,
                             const std::string& command) {
  static const ThesisRow thesis[] = {
      {"plain_to_plain", "USARSim, plain walls", "94", "2", "1.3", "47.0"},
      {"plain_to_textured", "USARSim, ISLA-textured walls", "82", "1208", "1.84", "0.0679"},
      {"plain_to_realistic", "real ISLA images", "7", "2801", "2.6", "0.0025"},
      {"random_textures_to_realistic", "(not in the thesis)", "–", "–", "–", "–"},
      {"path_to_realistic", "(not in the thesis)", "–", "–", "–", "–"},
      {"realistic_to_path", "(not in the thesis)", "–", "–", "–", "–"}};
  md << "# Texture realism: the thesis' experiment, reproduced\n\n"
     << "<!-- Generated by `" << command << "`; do not edit by hand. -->\n\n"
     << "The thesis (Schmits 2008, Chapter 4) trained colour-histogram pixel classifiers on a plain simulated "
        "RoboCup hall, saw them collapse on real images, and found that texturing the simulated walls with real "
        "photos brought the real images' false positives back into simulation. `omnicam experiment "
        "texture-realism` repeats this with ground truth from projection instead of hand labels "
        "(experiments/texture_realism.h).\n\n"
     << "- Test frames: " << results.conditions.front().frames << " poses of `thesis-loop` ("
     << (o.testStride == 1 ? std::string("all 100") : "every " + std::to_string(o.testStride) + "th of 100") << "), "
     << o.size << "×" << o.size << " px.\n"
     << "- plain / textured: the fast renderer, lit, " << o.spp << " spp. Textured walls: planar projections of "
        "a CC0 360° photo (`interior.exr` from Debian's blender-data) seen from the hall's middle.\n"
     << "- realistic: Blender Cycles, lit and path traced, " << o.realistic.spp << " spp, of the textured hall ("
     << o.realistic.describe() << "; how converged: see below), "
        "through the recording-camera model (exposure +0.3 EV, warm white balance, vignetting 0.35, shot noise "
        "at 2500 e⁻, read noise 0.8 %, JPEG 80). **We have no ISLA images; these frames stand in for them.**\n"
     << "- Classifiers: " << o.bins << "³-bin RGB histograms per colour (cyan, magenta, yellow), Θ = "
     << o.detector.theta << ", trained on " << o.trainFrames << " random poses; positives and negatives from "
        "the fast renderer's instance masks (pixels next to a band left out of the negatives). random_textures: halls whose walls carry "
        "the other seven photos, a random photo and turn per wall.\n"
     << "- path: the fast renderer's physically based light (`--shading path`, docs/path-tracing.md) on the textured "
        "hall, " << o.pathSpp << " spp, denoised, without the recording camera — the same physics as the realistic "
        "frames at a fraction of Cycles' time. The path training set and the realistic training set share their "
        "random poses.\n"
     << "- A true positive is a beacon identified by its two bands within " << o.matchRadiusPx << " px (at 360 "
        "px) of its projected band boundary. False positives: colour blobs lying on no band of their colour (most "
        "of their pixels, by the instance mask), plus identifications of a beacon that is not there; the footprint "
        "detector's bands of a beacon it names rightly, where its model puts them, are none.\n\n"
     << "| train → test | thesis setting | thesis TP | thesis FP | thesis px | thesis TP/FP | TP | FP | "
        "wrong beacons | FP blobs on the hall (walls, floor, ceiling) | missed | px | range cm (median) | bearing ° | TP/FP |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ThesisRow& row : thesis) {
    const ConditionOutcome* c = findCondition(results, row.condition);
    if (!c) continue;
    md << "| " << row.condition << " | " << row.thesisSetting << " | " << row.truePositives << " | "
       << row.falsePositives << " | " << row.errorPx << " | " << row.ratio << " | " << c->truePositives << " | "
       << c->falsePositives << " | " << c->falseIdentifications() << " | "
       << c->falsePositiveBlobsOnHall << " | " << c->missed << " | "
       << decimalsOrDash(c->meanLocalisationErrorPx, 2) << " | " << decimalsOrDash(c->medianRangeErrorCm, 1) << " | "
       << decimalsOrDash(c->meanBearingErrorDeg, 2) << " | " << ratioText(trueOverFalse(*c)) << " |\n";
  }
}

// What the false-positive blobs lie on, and the EKF's errors.
void writeFalsePositivesAndEkf(std::ostringstream& md, const TextureRealismResults& results) {
  md << "\nWhat the false-positive blobs lie on (most frequent objects):\n\n";
  for (const ConditionOutcome& c : results.conditions) {
    md << "- " << c.key() << ":";
    if (c.falsePositiveSources.empty()) md << " none";
    for (size_t k = 0; k < c.falsePositiveSources.size(); ++k)
      md << (k ? ", " : " ") << "`" << c.falsePositiveSources[k].first << "` " << c.falsePositiveSources[k].second;
    md << "\n";
  }
  md << "\n" << ekfDrivesText(results) << "\n"
     << "\n| EKF along thesis-loop | thesis improvement | odometry error cm | EKF error cm | EKF error cm, drives (min–max) | improvement cm |\n"
     << "|---|---|---|---|---|---|\n";
  for (const EkfOutcome& e : results.ekf)
    md << "| " << e.condition << " | "
       << (e.condition == "plain_to_plain" ? "30.35 (simulation)" : e.condition == "plain_to_realistic" ? "35.11 (real)" : "–")
       << " | " << fixedDecimals(e.meanErrorOdometryCm, 1) << " | " << fixedDecimals(e.meanErrorEkfCm, 1) << " | "
       << spreadText(e.ekfErrorCmPerDrive) << " | " << fixedDecimals(e.meanErrorOdometryCm - e.meanErrorEkfCm, 1) << " |\n";
}

// Which of the thesis' findings reproduce, each with its verdict.
void writeFindings(std::ostringstream& md, const TextureRealismResults& results, bool reduced) {
  const ConditionOutcome* pp = findCondition(results, "plain_to_plain");
  const ConditionOutcome* pt = findCondition(results, "plain_to_textured");
  const ConditionOutcome* pr = findCondition(results, "plain_to_realistic");
  const ConditionOutcome* rr = findCondition(results, "random_textures_to_realistic");
  auto verdict = [](bool holds) { return holds ? "**reproduces**" : "**does not reproduce**"; };
  md << "\n## Which findings reproduce\n\n";
  if (reduced)
    md << "*A reduced run (`--quick`: a few frames, small images, few samples): the verdicts below test that the experiment "
          "runs, on too few frames to be the study's; docs/texture-realism.md holds the full run's.*\n\n";
  if (pp && pt && pr) {
    const int ppWrong = pp->falseIdentifications();
    md << "1. In the plain hall the beacons are found and almost never confused (thesis 94 TP, 2 FP): "
       << verdict(pp->truePositives > 0 && ppWrong * 50 <= pp->truePositives) << " — " << pp->truePositives
       << " TP, " << ppWrong << " wrong beacons. Colour blobs are another matter: the goals are painted the "
          "beacons' yellow and sky blue (as in the real league), so " << pp->falsePositiveBlobs - pp->falsePositiveBlobsOnHall
       << " blobs on the goals count as false positives here; the thesis' count of 2 cannot have included them.\n"
       << "2. Classifiers trained on plain simulation collapse on realistic images (thesis 7 TP, 2801 FP): "
       << verdict(pr->truePositives * 2 < pp->truePositives && pr->falsePositives > pp->falsePositives) << " — "
       << pr->truePositives << " of " << pp->truePositives << " true positives left, " << pr->falsePositives
       << " false positives.\n"
       << "3. Textured walls bring false positives into simulation while the beacons stay detectable (thesis "
          "82 TP, 1208 FP): "
       << verdict(pt->falsePositiveBlobsOnHall >= 10 * std::max(1, pp->falsePositiveBlobsOnHall) &&
                  pt->truePositives * 10 >= 7 * pp->truePositives)
       << " — false-positive blobs on the hall's walls, floor and ceiling " << pp->falsePositiveBlobsOnHall << " → "
       << pt->falsePositiveBlobsOnHall << ", " << pt->truePositives << " TP (plain: " << pp->truePositives << ").\n";
  }
  for (const EkfOutcome& e : results.ekf)
    if (e.condition == "plain_to_plain")
      md << "4. The EKF improves on odometry (thesis 30.35 cm): " << verdict(e.meanErrorOdometryCm > e.meanErrorEkfCm)
         << " — " << fixedDecimals(e.meanErrorOdometryCm - e.meanErrorEkfCm, 1) << " cm.\n";
  if (pr && rr)
    md << "5. Beyond the thesis: training on walls with random real photos instead of plain walls changes the "
          "realistic result from "
       << pr->truePositives << " TP, " << pr->falsePositives << " FP (TP/FP " << ratioText(trueOverFalse(*pr)) << ") to "
       << rr->truePositives << " TP, " << rr->falsePositives << " FP (TP/FP " << ratioText(trueOverFalse(*rr)) << ").\n";
  const ConditionOutcome* path = findCondition(results, "path_to_realistic");
  const ConditionOutcome* back = findCondition(results, "realistic_to_path");
  if (pr && path) {
    // Yes: most of the beacons plain frames find in plain frames; partly: several times plain
    // training's few, with fewer false positives per true one; else no.
    const bool better = path->truePositives > 2 * std::max(1, pr->truePositives) && trueOverFalse(*path) > trueOverFalse(*pr);
    const bool most = pp && 2 * path->truePositives >= pp->truePositives;
    md << "6. Beyond the thesis: does physically based light in training recover the beacons that plain training "
          "loses on realistic frames? "
       << (better ? (most ? "**Yes**" : "**Partly**") : "**No**")
       << " — trained on the fast renderer's path-traced frames of the textured hall, " << path->truePositives << " of "
       << path->truePositives + path->missed << " beacons found, " << path->falsePositives << " FP (TP/FP "
       << ratioText(trueOverFalse(*path)) << "), against " << pr->truePositives << " TP, " << pr->falsePositives
       << " FP trained on plain lit frames";
    if (pp) md << " (plain on plain: " << pp->truePositives << " TP)";
    const EkfOutcome* pathEkf = findEkf(results, "path_to_realistic");
    const EkfOutcome* plainEkf = findEkf(results, "plain_to_realistic");
    if (pathEkf && plainEkf)
      md << "; the EKF along thesis-loop, fed by its detections, errs " << fixedDecimals(pathEkf->meanErrorEkfCm, 1) << " cm against "
         << fixedDecimals(plainEkf->meanErrorEkfCm, 1) << " cm with plain training (odometry " << fixedDecimals(plainEkf->meanErrorOdometryCm, 1)
         << " cm)";
    if (back)
      md << "; the converse (trained on Cycles' realistic frames, tested on the path-traced ones) finds "
         << back->truePositives << " TP with " << back->falsePositives << " FP";
    md << ".\n";
  }
}

// The realistic frames' history: the numbers before and after their convergence fixes.
void writeRealisticChanges(std::ostringstream& md, const TextureRealismResults& results, const TextureRealismOptions& o) {
  if (o.reduced) {
    md << "\n## What changed with the new realistic frames\n\n"
          "The earlier runs' numbers, which this section sets beside the run's own, are of full runs; a reduced run "
          "(fewer poses and samples) is not comparable with them, so they are left out here.\n";
    return;
  }
  // The earlier runs detected with the default detector: another one is not comparable either.
  const TextureRealismOptions defaults;
  if (o.bins != defaults.bins || o.detector.theta != defaults.detector.theta ||
      o.detector.minBlobArea != defaults.detector.minBlobArea || o.detector.medianPx != defaults.detector.medianPx) {
    md << "\n## What changed with the new realistic frames\n\n"
          "The earlier runs' numbers, which this section sets beside the run's own, were detected with the default detector "
          "(32 bins, Θ 1, blobs of 2 pixels, no median); this run's detector differs, so they are left out here.\n";
    return;
  }
  const ConditionOutcome* pp = findCondition(results, "plain_to_plain");
  const ConditionOutcome* pr = findCondition(results, "plain_to_realistic");
  md << "\n## What changed with the new realistic frames\n\n"
        "Until issue #20 the realistic frames were Cycles renders at 16 spp with point lamps 0.2 m under the ceiling: "
        "mostly render noise (about 21 dB against a converged frame, white speckle over the whole mirror disc). "
        "A first fix (lamps of real size, the mirror seen by camera rays only, 100 spp) left frames about 33 dB "
        "from converged ones; the frames now filter their indirect light and are measured below. The numbers of the "
        "three runs:\n\n"
        "| train → test | TP before | FP before | TP 100 spp | FP 100 spp | TP now | FP now | EKF error cm before | "
        "EKF error cm 100 spp | EKF error cm now |\n"
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const BeforeRow& row : kBeforeConvergence) {
    const ConditionOutcome* c = findCondition(results, row.condition);
    const EkfOutcome* e = findEkf(results, row.condition);
    if (!c || !e) continue;
    md << "| " << row.condition << " | " << row.truePositives << " | " << row.falsePositives << " | "
       << row.truePositivesUnfiltered << " | " << row.falsePositivesUnfiltered << " | " << c->truePositives << " | "
       << c->falsePositives << " | " << fixedDecimals(row.ekfErrorCm, 1) << " | " << fixedDecimals(row.ekfErrorCmUnfiltered, 1) << " | "
       << fixedDecimals(e->meanErrorEkfCm, 1) << " |\n";
  }
  const BeforeRow& earlier = kBeforeConvergence[2];  // plain_to_realistic
  if (pp && pr)
    md << "\nThe plain and textured conditions are rendered by the fast renderer and did not change. On converged "
          "realistic frames the classifiers trained on plain simulation keep "
       << pr->truePositives << " of " << pp->truePositives << " true positives (before: " << earlier.truePositives << " of "
       << kBeforeConvergence[0].truePositives << "; at 100 spp: " << earlier.truePositivesUnfiltered << ") with "
       << pr->falsePositives << " false positives (before: " << earlier.falsePositives << "; at 100 spp: "
       << earlier.falsePositivesUnfiltered << ")"
       << (pr->truePositives * 2 < pp->truePositives ? ": the collapse of finding 2 still holds, now on frames that are not mostly noise."
                                                      : ": the collapse of finding 2 was the render noise; it does not hold on the new frames.")
       << "\n";
}

}  // namespace

std::string textureRealismMarkdown(const TextureRealismResults& results, const TextureRealismOptions& o,
                                   const std::string& command, const std::string& convergence) {
  std::ostringstream md;
  writeSetupAndDetections(md, results, o, command);
  writeFalsePositivesAndEkf(md, results);
  writeFindings(md, results, o.reduced);
  writeRealisticChanges(md, results, o);
  md << recordingSectionMarkdown(results, o, results.comparison.width > 0 ? std::string("figures/") + kRecordingFigure : "");
  if (!convergence.empty()) md << "\n" << convergence;
  md << "\nWhere the numbers differ from the thesis: its counts come from hand labels on its own arena and ISLA's "
        "real camera; ours from projection on our hall, and our realistic frames are rendered, so only the "
        "direction of each effect is comparable, not the counts.\n\n"
     << (o.reduced ? "Reduced run (fewer poses and samples): " : "Full run: ") << fixedDecimals(results.seconds / 60.0, 1) << " min on this machine ("
     << results.cyclesFramesRendered << " Cycles frames rendered, " << results.cyclesFramesReused
     << " reused from an earlier run into the same folder). Figures and the per-frame data "
        "are in the run's folder (`report.html`, `figures/`, `data/`).\n";
  return md.str();
}

}  // namespace omnicam
