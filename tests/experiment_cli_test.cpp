// End to end: `omnicam experiment texture-realism --quick` (fast and Blender renders, classifiers,
// detection, EKF, matplotlib figures, report) and `omnicam arena hall` from a real 360° photo and
// from an omni image unwrapped with `omnicam view --as panorama`.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "folder_snapshot.h"
#include "image.h"
#include "scene_loader.h"
#include "shell_command.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

testing::CommandResult omnicam(const std::string& args) {
  return testing::runShell(std::string(OMNICAM_BINARY) + " " + args + " 2>&1");
}

// A CSV file (RFC 4180 quoting) as rows of named fields; the header must be `header`.
std::vector<std::map<std::string, std::string>> readCsv(const std::string& file, const std::vector<std::string>& header) {
  std::ifstream in(file);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (size_t k = 0; k < line.size(); ++k) {
      const char ch = line[k];
      if (quoted && ch == '"' && k + 1 < line.size() && line[k + 1] == '"') fields.back() += '"', ++k;
      else if (ch == '"') quoted = !quoted;
      else if (ch == ',' && !quoted) fields.emplace_back();
      else fields.back() += ch;
    }
    rows.push_back(fields);
  }
  std::vector<std::map<std::string, std::string>> named;
  EXPECT_FALSE(rows.empty()) << file;
  if (rows.empty()) return named;
  EXPECT_EQ(rows.front(), header) << file;
  for (size_t r = 1; r < rows.size(); ++r) {
    EXPECT_EQ(rows[r].size(), header.size()) << file << " row " << r;
    std::map<std::string, std::string> row;
    for (size_t c = 0; c < header.size() && c < rows[r].size(); ++c) row[header[c]] = rows[r][c];
    named.push_back(row);
  }
  return named;
}

int integer(const std::map<std::string, std::string>& row, const std::string& key) { return std::stoi(row.at(key)); }
double number(const std::map<std::string, std::string>& row, const std::string& key) { return std::stod(row.at(key)); }

class ExperimentCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_experiment_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

// The realistic-convergence study (--quick: 32 px, 4 and 16 spp against 64, one pose), then the
// texture-realism experiment that embeds it in its document.
void expectQuickConvergenceStudy(const std::string& folder, const std::string& printed) {
  std::ifstream in(folder + "/convergence.json");
  const json c = json::parse(in);
  EXPECT_EQ(c["format"], "omnicam-realistic-convergence-2");
  std::map<std::string, std::map<int, double>> psnr;  // setup → spp → dB
  for (const json& point : c["ladder"]) {
    EXPECT_EQ(point["pose"], 0);
    const double db = point["psnr_db"].get<double>();
    EXPECT_GT(db, 5.0);
    EXPECT_LT(db, 99.0);
    psnr[point["setup"].get<std::string>()][point["spp"].get<int>()] = db;
    EXPECT_GE(point["outlier_share"].get<double>(), 0.0);
  }
  ASSERT_EQ(psnr.size(), 3u);
  ASSERT_TRUE(psnr.count("before") && psnr.count("physical") && psnr.count("today"));
  // Four times the samples: the physical setup's frames come about 6 dB closer to their reference
  // (before's 64-spp reference is itself mostly speckle); its lamps are cleaner at the same spp;
  // filtering its indirect light brings its frames closer still to the same (unfiltered) reference.
  EXPECT_GT(psnr["physical"][16], psnr["physical"][4] + 2.0);
  EXPECT_GT(psnr["physical"][16], psnr["before"][16] + 3.0);
  EXPECT_GT(psnr["today"][4], psnr["physical"][4] + 2.0);
  // The clamp darkens (Cycles counts everything seen in the mirror as indirect light).
  EXPECT_LT(c["clamp_bias"]["luminance_percent"].get<double>(), 0.0);
  EXPECT_EQ(c["experiment_check"]["size"], 64);
  EXPECT_EQ(c["experiment_check"]["reference_spp"], 64);
  EXPECT_EQ(c["experiment_check"]["psnr_db"].size(), 1u);
  EXPECT_EQ(c["paths"].size(), 2u);
  EXPECT_GT(readImage(folder + "/frames/today_16spp.png").width, 0);
  EXPECT_TRUE(fs::exists(folder + "/figures/convergence.svg"));
  EXPECT_NE(printed.find("## Are the realistic frames converged?"), std::string::npos) << printed;
  // The report is kept in the folder too, as every other experiment's is.
  const std::string report = testing::readFile(folder + "/convergence.md");
  EXPECT_NE(report.find("## Are the realistic frames converged?"), std::string::npos) << report;
  EXPECT_NE(printed.find(report), std::string::npos) << printed;
}

