// omnicam compare A B [--json] [--diff OUT.png] [--fail-psnr DB] [--fail-rmse X] [--fail-max X]
//                     [--tol X] [--disc] [--box-downsample]
// omnicam compare DIR_A DIR_B [--fail-psnr DB] [--fail-max X] [--report OUT.html] [--junit OUT.xml] [--json] [--tol X] [--disc]
// Exit 0 pass, 1 over a threshold, 2 bad input. One verdict line: "PASS …" or "FAIL …", or
// "NOTHRESHOLD …" when no --fail-* was given (nothing was checked, so nothing passed). With
// --json, stdout holds only the JSON and the verdict line goes to stderr.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "atomic_file.h"
#include "commands.h"
#include "dataset_compare.h"
#include "cli_util.h"
#include "errors.h"
#include "image_compare.h"
#include "memory_budget.h"
#include "number_format.h"
#include "render_records.h"

namespace omnicam::cli {

namespace {

struct CompareArgs {
  std::string a, b, diff, report, junit;
  bool json = false, disc = false, boxDownsample = false, commonFrames = false, anyPose = false;
  double failPsnr = 0.0, failRmse = 0.0, failMax = 0.0, tol = 1.0 / 255.0, diffScale = 0.05;
};

// The --fail-* flags given, whatever their value: a PSNR may be below 0 (an HDR image's errors
// beyond its peak of 1), and --fail-psnr -5 is a threshold like any other.
CompareThresholds thresholdsOf(const CompareArgs& args, const CLI::App& cmd) {
  CompareThresholds t;
  if (cmd.count("--fail-psnr")) t.minPsnrDb = args.failPsnr;
  if (cmd.count("--fail-rmse")) t.maxRmse = args.failRmse;
  if (cmd.count("--fail-max")) t.maxAbs = args.failMax;
  return t;
}

// Two dataset folders: every frame and camera, matched by manifest.
int runDatasetCompare(const CompareArgs& args, const CLI::App& cmd) {
  refuseUnless(cmd, "--diff", false, "two images (datasets: --report shows heat maps of the worst frames)");
  refuseUnless(cmd, "--fail-rmse", false, "two images");
  refuseUnless(cmd, "--diff-scale", !args.report.empty(), "--report");
  refuseUnless(cmd, "--box-downsample", false, "two images");
  refuseUnless(cmd, "--any-pose", false, "two images (datasets are matched frame by frame)");
  // Neither output may land in a compared folder (a --junit over A's manifest destroyed it), nor
  // on the other output.
  std::vector<std::pair<std::string, std::string>> outputs;
  if (!args.report.empty()) outputs = {{args.report, "--report"}, {reportAssetsFolder(args.report), "--report (its images)"}};
  if (!args.junit.empty()) outputs.push_back({args.junit, "--junit"});
  for (const auto& [output, flag] : outputs) {
    checkOutputIsOutsideFolder(output, flag, args.a, "the first dataset");
    checkOutputIsOutsideFolder(output, flag, args.b, "the second dataset");
  }
  if (!args.report.empty()) {
    checkOutputFile(args.report, "--report");
    const std::string assets = reportAssetsFolder(args.report);
    checkOutputFolder(assets, "--report (its images)");
    // Checked again where the images are written (SafeFolder); said here before any comparing.
    std::error_code ec;
    if (std::filesystem::is_symlink(assets, ec))
      throw InputError("--report (its images): " + showPath(assets) + " is a symbolic link; omnicam writes its images into a folder "
                       "of its own there and follows no link: remove it or give the report another name");
  }
  if (!args.junit.empty()) {
    checkOutputFile(args.junit, "--junit");
    if (!args.report.empty() && namesSameFile(args.junit, args.report))
      throw InputError("--junit: " + showPath(args.junit) + " is the --report file too: give each its own name");
  }
  DatasetCompareOptions options;
  options.image.tolerance = args.tol;
  options.image.discOnly = args.disc;
  options.thresholds = thresholdsOf(args, cmd);
  options.diffScale = args.diffScale;
  options.commonFramesOnly = args.commonFrames;
  const DatasetCompareResult r = compareDatasets(args.a, args.b, options);
  // The small file first: a report that cannot be finished removes its images, so an exit 5
  // leaves at most a whole JUnit file.
  if (!args.junit.empty()) writeTextAtomically(args.junit, datasetCompareJUnit(args.a, args.b, r, options));
  if (!args.report.empty()) writeDatasetCompareReport(args.report, args.a, args.b, r, options);
  const bool checked = options.thresholds.any();
  const char* verdict = !checked ? "NOTHRESHOLD" : r.failures ? "FAIL" : "PASS";
  if (args.json) {
    nlohmann::json frames = nlohmann::json::array();
    for (const FrameComparison& f : r.frames) {
      nlohmann::json j = compareResultToJson(f.result);
      j["frame"] = f.index;
      j["camera"] = f.camera;
      if (checked) j["pass"] = !f.failed;
      frames.push_back(j);
    }
    nlohmann::json summary = {{"images", r.frames.size()}, {"failures", r.failures}, {"verdict", verdict},
                              {"mean_psnr_db", std::isfinite(r.meanPsnrDb) ? nlohmann::json(r.meanPsnrDb) : nlohmann::json("inf")},
                              {"min_psnr_db", std::isfinite(r.minPsnrDb) ? nlohmann::json(r.minPsnrDb) : nlohmann::json("inf")},
                              {"identical_images", r.identical}, {"mean_ssim", r.meanSsim}, {"max_abs", r.maxAbs},
                              {"max_abs_alpha", r.alphaCompared ? nlohmann::json(r.maxAbsAlpha) : nlohmann::json(nullptr)},
                              {"notes", r.notes}, {"frames", frames}};
    std::printf("%s\n", summary.dump(2).c_str());
  } else {
    std::vector<const FrameComparison*> worst;
    for (const FrameComparison& f : r.frames) worst.push_back(&f);
    std::sort(worst.begin(), worst.end(), [](auto* x, auto* y) { return x->result.psnrDb < y->result.psnrDb; });
    std::printf("compared %zu images (frames x cameras)%s\n  mean PSNR %.2f dB%s  worst %.2f dB  mean SSIM %.5f  max abs %.9g  max abs of alpha %s\n",
                r.frames.size(), args.disc ? " wholly imaged in both (alpha 1)" : "", r.meanPsnrDb,
                r.identical ? (" (over the " + std::to_string(r.frames.size() - static_cast<size_t>(r.identical)) + " whose colour differs; " +
                               std::to_string(r.identical) + " of identical colour)").c_str()
                            : "",
                r.minPsnrDb, r.meanSsim, r.maxAbs, datasetAlphaText(r).c_str());
    // Only images that differ: among identical ones (∞ dB) none is worst.
    for (size_t k = 0; k < std::min<size_t>(3, worst.size()) && std::isfinite(worst[k]->result.psnrDb); ++k)
      std::printf("  worst: frame %d %s  %.2f dB\n", worst[k]->index, worst[k]->camera.c_str(), worst[k]->result.psnrDb);
    int broken = 0;
    for (const FrameComparison& f : r.frames)
      if (!f.result.allFinite() && ++broken <= 3)
        std::printf("  frame %d %s: %s\n", f.index, f.camera.c_str(), nonFiniteText(f.result).c_str());
    if (broken > 3) std::printf("  and %d more frames with pixels not finite\n", broken - 3);
    for (const std::string& note : r.notes) std::printf("  note: %s\n", note.c_str());
  }
  std::fprintf(args.json ? stderr : stdout, "%s images=%zu failing=%d min_psnr_db=%.2f mean_psnr_db=%.2f%s\n", verdict,
               r.frames.size(), r.failures, r.minPsnrDb, r.meanPsnrDb,
               checked ? "" : " (no --fail-psnr or --fail-max given: nothing checked)");
  return r.failures ? 1 : 0;
}

// Two images read a band of rows at a time: memory for a few rows, whatever their size.
CompareResult compareStreamed(const CompareArgs& args, const CompareOptions& options) {
  ImageRowReader a = ImageRowReader::openFile(args.a), b = ImageRowReader::openFile(args.b);
  requireMemory(imageRowsCompareBytes(a, b), "comparing the two images");
  return compareImageRows(a, b, options);
}

// Both images whole, for the heat map (--diff) or to bring the larger to the smaller's size
// (--box-downsample), sized from the headers before either is decoded.
CompareResult compareWhole(const CompareArgs& args, const CompareOptions& options) {
  const int64_t bytesA = imageDecodeBytes(args.a), bytesB = imageDecodeBytes(args.b);
  // Both images, and at the smaller one's size the larger one's downsampled copy and the heat map.
  const int64_t extra = std::min(bytesA, bytesB) * ((args.boxDownsample ? 1 : 0) + (args.diff.empty() ? 0 : 1));
  requireMemory(bytesA + bytesB + extra, args.diff.empty() ? "comparing the two images"
                                                           : "comparing the two images and their heat map (--diff)");
  ImageRowReader readerA = ImageRowReader::openFile(args.a), readerB = ImageRowReader::openFile(args.b);
  ColourImagePair pair = readColourImages(readerA, readerB);
  ImageRGBA &a = pair.a, &b = pair.b;
  if (args.boxDownsample) {
    if (const auto n = wholeMultiple(a.width, a.height, b.width, b.height)) b = boxDownsample(b, *n);
    else if (const auto m = wholeMultiple(b.width, b.height, a.width, a.height)) a = boxDownsample(a, *m);
    else
      throw InputError("--box-downsample: neither image is a whole multiple (2x or more) of the other in both directions (" +
                       std::to_string(a.width) + "x" + std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                       std::to_string(b.height) + ")");
  }
  const CompareResult r = compareImagePair(pair, options);
  if (!args.diff.empty()) writeImageAtomic(args.diff, differenceHeatmap(a, b, args.diffScale));
  return r;
}

// Two images whose sizes differ by a whole factor are most likely a POV-Ray job's render beside
// omnicam's image: said so, with the flag that compares them.
void explainSizes(const CompareArgs& args) {
  const ImageRowReader a = ImageRowReader::openFile(args.a), b = ImageRowReader::openFile(args.b);
  const auto n = wholeMultiple(a.width(), a.height(), b.width(), b.height()), m = wholeMultiple(b.width(), b.height(), a.width(), a.height());
  if (!n && !m) return;
  const std::string size = std::to_string(a.width()) + "x" + std::to_string(a.height()) + " vs " + std::to_string(b.width()) +
                           "x" + std::to_string(b.height());
  throw InputError("compare: image sizes differ (" + size + "): one is " + std::to_string(n ? *n : *m) +
                   "x the other, as a POV-Ray job's render.exr is for " + std::to_string(n ? *n * *n : *m * *m) +
                   " spp; --box-downsample averages its blocks first (docs/povray.md)");
}

int runCompare(const CompareArgs& args, const CLI::App& cmd) {
  std::error_code ec;
  const bool folderA = std::filesystem::is_directory(args.a, ec), folderB = std::filesystem::is_directory(args.b, ec);
  if (folderA != folderB) {
    // Beside a folder, a name that is nothing is most likely a misspelt folder.
    const std::string& other = folderA ? args.b : args.a;
    if (!std::filesystem::exists(other, ec)) throw InputError(showPath(other) + ": no such file or folder");
    throw InputError("compare: give two images or two dataset folders (got one of each)");
  }
  if (folderA) return runDatasetCompare(args, cmd);
  // Neither a folder: a name that is nothing may be a misspelt image or dataset folder.
  for (const std::string& path : {args.a, args.b})
    if (std::filesystem::symlink_status(path, ec).type() == std::filesystem::file_type::not_found)  // not EACCES
      throw InputError(showPath(path) + ": no such file or folder (compare takes two images or two dataset folders)");
  refuseUnless(cmd, "--report", false, "two dataset folders");
  refuseUnless(cmd, "--junit", false, "two dataset folders");
  refuseUnless(cmd, "--common-frames", false, "two dataset folders");
  refuseUnless(cmd, "--diff-scale", !args.diff.empty(), "--diff");
  if (!args.diff.empty()) {
    if (!isSupportedImageOutput(args.diff)) throw InputError("--diff: " + showPath(args.diff) + ": must end in .png or .exr");
    checkOutputFile(args.diff, "--diff");
    checkOutputIsNotInput(args.diff, "--diff", args.a, "the first image");
    checkOutputIsNotInput(args.diff, "--diff", args.b, "the second image");
  }
  CompareOptions options;
  options.tolerance = args.tol;
  options.discOnly = args.disc;
  if (!args.boxDownsample) explainSizes(args);
  // What the sidecars say: images of another place are refused unless asked for (a PASS between
  // them would pass nothing); a pose apart by what typing it loses, or asked for, is a note.
  const SidecarComparison sidecars = compareSidecars(args.a, args.b);
  if (sidecars.posesApart && !args.anyPose)
    throw InputError("compare: " + showPath(args.b) + " is of another pose than " + showPath(args.a) + " (their sidecars: " +
                     sidecars.poses + "); --any-pose compares them all the same");
  std::vector<std::string> notes = sidecars.notes;
  if (!sidecars.poses.empty()) notes.insert(notes.begin(), "pose differs: " + sidecars.poses);
  const CompareResult r = args.diff.empty() && !args.boxDownsample ? compareStreamed(args, options) : compareWhole(args, options);
  const CompareThresholds thresholds = thresholdsOf(args, cmd);
  std::string failure;
  for (const std::string& failed : thresholds.failures(r)) failure += " " + failed;
  const bool checked = thresholds.any();
  const char* verdict = !checked ? "NOTHRESHOLD" : failure.empty() ? "PASS" : "FAIL";
  if (args.json) {
    nlohmann::json j = compareResultToJson(r);
    j["verdict"] = verdict;
    if (checked) j["pass"] = failure.empty();
    j["notes"] = notes;
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("compared %ld pixels%s\n  RMSE %.6g  PSNR %.2f dB  SSIM %.5f\n  max abs %.9g at (%d, %d)  max abs of alpha %s  over tol %.6g: %.4f%%\n",
                r.pixels, args.disc ? " wholly imaged in both (alpha 1)" : "", r.rmse, r.psnrDb, r.ssim, r.maxAbs, r.maxI, r.maxJ,
                alphaText(r).c_str(), args.tol, 100.0 * r.fracOverTol);
    if (!r.allFinite()) std::printf("  %s\n", nonFiniteText(r).c_str());
    for (const std::string& note : notes) std::printf("  note: %s\n", note.c_str());
  }
  std::fprintf(args.json ? stderr : stdout, "%s psnr_db=%.2f rmse=%.6g max_abs=%.9g%s\n", verdict, r.psnrDb, r.rmse,
               r.maxAbs, checked ? failure.c_str() : " (no --fail-psnr, --fail-rmse or --fail-max given: nothing checked)");
  return failure.empty() ? 0 : 1;
}

}  // namespace

void addCompareCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "Compare two images, or two datasets frame by frame (PASS/FAIL, exit 0/1)");
  cmd->add_option("a", args->a, "First image (EXR or PNG), or dataset folder")->required();
  cmd->add_option("b", args->b, "Second image, or dataset folder (with a manifest, or in the dataset layout)")->required();
  cmd->add_option("--report", args->report, "Datasets: write an HTML report (worst frames with heat maps)");
  cmd->add_option("--junit", args->junit, "Datasets: write JUnit XML, one test case per frame and camera");
  cmd->add_flag("--json", args->json, "Print the metrics as JSON");
  cmd->add_option("--diff", args->diff, "Write a difference heat map (PNG/EXR)");
  cmd->add_option("--diff-scale", args->diffScale, "Difference shown as white in heat maps (default 0.05)")
      ->check(numberIn(0, 1e6, true));
  cmd->add_option("--fail-psnr", args->failPsnr, "Fail below this PSNR (dB); datasets: any frame below")
      ->check(numberIn(-1e6, 1e6));
  cmd->add_option("--fail-rmse", args->failRmse, "Fail above this RMSE")->check(numberIn(0, 1e6));
  cmd->add_option("--fail-max", args->failMax, "Fail above this max abs error (colour, and alpha on its own); datasets: any frame above")->check(numberIn(0, 1e6));
  cmd->add_option("--tol", args->tol, "Per-channel tolerance for frac_over_tol (default 1/255)")->check(numberIn(0, 1e6));
  cmd->add_flag("--disc", args->disc, "Only pixels wholly imaged in both images (alpha 1: inside the mirror's disc, a fisheye's circle)");
  cmd->add_flag("--common-frames", args->commonFrames,
                "Datasets: compare only the frames both hold (a ground truth of fewer frames), saying how many were left out");
  cmd->add_flag("--any-pose", args->anyPose,
                "Two images whose sidecars say they were rendered at other poses: compare them all the same (a note says how far apart)");
  cmd->add_flag("--box-downsample", args->boxDownsample,
                "Average the larger image's NxN blocks first, N the whole factor between the sizes (a POV-Ray job's render.exr)");
  cmd->callback([args, cmd, &exitCode] { exitCode = runCompare(*args, *cmd); });
}

}  // namespace omnicam::cli
