// omnicam compare A B [--json] [--diff OUT.png] [--fail-psnr DB] [--fail-rmse X] [--fail-max X]
//                     [--tol X] [--disc]
// Exit 0 pass, 1 over a threshold, 2 bad input. One verdict line: "PASS …" or "FAIL …", or
// "NOTHRESHOLD …" when no --fail-* was given (nothing was checked, so nothing passed). With
// --json, stdout holds only the JSON and the verdict line goes to stderr.
#include <cstdio>
#include <memory>

#include "commands.h"
#include "atomic_file.h"
#include "cli_util.h"
#include "errors.h"
#include "image_compare.h"

namespace omnicam::cli {

namespace {

struct CompareArgs {
  std::string a, b, diff;
  bool json = false, disc = false;
  double failPsnr = -1.0, failRmse = -1.0, failMax = -1.0, tol = 1.0 / 255.0, diffScale = 0.05;
};

int runCompare(const CompareArgs& args, const CLI::App& cmd) {
  refuseUnless(cmd, "--diff-scale", !args.diff.empty(), "--diff");
  if (!args.diff.empty()) {
    if (!isSupportedImageOutput(args.diff)) throw InputError("--diff: " + args.diff + ": must end in .png or .exr");
    checkOutputFile(args.diff, "--diff");
  }
  const ImageRGBA a = readImage(args.a), b = readImage(args.b);
  CompareOptions options;
  options.tolerance = args.tol;
  options.discOnly = args.disc;
  const CompareResult r = compareImages(a, b, options);
  std::string failure;
  if (args.failPsnr >= 0.0 && r.psnrDb < args.failPsnr) failure += " psnr_db < " + std::to_string(args.failPsnr);
  if (args.failRmse >= 0.0 && r.rmse > args.failRmse) failure += " rmse > " + std::to_string(args.failRmse);
  if (args.failMax >= 0.0 && r.maxAbs > args.failMax) failure += " max_abs > " + std::to_string(args.failMax);
  if (!args.diff.empty()) writeImageAtomic(args.diff, differenceHeatmap(a, b, args.diffScale));
  const bool checked = args.failPsnr >= 0.0 || args.failRmse >= 0.0 || args.failMax >= 0.0;
  const char* verdict = !checked ? "NOTHRESHOLD" : failure.empty() ? "PASS" : "FAIL";
  if (args.json) {
    nlohmann::json j = compareResultToJson(r);
    j["verdict"] = verdict;
    if (checked) j["pass"] = failure.empty();
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("compared %ld pixels%s\n  RMSE %.6g  PSNR %.2f dB  SSIM %.5f\n  max abs %.6g at (%d, %d)  over tol %.6g: %.4f%%\n",
                r.pixels, args.disc ? " inside the mirror disc" : "", r.rmse, r.psnrDb, r.ssim, r.maxAbs, r.maxI, r.maxJ,
                args.tol, 100.0 * r.fracOverTol);
  }
  std::fprintf(args.json ? stderr : stdout, "%s psnr_db=%.2f rmse=%.6g max_abs=%.6g%s\n", verdict, r.psnrDb, r.rmse,
               r.maxAbs, checked ? failure.c_str() : " (no --fail-psnr, --fail-rmse or --fail-max given: nothing checked)");
  return failure.empty() ? 0 : 1;
}

}  // namespace

void addCompareCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "Compare two images pixel by pixel (PASS/FAIL, exit 0/1)");
  cmd->add_option("a", args->a, "First image (EXR or PNG)")->required();
  cmd->add_option("b", args->b, "Second image")->required();
  cmd->add_flag("--json", args->json, "Print the metrics as JSON");
  cmd->add_option("--diff", args->diff, "Write a difference heat map (PNG/EXR)");
  cmd->add_option("--diff-scale", args->diffScale, "Difference shown as white in the heat map (default 0.05)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--fail-psnr", args->failPsnr, "Fail below this PSNR (dB)");
  cmd->add_option("--fail-rmse", args->failRmse, "Fail above this RMSE");
  cmd->add_option("--fail-max", args->failMax, "Fail above this max abs error");
  cmd->add_option("--tol", args->tol, "Per-channel tolerance for frac_over_tol (default 1/255)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--disc", args->disc, "Only pixels wholly inside the mirror disc in both images");
  cmd->callback([args, cmd, &exitCode] { exitCode = runCompare(*args, *cmd); });
}

}  // namespace omnicam::cli