TEST_F(ExperimentCliTest, QuickTextureRealismWritesResultsFiguresAndReport) {
  const auto study = omnicam("experiment realistic-convergence --quick -o " + path("convergence"));
  ASSERT_EQ(study.code, 0) << study.out;
  expectQuickConvergenceStudy(path("convergence"), study.out);
  const std::string testCameras = " --test-camera " OMNICAM_SOURCE_DIR "/examples/recording/cool_noisy.json --test-camera " OMNICAM_SOURCE_DIR
                                  "/examples/recording/sharp_jpeg95.json";
  // An earlier run into the folder, with a condition this one lacks: its frame goes; a file of the
  // user's and a name reaching out of frames/ stay.
  fs::create_directories(path("run/frames"));
  std::ofstream(path("run/results.json"))
      << R"({"study": "texture-realism", "conditions": {"an_earlier_condition": {}, "../../escape": {}, "plain_to_plain": {}}})";
  for (const char* file : {"run/frames/an_earlier_condition.png", "run/frames/my_own.png", "escape.png"})
    std::ofstream(path(file)) << "bytes";
  // A study folder whose figure holds a script (someone else's folder): refused before the run,
  // never copied into the documents.
  fs::copy(path("convergence"), path("scripted"), fs::copy_options::recursive);
  std::string svg = testing::readFile(path("scripted/figures/convergence.svg"));
  svg.insert(svg.rfind("</svg>"), "<script>alert(1)</script>");
  std::ofstream(path("scripted/figures/convergence.svg"), std::ios::trunc) << svg;
  const auto scripted = omnicam("experiment texture-realism --quick -o " + path("refused") + " --doc " + path("refused.md") +
                                " --convergence " + path("scripted"));
  EXPECT_EQ(scripted.code, 2) << scripted.out;
  EXPECT_EQ(scripted.out, "omnicam: " + path("scripted/figures/convergence.svg") +
                              ": holds \"<script\", which the study's figure never does: not copied into the documents\n");
  EXPECT_FALSE(fs::exists(path("refused")));
  EXPECT_FALSE(fs::exists(path("refused.md")));
  const auto r = omnicam("experiment texture-realism --quick -o " + path("run") + " --doc " + path("doc.md") +
                         " --convergence " + path("convergence") + testCameras);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_FALSE(fs::exists(path("run/frames/an_earlier_condition.png")));
  EXPECT_TRUE(fs::exists(path("run/frames/my_own.png")));
  EXPECT_TRUE(fs::exists(path("escape.png")));
  EXPECT_TRUE(fs::exists(path("run/frames/plain_to_plain.png")));
  std::ifstream in(path("run/results.json"));
  const json results = json::parse(in);
  // The run's operating point: the quick run's sizes, the default detector, the test cameras given.
  EXPECT_EQ(results["study"], "texture-realism");
  const json& settings = results["settings"];
  EXPECT_EQ(settings["theta"], 1.0);
  EXPECT_EQ(settings["bins"], 32);
  EXPECT_EQ(settings["ablation"], true);
  EXPECT_EQ(settings["test_cameras"], json({OMNICAM_SOURCE_DIR "/examples/recording/cool_noisy.json",
                                            OMNICAM_SOURCE_DIR "/examples/recording/sharp_jpeg95.json"}));
  EXPECT_EQ(settings["test_stride"], 25);  // --quick: every 25th pose
  for (const char* condition : {"plain_to_plain", "plain_to_textured", "plain_to_realistic", "random_textures_to_realistic",
                                "path_to_realistic", "realistic_to_path"}) {
    ASSERT_TRUE(results["conditions"].contains(condition)) << condition;
    const json& c = results["conditions"][condition];
    EXPECT_EQ(c["frames"], 4) << condition;
    for (const char* key : {"true_positives", "false_positives"}) EXPECT_TRUE(c[key].is_number()) << condition << " " << key;
    EXPECT_EQ(c["mean_localisation_error_px"].is_number(), c["true_positives"].get<int>() > 0) << condition;
    ASSERT_TRUE(results["ekf"].contains(condition)) << condition;
    const json& e = results["ekf"][condition];
    EXPECT_NEAR(e["mean_improvement_cm"].get<double>(),
                e["mean_error_odometry_cm"].get<double>() - e["mean_error_ekf_cm"].get<double>(), 1e-9);
  }
  // On the plain hall the classifiers find beacons, to within a pixel, and the EKF uses them.
  const json& plain = results["conditions"]["plain_to_plain"];
  EXPECT_GE(plain["true_positives"].get<int>(), 4);
  EXPECT_LT(plain["mean_localisation_error_px"].get<double>(), 1.5);
  EXPECT_LT(results["ekf"]["plain_to_plain"]["mean_error_ekf_cm"].get<double>(),
            results["ekf"]["plain_to_plain"]["mean_error_odometry_cm"].get<double>());
  EXPECT_GT(results["seconds"].get<double>(), 0.0);
  // By the pixel detector: the two ceilings (realistic → realistic, the oracle), training through
  // drawn cameras, the ablation (nine stages) and two test cameras against four training sets each:
  // 6 + 2 + 2 + 9 + 8 conditions. By the footprint detector: the questions of transfer again, 7 + 9 + 8.
  std::vector<std::string> recordingConditions = {"realistic_to_realistic", "realistic_test_frames_to_realistic",
                                                  "path_recorded_to_realistic", "plain_recorded_to_realistic"};
  for (const char* stage : {"blur", "chromatic_aberration", "vignetting", "exposure", "white_balance", "bayer", "noise", "tone", "jpeg"})
    recordingConditions.push_back(std::string("path_recorded_without_") + stage + "_to_realistic");
  for (const char* camera : {"realistic_camera_1", "realistic_camera_2"})
    for (const char* train : {"plain", "path", "path_recorded", "plain_recorded"}) recordingConditions.push_back(std::string(train) + "_to_" + camera);
  std::vector<std::string> footprintConditions = {"plain_to_plain", "plain_to_realistic", "path_to_realistic"};
  footprintConditions.insert(footprintConditions.end(), recordingConditions.begin(), recordingConditions.end());
  for (const std::string& condition : footprintConditions) recordingConditions.push_back(condition + "_footprints");
  for (const std::string& condition : recordingConditions) {
    ASSERT_TRUE(results["conditions"].contains(condition)) << condition;
    EXPECT_EQ(results["conditions"][condition]["frames"], 4) << condition;
    ASSERT_TRUE(results["ekf"].contains(condition)) << condition;
  }
  ASSERT_EQ(results["conditions"].size(), 51u);
  ASSERT_EQ(results["ekf"].size(), 52u);
  // The EKF's floor: every beacon visible from a test pose measured exactly (used, or gated where
  // odometry drifted further than its covariance says), on the same drives as every condition.
  const json& exact = results["ekf"]["exact_measurements"];
  const json& plainCondition = results["conditions"]["plain_to_plain"];
  EXPECT_EQ(exact["measurements_used"].get<int>() + exact["measurements_gated"].get<int>(),
            plainCondition["true_positives"].get<int>() + plainCondition["missed"].get<int>());
  EXPECT_GT(exact["measurements_used"].get<int>(), 3 * exact["measurements_gated"].get<int>());
  EXPECT_EQ(exact["odometry_error_cm_per_drive"], results["ekf"]["plain_to_plain"]["odometry_error_cm_per_drive"]);
  EXPECT_LT(exact["mean_error_ekf_cm"].get<double>(), exact["mean_error_odometry_cm"].get<double>());
  // On the plain hall the footprint detector finds beacons too; its false positives are its own
  // bands placed off a band, so the goals' yellow and blue blobs the pixel detector counts are not.
  const json& plainFootprints = results["conditions"]["plain_to_plain_footprints"];
  EXPECT_GE(plainFootprints["true_positives"].get<int>(), 4);
  EXPECT_LT(plainFootprints["false_positives"].get<int>(), plain["false_positives"].get<int>());
  // The fixed test cameras' values no training camera has: the webcam records without a mosaic,
  // which every preset draws; cool_noisy's noise lies beyond every preset's; sharp_jpeg95 inside.
  EXPECT_EQ(results["beyond_training"], json::parse(R"({"realistic": ["bayer"],
      "realistic_camera_1": ["full_well_electrons", "read_noise", "row_noise"], "realistic_camera_2": []})"));
  // Its setting: no filter and a 3 × 3 median, each with 32 bins and its halvings, each with the
  // three scores and the three band tolerances, tried on the validation frames (6 poses, each
  // through 2 cameras of its fold's held-out preset); the chosen one scores best.
  const json& trials = results["footprint_trials"];
  const std::vector<std::string> scores = {"total", "standardised", "mean"};
  const std::vector<double> tolerances = {0.0, 1.0, 2.0};
  ASSERT_EQ(trials.size(), 54u);
  int bestScore = std::numeric_limits<int>::min();
  for (size_t k = 0; k < trials.size(); ++k) {
    EXPECT_EQ(trials[k]["median_px"], k < 27 ? 1 : 3);
    EXPECT_EQ(trials[k]["bins_per_channel"], 32 >> (k % 27 / 9));
    EXPECT_EQ(trials[k]["score"], scores[k / 3 % 3]);
    EXPECT_EQ(trials[k]["band_tolerance"].get<double>(), tolerances[k % 3]);
    EXPECT_LE(trials[k]["visible_beacons"].get<int>(), 144);  // 6 poses × 3 folds × 2 cameras, at most 4 beacons each
    EXPECT_EQ(trials[k]["visible_beacons"].get<int>() % 6, 0);  // each pose's beacons counted once per fold and camera
    EXPECT_EQ(trials[k]["visible_beacons"], trials[0]["visible_beacons"]);
    EXPECT_GT(trials[k]["visible_beacons"].get<int>(), 0);
    bestScore = std::max(bestScore, trials[k]["true_positives"].get<int>() - trials[k]["false_positives"].get<int>());
  }
  // The first trial with the best score: the smaller filter on a tie, then the finer resolution,
  // then total, standardised, mean, then the smaller tolerance.
  for (const json& t : trials)
    if (t["true_positives"].get<int>() - t["false_positives"].get<int>() == bestScore) {
      EXPECT_EQ(t["median_px"], results["footprint_median_px"]);
      EXPECT_EQ(t["bins_per_channel"], results["footprint_bins"]);
      EXPECT_EQ(t["score"], results["footprint_score"]);
      EXPECT_EQ(t["band_tolerance"], results["footprint_band_tolerance"]);
      break;
    }

  // --quick: every 25th of the 100 thesis-loop poses (4 test frames), 360 px, 6 training frames.
  const Scene field = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  ASSERT_TRUE(field.findPath("thesis-loop"));
  const std::vector<RobotPose> loop = field.findPath("thesis-loop")->poses;
  ASSERT_EQ(loop.size(), 100u);
  const std::set<std::string> colours = {"cyan", "magenta", "yellow"};

  // Per frame (data/detections.csv): the frames requested, in order, and totals that are
  // results.json's; the same four beacons (robocup2006 has four) visible in every condition.
  const auto detections = readCsv(path("run/data/detections.csv"),
                                  {"condition", "frame", "pose_index", "visible_beacons", "true_positives",
                                   "false_identifications", "false_positive_blobs", "mean_error_px"});
  ASSERT_EQ(detections.size(), 204u);  // 51 conditions of four frames
  const auto blobs = readCsv(path("run/data/false_positive_blobs.csv"),
                             {"condition", "frame", "colour", "area_px", "u", "v", "object"});
  std::vector<int> beaconsByRange(6, 0);  // each beacon's distance from the 4 test poses, in whole metres
  for (const Landmark& band : field.landmarks)
    if (band.name.size() > 6 && band.name.compare(band.name.size() - 6, 6, "_upper") == 0)
      for (size_t f = 0; f < 4; ++f) {
        const double range = std::hypot(band.position.x() - loop[25 * f].x, band.position.y() - loop[25 * f].y);
        ++beaconsByRange[std::min<size_t>(5, static_cast<size_t>(range))];
      }
  std::map<int, int> visibleAt;  // frame → visible beacons, from the first condition
  for (const auto& [key, c] : results["conditions"].items()) {
    SCOPED_TRACE(key);
    EXPECT_EQ(c["frames"], 4);
    int frames = 0, tp = 0, identifications = 0, blobCount = 0, missed = 0;
    double weightedError = 0.0;
    for (const auto& row : detections) {
      if (row.at("condition") != key) continue;
      EXPECT_EQ(integer(row, "frame"), frames);
      EXPECT_EQ(integer(row, "pose_index"), 25 * frames);
      const int visible = integer(row, "visible_beacons"), rowTp = integer(row, "true_positives");
      EXPECT_GE(visible, 0);
      EXPECT_LE(visible, 4);
      if (!visibleAt.count(frames)) visibleAt[frames] = visible;
      EXPECT_EQ(visible, visibleAt[frames]) << "frame " << frames;
      EXPECT_GE(rowTp, 0);
      EXPECT_LE(rowTp, visible);
      // A frame without a true positive has no error (an empty field), not an error of 0.
      const double error = rowTp ? number(row, "mean_error_px") : 0.0;
      if (rowTp == 0) {
        EXPECT_EQ(row.at("mean_error_px"), "");
      }
      EXPECT_GE(error, 0.0);
      EXPECT_LE(error, 8.0);  // a true positive lies within 8 px (at 360 px) of its beacon
      tp += rowTp, missed += visible - rowTp, weightedError += rowTp * error;
      identifications += integer(row, "false_identifications");
      blobCount += integer(row, "false_positive_blobs");
      ++frames;
    }
    EXPECT_EQ(frames, 4);
    EXPECT_EQ(c["true_positives"], tp);
    EXPECT_EQ(c["missed"], missed);
    EXPECT_EQ(c["false_identifications"], identifications);
    EXPECT_EQ(c["false_positive_blobs"], blobCount);
    EXPECT_EQ(c["false_positives"], identifications + blobCount);
    // By true range in whole metres: the buckets hold every visible beacon and true positive; all
    // four beacons are in view from each of the four test poses, so the visible ones are the
    // beacons' distances from those poses.
    int visibleSum = 0, foundSum = 0;
    for (size_t k = 0; k < 6; ++k) {
      const int visible = c["visible_by_range_m"][k], found = c["true_positives_by_range_m"][k];
      EXPECT_LE(found, visible) << k;
      visibleSum += visible, foundSum += found;
    }
    EXPECT_EQ(visibleSum, tp + missed);
    EXPECT_EQ(foundSum, tp);
    EXPECT_EQ(visibleSum, 16);
    EXPECT_EQ(c["visible_by_range_m"], json(beaconsByRange));
    // Means over true positives: null where there were none (a 0 would read as perfect accuracy).
    if (tp == 0) {
      for (const char* mean : {"mean_localisation_error_px", "mean_bearing_error_deg", "mean_range_error_cm"})
        EXPECT_TRUE(c[mean].is_null()) << mean;
    } else {
      EXPECT_NEAR(c["mean_localisation_error_px"].get<double>(), weightedError / tp, 1e-9);
      const double bearing = c["mean_bearing_error_deg"].get<double>(), range = c["mean_range_error_cm"].get<double>();
      EXPECT_GE(bearing, 0.0);
      EXPECT_LE(bearing, 180.0);
      EXPECT_GE(range, 0.0);
    }

    // Every false-positive blob listed once (data/false_positive_blobs.csv), on the objects
    // results.json names, most frequent first.
    std::map<std::string, int> onObject;
    int listed = 0, onHall = 0;
    for (const auto& row : blobs) {
      if (row.at("condition") != key) continue;
      ++listed;
      EXPECT_TRUE(colours.count(row.at("colour"))) << row.at("colour");
      EXPECT_GT(integer(row, "area_px"), 0);
      EXPECT_GE(integer(row, "frame"), 0);
      EXPECT_LT(integer(row, "frame"), 4);
      for (const char* axis : {"u", "v"}) {
        EXPECT_GE(number(row, axis), 0.0);
        EXPECT_LE(number(row, axis), 360.0);
      }
      ++onObject[row.at("object")];
      onHall += row.at("object").rfind("hall_", 0) == 0;
    }
    EXPECT_EQ(listed, blobCount);
    EXPECT_EQ(c["false_positive_blobs_on_hall"], onHall);
    // Bands of beacons named rightly are no false positives, however they fall on the mask (two at
    // most per beacon found); the footprint detector reports no blob but a beacon's two bands, so
    // its off-band blobs are bands of beacons named where they are not.
    EXPECT_LE(c["off_band_bands_of_found_beacons"].get<int>(), 2 * tp);
    if (key.ends_with("_footprints")) {
      EXPECT_LE(blobCount, 2 * identifications);
    }
    const json& sources = c["false_positive_sources"];
    EXPECT_LE(sources.size(), 5u);
    EXPECT_EQ(sources.size(), std::min<size_t>(5, onObject.size()));
    for (size_t k = 0; k < sources.size(); ++k) {
      EXPECT_EQ(sources[k][1].get<int>(), onObject[sources[k][0].get<std::string>()]) << sources[k];
      if (k > 0) {
        EXPECT_GE(sources[k - 1][1].get<int>(), sources[k][1].get<int>());
      }
    }

    // The EKF trace (data/ekf_<condition>.csv): every one of the 100 poses driven, the truth
    // is thesis-loop's, the odometry the same noisy drive in every condition, the covariance a
    // covariance, and results.json's errors of the first drive are the trace's; its means are
    // those over every drive.
    const auto ekf = readCsv(path("run/data/ekf_" + key + ".csv"),
                             {"frame", "true_x", "true_y", "true_theta", "odometry_x", "odometry_y", "ekf_x", "ekf_y",
                              "ekf_theta", "p_xx", "p_xy", "p_yy", "p_thth"});
    ASSERT_EQ(ekf.size(), loop.size());
    double odometryError = 0.0, ekfError = 0.0;
    for (size_t k = 0; k < ekf.size(); ++k) {
      const auto& row = ekf[k];
      EXPECT_EQ(integer(row, "frame"), static_cast<int>(k));
      EXPECT_NEAR(number(row, "true_x"), loop[k].x, 1e-7);
      EXPECT_NEAR(number(row, "true_y"), loop[k].y, 1e-7);
      EXPECT_NEAR(std::remainder(number(row, "true_theta") - loop[k].yawDeg * kPi / 180.0, 2.0 * kPi), 0.0, 1e-7);
      const double pxx = number(row, "p_xx"), pyy = number(row, "p_yy"), pxy = number(row, "p_xy");
      EXPECT_GT(pxx, 0.0);
      EXPECT_GT(pyy, 0.0);
      EXPECT_GT(number(row, "p_thth"), 0.0);
      EXPECT_LE(pxy * pxy, pxx * pyy * (1 + 1e-6));
      if (k == 0) {
        EXPECT_EQ(row.at("odometry_x"), row.at("true_x"));
        EXPECT_EQ(row.at("odometry_y"), row.at("true_y"));
        continue;
      }
      odometryError += 100.0 * std::hypot(number(row, "odometry_x") - loop[k].x, number(row, "odometry_y") - loop[k].y);
      ekfError += 100.0 * std::hypot(number(row, "ekf_x") - loop[k].x, number(row, "ekf_y") - loop[k].y);
    }
    const json& e = results["ekf"][key];
    const auto perDrive = [&](const char* name) { return e[name].get<std::vector<double>>(); };
    ASSERT_EQ(e["drives"], 16);
    ASSERT_EQ(perDrive("odometry_error_cm_per_drive").size(), 16u);
    ASSERT_EQ(perDrive("ekf_error_cm_per_drive").size(), 16u);
    EXPECT_NEAR(perDrive("odometry_error_cm_per_drive")[0], odometryError / 99.0, 1e-4);
    EXPECT_NEAR(perDrive("ekf_error_cm_per_drive")[0], ekfError / 99.0, 1e-4);
    const auto meanOfDrives = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / v.size(); };
    EXPECT_NEAR(e["mean_error_odometry_cm"].get<double>(), meanOfDrives(perDrive("odometry_error_cm_per_drive")), 1e-9);
    EXPECT_NEAR(e["mean_error_ekf_cm"].get<double>(), meanOfDrives(perDrive("ekf_error_cm_per_drive")), 1e-9);
    // Each drive's odometry noise is its own (no two drives alike), and the same in every condition.
    const std::vector<double> odometryPerDrive = perDrive("odometry_error_cm_per_drive");
    EXPECT_EQ(std::set<double>(odometryPerDrive.begin(), odometryPerDrive.end()).size(), 16u);
    EXPECT_EQ(e["odometry_error_cm_per_drive"], results["ekf"]["plain_to_plain"]["odometry_error_cm_per_drive"]);
    // A measurement is a detection with range and bearing: at most one per identification.
    const int used = e["measurements_used"].get<int>(), gated = e["measurements_gated"].get<int>();
    EXPECT_GE(used, 0);
    EXPECT_GE(gated, 0);
    EXPECT_LE(used + gated, tp + identifications);
    if (used == 0) {
      EXPECT_EQ(perDrive("ekf_error_cm_per_drive")[0], perDrive("odometry_error_cm_per_drive")[0]);  // nothing but odometry
    }

    // The report's tables hold these numbers.
    std::stringstream html;
    html << std::ifstream(path("run/report.html")).rdbuf();
    EXPECT_NE(html.str().find("<tr><td>" + key + "</td><td>4</td><td>" + std::to_string(tp) + "</td><td>" +
                              std::to_string(identifications + blobCount) + "</td><td>" + std::to_string(blobCount) +
                              "</td>"),
              std::string::npos);
    EXPECT_NE(html.str().find("</td><td>" + std::to_string(used) + " / " + std::to_string(gated) + "</td></tr>"),
              std::string::npos);
  }
  EXPECT_GT(results["ekf"]["plain_to_plain"]["measurements_used"].get<int>(), 0);

  // The trained histograms (data/histograms.json): both training sets, one classifier per
  // colour, 32 bins, totals that are the sums of their bins; every classifier of a set saw the
  // same labelled pixels, at most those inside the rim of 6 frames (radius 180 px).
  std::ifstream histogramFile(path("run/data/histograms.json"));
  const json histograms = json::parse(histogramFile);
  ASSERT_EQ(histograms.size(), 16u);
  for (const auto& [set, classifiers] : histograms.items()) {
    SCOPED_TRACE(set);
    // A recorded set sees each of its 6 frames twice (--quick: two drawn cameras per frame).
    // The oracle set sees the 4 realistic test frames.
    const double frames = set.find("_recorded") != std::string::npos ? 12.0 : set == "realistic_test_frames" ? 4.0 : 6.0;
    ASSERT_TRUE(histograms.contains(set));
    ASSERT_EQ(histograms[set].size(), 3u);
    uint64_t labelled = 0;
    for (const std::string& colour : colours) {
      const json& h = histograms[set][colour];
      EXPECT_EQ(h["bins_per_channel"], 32);
      for (const char* kind : {"positive", "negative"}) {
        uint64_t sum = 0;
        for (const json& bin : h[kind]) {
          ASSERT_EQ(bin.size(), 4u);
          for (int c = 0; c < 3; ++c) EXPECT_LE(bin[c].get<int>(), 255);
          EXPECT_GT(bin[3].get<uint64_t>(), 0u);
          sum += bin[3].get<uint64_t>();
        }
        EXPECT_EQ(h[std::string(kind) + "_total"].get<uint64_t>(), sum) << colour << " " << kind;
      }
      EXPECT_GT(h["positive_total"].get<uint64_t>(), 0u) << colour;
      const uint64_t total = h["positive_total"].get<uint64_t>() + h["negative_total"].get<uint64_t>();
      if (labelled == 0) labelled = total;
      EXPECT_EQ(total, labelled) << colour;
    }
    EXPECT_LE(static_cast<double>(labelled), frames * kPi * 180.0 * 180.0);
    EXPECT_GT(static_cast<double>(labelled), 0.9 * frames * kPi * 180.0 * 180.0);
  }

  // Every image the report shows exists: the four figures, and a 360 px frame per condition.
  std::stringstream html;
  html << std::ifstream(path("run/report.html")).rdbuf();
  std::set<std::string> shown;
  const std::string text = html.str();
  const std::regex image("<img src=\"([^\"]+)\"");
  for (std::sregex_iterator m(text.begin(), text.end(), image), end; m != end; ++m)
    shown.insert((*m)[1]);
  EXPECT_TRUE(shown.count("figures/texture_realism_recording.png"));
  // The .md's verdicts, transfer tables and the footprint detector's chosen setting are in the HTML too.
  for (const char* part : {"<h2>Which findings reproduce</h2>", "<ol>\n<li>In the plain hall", "A reduced run (<code>--quick</code>",
                           "<h2>Frames that transfer: the recording camera in training</h2>",
                           "<th>train ↓ test →</th>", "<th>stage held neutral</th>", ", chosen</strong></td>"})
    EXPECT_NE(text.find(part), std::string::npos) << part;
  for (const char* figure : {"detections_per_frame", "histograms", "ekf_path", "ekf_covariance"}) {
    const std::string file = std::string("figures/") + figure + ".png";
    EXPECT_TRUE(shown.count(file)) << file;
    EXPECT_GT(readImage(path("run/" + file)).width, 300) << figure;
  }
  for (const auto& [key, c] : results["conditions"].items()) {
    const std::string file = "frames/" + key + ".png";
    EXPECT_TRUE(shown.count(file)) << file;
    const ImageRGBA frame = readImage(path("run/" + file));
    EXPECT_EQ(frame.width, 360) << file;
    EXPECT_EQ(frame.height, 360) << file;
  }
  EXPECT_TRUE(shown.count("figures/texture_realism_recording.png"));
  EXPECT_EQ(shown.size(), 56u);  // four figures, the recording strip, one frame per condition
  for (const std::string& file : shown) EXPECT_TRUE(fs::exists(path("run/" + file))) << file;

  // The Markdown summary: the thesis' row beside the measured one.
  std::stringstream doc;
  doc << std::ifstream(path("doc.md")).rdbuf();
  const json& pp = results["conditions"]["plain_to_plain"];
  const std::string measured = "| plain_to_plain | USARSim, plain walls | 94 | 2 | 1.3 | 47.0 | " +
                               std::to_string(pp["true_positives"].get<int>()) + " | " +
                               std::to_string(pp["false_positives"].get<int>()) + " | " +
                               std::to_string(pp["false_identifications"].get<int>()) + " | " +
                               std::to_string(pp["false_positive_blobs_on_hall"].get<int>()) + " | " +
                               std::to_string(pp["missed"].get<int>()) + " | ";
  EXPECT_NE(doc.str().find(measured), std::string::npos) << measured << "\n" << doc.str();
  EXPECT_NE(doc.str().find("Which findings reproduce"), std::string::npos);
  // The study's section and its figure beside the document.
  EXPECT_NE(doc.str().find("## Are the realistic frames converged?"), std::string::npos);
  EXPECT_NE(doc.str().find("](figures/realistic_convergence.svg)"), std::string::npos);
  EXPECT_TRUE(fs::exists(path("figures/realistic_convergence.svg")));
  EXPECT_TRUE(fs::exists(path("run/figures/realistic_convergence.svg")));  // beside the run's own texture-realism.md too
  EXPECT_NE(doc.str().find("## What changed with the new realistic frames"), std::string::npos);
  // A reduced run says so, and does not set its numbers beside the full runs' of earlier issues.
  EXPECT_NE(doc.str().find("Reduced run (fewer poses and samples): "), std::string::npos);
  EXPECT_EQ(doc.str().find("Full run"), std::string::npos);
  EXPECT_EQ(doc.str().find("| TP before |"), std::string::npos);
  EXPECT_NE(doc.str().find("| FP blobs on the hall (walls, floor, ceiling) |"), std::string::npos);
  // The recording section: the table per test camera, the ablation, the ranges beside the test
  // cameras' values (each file named), the strip of four 240-px panels beside the document.
  for (const char* part : {"## Frames that transfer: the recording camera in training", "| path + drawn recording cameras |",
                           "### Which faults matter", "| noise |",
                           "### A detector with spatial context: whole beacon footprints", "#### Which faults matter to the footprint detector",
                           "| realistic (the test camera's own frames, other poses: a ceiling, not a method) |", "**They are never tuned to a test camera**",
                           "| camera 1: cool_noisy.json | camera 2: sharp_jpeg95.json |", "| bayer | webcam: one of rggb, bggr, grbg, gbrg;",
                           "](figures/texture_realism_recording.png)", "### Finding",
                           "#### Where beacons are lost: found of visible, by true range",
                           "| plain → plain (the bar) |", "| path + drawn cameras → camera 2: sharp_jpeg95.json |",
                           "| ceiling: the webcam's own frames → realistic |",
                           "| train → test | FP | beacons named where they are not | off-band blobs | not counted: bands of beacons named rightly, "
                           "mostly off their band |",
                           "| oracle: the test frames → realistic |",
                           // The values no training camera has, marked in the table and listed.
                           "| full_well_electrons | webcam: log-uniform [1000, 8000]; machine_vision: log-uniform [5000, 30000]; "
                           "phone: log-uniform [1500, 8000] | 2500 | **700** beyond | 20000 |",
                           "Beyond every training camera:\n- webcam (fixed; the realistic frames): `bayer`\n"
                           "- camera 1: cool_noisy.json: `full_well_electrons`, `read_noise`, `row_noise`\n"
                           "- camera 2: sharp_jpeg95.json: nothing\n"})
    EXPECT_NE(doc.str().find(part), std::string::npos) << part;
  // What each detector's plain → plain false positives are, from results.json.
  for (const char* key : {"plain_to_plain", "plain_to_plain_footprints"}) {
    const json& c = results["conditions"][key];
    const std::string makeup = "| plain → plain (the bar) | " + std::to_string(c["false_positives"].get<int>()) + " | " +
                               std::to_string(c["false_identifications"].get<int>()) + " | " +
                               std::to_string(c["false_positive_blobs"].get<int>()) + " | " +
                               std::to_string(c["off_band_bands_of_found_beacons"].get<int>()) + " |\n";
    EXPECT_NE(doc.str().find(makeup), std::string::npos) << key << ": " << makeup;
  }
  // The chosen setting's cell, bold, in its filter's, resolution's and score's row.
  const int chosenMedian = results["footprint_median_px"].get<int>();
  const std::string chosenRow = "| " + (chosenMedian == 1 ? std::string("none") : "3 × 3") + " | " +
                                std::to_string(results["footprint_bins"].get<int>()) + " | " +
                                results["footprint_score"].get<std::string>() + " |";
  const size_t row = doc.str().find(chosenRow);
  ASSERT_NE(row, std::string::npos) << chosenRow;
  const std::string rowText = doc.str().substr(row, doc.str().find('\n', row) - row);
  ASSERT_NE(rowText.find(", chosen**"), std::string::npos) << rowText;
  // Its column: the cells before it are the filter, the resolution, the score and the smaller tolerances.
  const auto barsBefore = std::count(rowText.begin(), rowText.begin() + static_cast<std::ptrdiff_t>(rowText.find(", chosen**")), '|');
  ASSERT_GE(barsBefore, 4);
  EXPECT_EQ(tolerances.at(static_cast<size_t>(barsBefore - 4)), results["footprint_band_tolerance"].get<double>()) << rowText;
  EXPECT_EQ(doc.str().find(", chosen**"), row + rowText.find(", chosen**"));  // chosen once
  EXPECT_EQ(doc.str().find(", chosen**", row + rowText.size()), std::string::npos);
  const ImageRGBA strip = readImage(path("figures/texture_realism_recording.png"));
  EXPECT_EQ(strip.width, 960);
  EXPECT_EQ(strip.height, 240);
  std::stringstream copy;
  copy << std::ifstream(path("run/texture-realism.md")).rdbuf();
  EXPECT_EQ(copy.str(), doc.str());

  // A second run into the folder reuses Cycles' frames (a Blender that cannot run proves it) and
  // finds the same.
  const auto again = testing::runShell("env OMNICAM_BLENDER=/bin/false " OMNICAM_BINARY " experiment texture-realism --quick --no-figures -o " +
                                       path("run") + testCameras + " 2>&1");
  ASSERT_EQ(again.code, 0) << again.out;
  std::ifstream secondIn(path("run/results.json"));
  const json second = json::parse(secondIn);
  EXPECT_EQ(second["conditions"], results["conditions"]);
}

