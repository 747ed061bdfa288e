// omnicam dataset SPEC -o DIR [--overwrite] | --verify DIR | --status DIR
#include <atomic>
#include <csignal>
#include <cstdio>

#include "cli_util.h"
#include "commands.h"
#include "dataset_runner.h"
#include "errors.h"

namespace omnicam::cli {

namespace {

std::atomic<bool> interruptRequested{false};
extern "C" void onInterrupt(int) { interruptRequested.store(true); }

struct DatasetArgs {
  std::string spec, out, verify, status;
  bool overwrite = false;
};

void runDatasetVerb(const DatasetArgs& a, const CLI::App& cmd, int& exitCode) {
  const int verbs = !a.spec.empty() + !a.verify.empty() + !a.status.empty();
  if (verbs != 1) throw InputError("dataset: give a SPEC with -o DIR, or --verify DIR, or --status DIR");
  if (!a.verify.empty() || !a.status.empty()) {
    refuseUnless(cmd, "-o", false, "a SPEC");
    refuseUnless(cmd, "--overwrite", false, "a SPEC");
  }
  if (!a.verify.empty()) {
    const DatasetVerifyResult r = verifyDataset(a.verify);
    for (const std::string& problem : r.problems) std::printf("%s\n", problem.c_str());
    std::printf("%s: %s: %d files checked, %zu problems\n", r.ok() ? "PASS" : "FAIL", a.verify.c_str(), r.files,
                r.problems.size());
    exitCode = r.ok() ? 0 : 1;
    return;
  }
  if (!a.status.empty()) {
    const DatasetStatus s = datasetStatus(a.status);
    std::printf("%s: %d of %d frames finished%s\n", a.status.c_str(), s.finished, s.frames,
                s.complete ? " (complete)" : " (incomplete: run the same command again to resume)");
    exitCode = s.complete ? 0 : 1;
    return;
  }
  if (a.out.empty()) throw InputError("-o: a dataset needs an output folder");
  const DatasetSpec spec = loadDatasetSpec(a.spec);
  DatasetRunOptions options;
  options.dir = a.out;
  options.overwrite = a.overwrite;
  options.stopRequested = &interruptRequested;
  std::unique_ptr<Progress> progress;
  options.onStart = [&](int kept, int total) { progress = std::make_unique<Progress>("dataset " + a.out, total, kept); };
  options.onFrame = [&](int, int) { progress->step(); };
  // Ctrl-C finishes the frame in progress, writes the manifest and stops: the run resumes.
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  const DatasetRunResult r = runDataset(spec, options);
  if (progress) progress->finish();
  for (const std::string& note : r.notes) std::fprintf(stderr, "omnicam: note: %s\n", note.c_str());
  if (r.stopped) {
    std::fprintf(stderr, "omnicam: interrupted: %d of %d frames finished in %s; run the same command again to resume\n",
                 r.kept + r.rendered, r.frames, a.out.c_str());
    exitCode = 130;
    return;
  }
  std::printf("wrote %s: %d frames (%d rendered, %d kept from an earlier run)\n", a.out.c_str(), r.frames, r.rendered,
              r.kept);
}

}  // namespace

void addDatasetCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<DatasetArgs>();
  CLI::App* cmd = app.add_subcommand("dataset", "Render a reference dataset from a spec (docs/dataset-format.md), "
                                                "resumably; or verify / report on one");
  cmd->add_option("spec", args->spec, "Dataset spec JSON (format omnicam-dataset/1)");
  cmd->add_option("-o,--output", args->out, "Dataset folder (created; an interrupted run resumes in it)");
  cmd->add_flag("--overwrite", args->overwrite, "Replace a dataset made from a different spec in the folder");
  cmd->add_option("--verify", args->verify, "Re-hash every file of dataset DIR against its manifest (exit 0 / 1)");
  cmd->add_option("--status", args->status, "Say how many frames of dataset DIR are finished (exit 0 complete / 1)");
  cmd->callback([args, cmd, &exitCode] { runDatasetVerb(*args, *cmd, exitCode); });
}

}  // namespace omnicam::cli