// The names a run ends with are checked before its minutes of work: a folder under one of them,
// --doc naming the -o folder, a link at --doc's figures/. One line, exit 2, nothing written.
TEST_F(ExperimentCliTest, TheNamesARunEndsWithAreCheckedBeforeItsWork) {
  const std::vector<std::pair<std::string, std::string>> taken = {
      {"experiment calibration --quick -o " + path("c"), "c/calibration-study.md"},
      {"experiment texture-realism --quick --no-ablation -o " + path("t"), "t/report.html"},
      {"experiment realistic-convergence --quick -o " + path("v"), "v/convergence.json"},
      {"experiment path-convergence --quick -o " + path("p"), "p/path-convergence.md"},
      {"study --spp 1 -o " + path("s/s.md"), "s/figures/s_psnr.svg"}};
  for (const auto& [command, folder] : taken) fs::create_directories(dir_ / folder);
  fs::create_directories(dir_ / "elsewhere");
  fs::create_directories(dir_ / "d");
  fs::create_directory_symlink(dir_ / "elsewhere", dir_ / "d/figures");
  const auto before = test_support::folderSnapshot(dir_);
  for (const auto& [command, folder] : taken) {
    const auto r = omnicam(command);
    EXPECT_EQ(r.code, 2) << command << ": " << r.out;
    EXPECT_TRUE(testing::isOneLine(r.out)) << r.out;
    EXPECT_NE(r.out.find(path(folder) + " is an existing folder, not a file name"), std::string::npos) << r.out;
  }
  auto r = omnicam("experiment texture-realism --quick -o " + path("t1") + " --doc " + path("t1"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--doc: " + path("t1") + " is the -o folder: give the document a file name"), std::string::npos) << r.out;
  r = omnicam("experiment calibration --quick -o " + path("c2") + " --doc " + path("d/study.md"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--doc: " + path("d/figures") + " is not a folder"), std::string::npos) << r.out;
  EXPECT_TRUE(test_support::folderSnapshot(dir_) == before);
}

TEST_F(ExperimentCliTest, AFolderOfAnotherExperimentOrOfForeignResultsIsRefused) {
  // Both experiments end with results.json: one run into the other's folder would replace it and
  // mix the two. An older texture-realism run's results (no "study" yet) are known by their conditions.
  const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
      {"experiment calibration --quick -o " + path("t"), R"({"study": "texture-realism", "conditions": {}})",
       "holds the results of experiment \"texture-realism\", not calibration: give another folder"},
      {"experiment calibration --quick -o " + path("t"), R"({"conditions": {}})",
       "holds the results of experiment \"texture-realism\", not calibration"},
      {"experiment texture-realism --quick -o " + path("t"), R"({"study": "calibration"})",
       "holds the results of experiment \"calibration\", not texture-realism"},
      {"experiment texture-realism --quick -o " + path("t"), R"({"my": "own results"})",
       "not written by an omnicam experiment (it names no study): give another folder"},
      {"experiment calibration --quick -o " + path("t"), "my notes, not JSON",
       "results.json"}};
  fs::create_directories(path("t"));
  for (const auto& [command, results, message] : cases) {
    std::ofstream(path("t/results.json")) << results;
    const auto before = test_support::folderSnapshot(dir_);
    const auto r = omnicam(command);
    EXPECT_EQ(r.code, 2) << command << ": " << r.out;
    EXPECT_TRUE(testing::isOneLine(r.out)) << r.out;
    EXPECT_NE(r.out.find(path("t/results.json") + ": "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
    EXPECT_TRUE(test_support::folderSnapshot(dir_) == before) << command;
  }
  // A link named results.json is not followed.
  fs::remove(path("t/results.json"));
  std::ofstream(path("elsewhere.json")) << R"({"study": "calibration"})";
  fs::create_symlink(path("elsewhere.json"), path("t/results.json"));
  const auto r = omnicam("experiment calibration --quick -o " + path("t"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("results.json: a link (omnicam follows none in its outputs): give another folder"), std::string::npos) << r.out;
}

// Every experiment marks its folder first: a folder of other files, or another study's (by its
// mark, or by its results file when written before marks), is refused before any work — one line,
// exit 2, nothing written. The quick runs below run twice into their own marked folders.
TEST_F(ExperimentCliTest, AFolderOfOtherFilesOrOfAnotherStudyIsRefusedByEveryExperiment) {
  const std::vector<std::string> experiments = {"texture-realism", "realistic-convergence", "path-convergence", "calibration"};
  fs::create_directories(path("mine"));
  std::ofstream(path("mine/notes.txt")) << "my notes";
  std::ofstream(path("mine/b.txt")) << "more";
  const std::vector<std::pair<std::string, std::string>> foreign = {
      {"convergence.json", "realistic-convergence"}, {"path-convergence.json", "path-convergence"}};
  for (const auto& [file, study] : foreign) {
    fs::create_directories(path(study));
    std::ofstream(path(study + "/" + file)) << "{}";
  }
  fs::create_directories(path("marked"));
  std::ofstream(path("marked/.omnicam-experiment.json")) << R"({"study": "calibration"})";
  std::ofstream(path("marked/results.json")) << R"({"study": "calibration"})";
  for (const std::string& experiment : experiments) {
    const auto before = test_support::folderSnapshot(dir_);
    const auto refused = [&](const std::string& folder, const std::string& message) {
      const auto r = omnicam("experiment " + experiment + " --quick -o " + path(folder));
      EXPECT_EQ(r.code, 2) << experiment << " into " << folder << ": " << r.out;
      EXPECT_TRUE(testing::isOneLine(r.out)) << r.out;
      EXPECT_NE(r.out.find(message), std::string::npos) << experiment << " into " << folder << ": " << r.out;
    };
    refused("mine", path("mine") + ": holds files no omnicam experiment wrote (\"b.txt\" and 1 more): give an empty or new folder");
    for (const auto& [file, study] : foreign)
      if (study != experiment)
        refused(study, path(study + "/" + file) + ": holds the results of experiment \"" + study + "\", not " + experiment);
    if (experiment != "calibration")
      refused("marked", path("marked/.omnicam-experiment.json") + ": the folder is experiment \"calibration\"'s (its mark), not " +
                            experiment + "'s: give another folder");
    EXPECT_TRUE(test_support::folderSnapshot(dir_) == before) << experiment;
  }
}

TEST_F(ExperimentCliTest, ConvergenceOptionsAreCheckedBeforeAnythingRuns) {
  // A folder without the study's results: one line, exit 2, nothing written.
  fs::create_directories(path("empty"));
  auto r = omnicam("experiment texture-realism --quick -o " + path("run") + " --convergence " + path("empty"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(testing::isOneLine(r.out)) << r.out;
  EXPECT_NE(r.out.find("convergence.json"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(path("run/results.json")));
  // A results file that is not the study's.
  std::ofstream(path("empty/convergence.json")) << R"({"format": "something else"})";
  r = omnicam("experiment texture-realism --quick -o " + path("run") + " --convergence " + path("empty"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(testing::isOneLine(r.out)) << r.out;
  // The study takes no texture-realism options.
  r = omnicam("experiment realistic-convergence --quick -o " + path("conv") + " --doc " + path("doc.md"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_TRUE(testing::isOneLine(r.out)) << r.out;
  EXPECT_NE(r.out.find("--doc: only with experiment texture-realism, calibration or path-convergence"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(path("doc.md")));
}

TEST_F(ExperimentCliTest, ArenaHallFromARealPhotoAndFromAnUnwrappedOmniImage) {
  auto r = omnicam("arena hall --photo /usr/share/blender/datafiles/studiolights/world/interior.exr -o " + path("lab/hall.json"));
  ASSERT_EQ(r.code, 0) << r.out;
  r = omnicam("render " + path("lab/hall.json") + " --size 96 -o " + path("lab.png"));
  ASSERT_EQ(r.code, 0) << r.out;

  // The thesis' route: an omni image, unwrapped, projected onto the walls.
  ASSERT_EQ(omnicam("render " + path("lab/hall.json") + " --size 200 --shading lit -o " + path("omni.png")).code, 0);
  ASSERT_EQ(omnicam("view " + path("omni.png") + " --as panorama -o " + path("pano.png")).code, 0);
  r = omnicam("arena hall --photo " + path("pano.png") + " -o " + path("fromomni/hall.json"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(path("fromomni/hall_textures/hall_wall_north.png")));
  ASSERT_EQ(omnicam("render " + path("fromomni/hall.json") + " --size 96 -o " + path("fromomni.png")).code, 0);

  // A panorama in the thesis variant has no exact elevation per row: refused, nothing written.
  ASSERT_EQ(omnicam("view " + path("omni.png") + " --as panorama --variant thesis -o " + path("thesis.png")).code, 0);
  r = omnicam("arena hall --photo " + path("thesis.png") + " -o " + path("bad/hall.json"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("view.variant"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(path("bad/hall.json")));
  r = omnicam("arena maze -o " + path("x.json"));
  EXPECT_EQ(r.code, 2) << r.out;
}

}  // namespace
}  // namespace omnicam

namespace omnicam {
namespace {

// experiment path-convergence --quick: nine frames against Cycles, each converged fast frame within
// a few percent of Cycles' mean radiance; a rerun reads Cycles' frames back from data/ and measures
// the same numbers (the fast side is deterministic, the Cycles side the cached frames).
TEST_F(ExperimentCliTest, QuickPathConvergenceMeasuresNineFramesAndReusesCyclesFrames) {
  const auto first = omnicam("experiment path-convergence --quick -o " + path("pc"));
  ASSERT_EQ(first.code, 0) << first.out;
  EXPECT_EQ(json::parse(testing::readFile(path("pc/.omnicam-experiment.json"))), json({{"study", "path-convergence"}}));
  const json results = json::parse(std::ifstream(path("pc/path-convergence.json")));
  ASSERT_EQ(results["frames"].size(), 9u);
  for (const json& f : results["frames"]) {
    EXPECT_NEAR(f["mean_ratio"].get<double>(), 1.0, 0.03) << f["scene"];  // 64 spp each side, 48 px
    EXPECT_GT(f["converged_psnr_db"].get<double>(), 25.0) << f["scene"];
    // Cycles' realistic frame is timed per frame of its session, its start-up apart.
    EXPECT_GT(f["cycles_realistic_seconds"].get<double>(), 0.0) << f["scene"];
    EXPECT_GT(f["cycles_startup_seconds"].get<double>(), 0.0) << f["scene"];
  }
  for (const json& rung : results["ladder"])
    if (rung["engine"] == "blender") {
      EXPECT_GT(rung["startup_seconds"].get<double>(), 0.0) << rung.dump();
    }
  EXPECT_TRUE(fs::exists(path("pc/data/textured_hall_cycles_64spp_seed0.json")));
  // A cache kept before Cycles was timed per frame (no start-up): its frames are reused, its
  // seconds (a session over its frames) shown as unknown rather than passed off as a frame's.
  const std::string kept = path("pc/data/textured_hall_cycles_4spp_denoised_seed5.json");
  json old = json::parse(std::ifstream(kept));
  ASSERT_TRUE(old.contains("startup_seconds")) << old.dump();
  old.erase("startup_seconds");
  std::ofstream(kept) << old.dump(2);
  const auto second = omnicam("experiment path-convergence --quick -o " + path("pc"));
  ASSERT_EQ(second.code, 0) << second.out;
  const json again = json::parse(std::ifstream(path("pc/path-convergence.json")));
  for (size_t k = 0; k < 9; ++k) {
    const json &now = again["frames"][k], &before = results["frames"][k];
    EXPECT_EQ(now["converged_psnr_db"], before["converged_psnr_db"]) << k;
    EXPECT_EQ(now["cycles_realistic_psnr_db"], before["cycles_realistic_psnr_db"]) << k;  // the kept frames
    if (now["scene"] == "textured hall") {
      EXPECT_EQ(now["cycles_startup_seconds"].get<double>(), 0.0) << k;
      EXPECT_EQ(now["cycles_realistic_seconds"].get<double>(), 0.0) << k;
    } else {
      EXPECT_EQ(now["cycles_startup_seconds"], before["cycles_startup_seconds"]) << k;  // kept with the frames
    }
  }
}


// `omnicam experiment calibration --quick`: the ideal rig, the pinhole 2 mm across and 2 mm along
// the axis, one seed of twelve AprilGrid views at 720 px. What must hold whatever the numbers:
// the ideal rig's calibration from exact corners is the rig (held-out error and triangulation
// nil; its EKF with the nominal model is the EKF with the true rays, the same rays); a pinhole
// moved across the axis is no longer central (the best central model errs > 1 px at 0.5 m) and
// the thesis' nominal model localises worse than the calibrated one. Figures and the document.
TEST_F(ExperimentCliTest, QuickCalibrationStudyMeasuresHeldOutErrorsAndWritesTheReport) {
  fs::create_directories(path("docs"));
  const mode_t umaskBefore = ::umask(022);  // the run's, inherited: its figures are checked against it below
  // A link planted under a figure's name in an earlier run's folder is replaced, never written through.
  fs::create_directories(path("cal/figures"));
  std::ofstream(path("cal/.omnicam-experiment.json")) << R"({"study": "calibration"})";
  std::ofstream(path("mine.svg")) << "mine";
  fs::create_symlink(path("mine.svg"), path("cal/figures/calibration_study_error.svg"));
  const auto r = omnicam("experiment calibration --quick -o " + path("cal") + " --doc " + path("docs/calibration-study.md"));
  ::umask(umaskBefore);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(testing::readFile(path("mine.svg")), "mine");
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(path("cal/figures/calibration_study_error.svg"))));
  // Figures get the umask's mode (022 here) as every other output, not mkstemp's 0600.
  for (const char* figure : {"cal/figures/calibration_study_error.svg", "cal/figures/calibration_study_residuals.png"})
    EXPECT_EQ(fs::status(path(figure)).permissions() & fs::perms::others_read, fs::perms::others_read) << figure;
  // What the folder holds is the run's results: nothing the plotting left (matplotlib's .cache).
  std::set<std::string> entries;
  for (const auto& entry : fs::directory_iterator(path("cal"))) entries.insert(entry.path().filename().string());
  EXPECT_EQ(entries, (std::set<std::string>{".omnicam-experiment.json", "arenas", "calibration-study.md", "data", "figures",
                                            "results.json"}));
  const json results = json::parse(testing::readFile(path("cal/results.json")));
  ASSERT_EQ(results["rigs"].size(), 3u);
  std::map<std::string, json> rigs;
  for (const json& rig : results["rigs"]) rigs[rig["label"].get<std::string>()] = rig;
  ASSERT_TRUE(rigs.count("ideal") && rigs.count("lateral 2 mm") && rigs.count("axial 2 mm"));
  const auto run = [](const json& rig, const std::string& source) {
    for (const json& calibration : rig["runs"])
      if (calibration["source"] == source) return calibration;
    return json();
  };
  const json idealExact = run(rigs["ideal"], "exact");
  ASSERT_TRUE(idealExact["converged"].get<bool>()) << idealExact.dump();
  EXPECT_LT(idealExact["rms_px"].get<double>(), 1e-3);
  for (const json& h : idealExact["held_out"]) {
    EXPECT_LT(h["max_px"].get<double>(), 1e-2) << h.dump();
    EXPECT_LT(h["rms_mrad"].get<double>(), 1e-2) << h.dump();
    EXPECT_EQ(h["unmodelled_share"].get<double>(), 0.0);
  }
  EXPECT_LT(idealExact["triangulation"]["p90_mm"].get<double>(), 0.01);
  EXPECT_GT(idealExact["triangulation"]["points"].get<int>(), 500);
  // Detections calibrate too, less exactly.
  for (const char* source : {"detected", "detected_noisy"}) {
    const json detected = run(rigs["ideal"], source);
    ASSERT_TRUE(detected["converged"].get<bool>()) << source;
    EXPECT_LT(detected["rms_px"].get<double>(), 0.5) << source;
    EXPECT_GT(detected["corners"].get<int>(), 200) << source;
  }
  // The ideal rig's nominal model (the thesis' landmark geometry) is its true rays.
  EXPECT_NEAR(rigs["ideal"]["ekf_cm"]["nominal"].get<double>(), rigs["ideal"]["ekf_cm"]["true_rays"].get<double>(), 1e-6);
  EXPECT_LT(rigs["ideal"]["ekf_cm"]["true_rays"].get<double>(), rigs["ideal"]["ekf_cm"]["odometry"].get<double>() / 2);
  const json& lateral = rigs["lateral 2 mm"];
  EXPECT_GT(lateral["best_fit_held_out"][1]["rms_px"].get<double>(), 1.0);
  EXPECT_LT(rigs["axial 2 mm"]["best_fit_held_out"][1]["rms_px"].get<double>(), 0.1) << "along the axis: almost central";
  EXPECT_GT(lateral["ekf_cm"]["nominal"].get<double>(), 2 * lateral["ekf_cm"]["calibrated_exact"].get<double>());
  // The report: the headline, the tables, the figures beside the document.
  const std::string doc = testing::readFile(path("docs/calibration-study.md"));
  EXPECT_NE(doc.find("## Headline"), std::string::npos);
  EXPECT_NE(doc.find("| lateral 2 mm | best central model |"), std::string::npos);
  EXPECT_EQ(doc, testing::readFile(path("cal/calibration-study.md")));
  for (const char* figure : {"calibration_study_error.svg", "calibration_study_residuals.png"}) {
    EXPECT_TRUE(fs::is_regular_file(path(std::string("docs/figures/") + figure))) << figure;
    EXPECT_GT(fs::file_size(path(std::string("cal/figures/") + figure)), 10000u) << figure;
  }
  EXPECT_TRUE(fs::is_regular_file(path("cal/data/residual_lateral_2_mm_exact.f32")));
}

}  // namespace
}  // namespace omnicam

namespace omnicam {
namespace {

// Every Markdown image link `![…](target)` in `markdown`, percent-decoded.
std::vector<std::string> imageLinks(const std::string& markdown) {
  std::vector<std::string> links;
  const std::regex link(R"(!\[[^\]]*\]\(([^)]*)\))");
  for (auto m = std::sregex_iterator(markdown.begin(), markdown.end(), link); m != std::sregex_iterator(); ++m) {
    const std::string target = (*m)[1];
    std::string decoded;
    for (size_t k = 0; k < target.size(); ++k)
      if (target[k] == '%' && k + 2 < target.size()) decoded += static_cast<char>(std::stoi(target.substr(k + 1, 2), nullptr, 16)), k += 2;
      else decoded += target[k];
    links.push_back(decoded);
  }
  return links;
}

std::string fileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// `omnicam study`: its header is the command that writes it again (flags and a quoted path
// included), its figures resolve, and a second study beside it keeps the first one's figures.
TEST_F(ExperimentCliTest, StudyReportsNameTheirCommandAndKeepTheirOwnFigures) {
  const std::string first = path("my study.md"), second = path("other.md");
  const auto r = omnicam("study -o '" + first + "' --spp 1 --timing-seconds 0.05");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string markdown = fileBytes(first);
  EXPECT_NE(markdown.find("Generated by `omnicam study -o '" + first + "' --spp 1 --timing-seconds 0.05`"), std::string::npos)
      << markdown.substr(0, 400);
  const std::vector<std::string> links = imageLinks(markdown);
  ASSERT_EQ(links.size(), 7u) << markdown;  // the PSNR plot and six frames
  std::map<std::string, std::string> before;
  for (const std::string& link : links) {
    EXPECT_TRUE(link.starts_with("figures/my study_")) << link;
    ASSERT_TRUE(fs::is_regular_file(dir_ / link)) << link;
    before[link] = fileBytes(dir_ / link);
  }
  ASSERT_EQ(omnicam("study -o " + second + " --spp 4 --timing-seconds 0.05").code, 0);
  for (const auto& [link, bytes] : before) EXPECT_EQ(fileBytes(dir_ / link), bytes) << link << " was replaced";
  for (const std::string& link : imageLinks(fileBytes(second))) EXPECT_TRUE(fs::is_regular_file(dir_ / link)) << link;
}

}  // namespace
}  // namespace omnicam
