// omnicam dataset SPEC -o DIR [--overwrite] | --verify DIR | --status DIR
#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <tuple>

#include "atomic_file.h"
#include "cli_util.h"
#include "number_format.h"
#include "commands.h"
#include "dataset_runner.h"
#include "dataset_shards.h"
#include "errors.h"
#include "interrupts.h"
#include "manifest.h"
#include "markup.h"
#include "safe_files.h"
#include "slurm_backend.h"

namespace omnicam::cli {

namespace {


struct DatasetArgs {
  std::string spec, out, verify, status, merge, shard, backend = "local", slurmArgs;
  bool overwrite = false;
  int shards = 0, maxParallel = 0, threads = 0;
  SceneLoadOptions load;  // the user's --allow-outside-files: a spec cannot set it
};

// "I/N" → {I, N}; InputError naming --shard otherwise.
std::pair<int, int> parseShard(const std::string& text) {
  const std::string_view whole(text);
  const auto slash = whole.find('/');
  if (slash != std::string_view::npos) {
    const auto index = parseIntegerIn(whole.substr(0, slash), 0, kMaxShards - 1);
    const auto count = parseIntegerIn(whole.substr(slash + 1), 1, kMaxShards);
    if (index && count && *index < *count) return {static_cast<int>(*index), static_cast<int>(*count)};
  }
  throw InputError("--shard: must be I/N with 0 <= I < N (got " + quote(text) + "), N at most " + std::to_string(kMaxShards));
}

void printShardStates(const std::string& dir, int count) {
  for (const ShardState& s : shardStates(dir, count, false))
    std::printf("  shard %d/%d: %s\n", s.index, count,
                !s.started ? "not started"
                           : (std::to_string(s.finished) + " of " + std::to_string(s.frames) + " frames" +
                              (s.complete ? " (complete)" : s.running ? " (being rendered now on this machine)" : "")).c_str());
}

void runSlurm(const DatasetArgs& a, const CLI::App& cmd) {
  refuseUnless(cmd, "--shard", false, "the local backend");
  refuseUnless(cmd, "--overwrite", false, "the local backend");
  refuseUnless(cmd, "--allow-outside-files", false, "the local backend");
  if (a.shards < 1) throw InputError("--shards: give the number of shards (array tasks) for --backend slurm");
  checkOutputFolder(a.out, "-o");
  SlurmSubmitOptions options;
  options.spec = a.spec;
  options.dir = a.out;
  options.shards = a.shards;
  options.maxParallel = a.maxParallel;
  options.threads = a.threads;
  options.sbatchArgs = parseSlurmArgs(a.slurmArgs);
  options.omnicamBinary = std::filesystem::canonical("/proc/self/exe").string();
  const SlurmSubmission s = submitDatasetToSlurm(options);
  for (const std::string& note : s.notes) std::fprintf(stderr, "omnicam: note: %s\n", note.c_str());
  if (s.shards.empty()) {
    std::printf("%s: every shard of %d is complete; merged the manifest (nothing submitted)\n", showPath(a.out).c_str(), a.shards);
    return;
  }
  std::printf("submitted array job %s (shards %s of %d) and merge job %s (after it)\n", s.arrayJob.c_str(),
              slurmArraySpec(s.shards, 0).c_str(), a.shards, s.mergeJob.c_str());
  std::printf("follow: omnicam dataset --status %s; after failures submit the same command again\n", shellPath(a.out).c_str());
}

// --merge DIR: the shard manifests into DIR's manifest; exit 0 complete, 1 not.
int runMerge(const std::string& dir, int shards, const CLI::App& cmd) {
  refuseUnless(cmd, "-o", false, "a SPEC");
  int count = shards;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError("--merge: " + showPath(dir) + (std::filesystem::exists(dir, ec) ? ": not a folder" : ": no such folder"));
  if (count == 0) {
    const std::vector<int> counts = shardCountsIn(dir);
    if (counts.empty())
      throw InputError("--merge: " + showPath(dir) + ": holds no shard manifests (shards/shard-I-of-N.json): it was not run "
                       "in shards, or none has started");
    if (counts.size() > 1) throw InputError("--merge: " + showPath(dir) + ": holds shards of several counts: say which with --shards N");
    count = counts.front();
  }
  const MergeResult r = mergeDatasetShards(dir, count);
  const std::string merged = r.started == count ? countOf(count, "shard") : std::to_string(r.started) + " of " + countOf(count, "shard");
  std::printf("%s: merged %s: %d of %d frames finished%s\n", showPath(dir).c_str(), merged.c_str(), r.finished, r.frames,
              r.complete() ? " (complete)" : "");
  if (!r.complete()) printShardStates(dir, count);
  return r.complete() ? 0 : 1;
}

// --verify DIR: every file re-hashed against the manifest; exit 0 all right, 1 not.
int runVerify(const std::string& dir) {
  if (entryInside(dir, kManifestName) == EntryKind::Missing && !shardCountsIn(dir).empty()) {
    // Shards not merged: nothing whole to verify yet; say what makes it whole (as --status does).
    std::printf("FAIL: %s: shards not merged yet: no manifest.json to verify (%s)\n", showPath(dir).c_str(), unmergedShardsNextStep(dir).c_str());
    return 1;
  }
  const DatasetVerifyResult r = verifyDataset(dir);
  for (const std::string& problem : r.problems) std::printf("%s\n", problem.c_str());
  std::printf("%s: %s: %s checked, %s\n", r.ok() ? "PASS" : "FAIL", showPath(dir).c_str(), countOf(r.files, "file").c_str(),
              countOf(static_cast<long long>(r.problems.size()), "problem").c_str());
  return r.ok() ? 0 : 1;
}

// What finishes an incomplete dataset: waiting for the run at work, the shards, or running again.
std::string nextStep(const std::string& dir) {
  if (wholeDatasetRunWriting(dir)) return "a run is writing it now: wait for it to end";
  if (!shardCountsIn(dir).empty()) return unmergedShardsNextStep(dir);
  return "run the same command again to resume";
}

// The last Slurm submission's jobs as --status names them (slurm/jobs.json): "array job 4711 and
// merge job 4712", and the squeue command that lists them. Empty when none are recorded.
struct SubmittedJobsText {
  std::string jobs, squeue;
};
SubmittedJobsText submittedJobsText(const std::string& dir) {
  SubmittedSlurmJobs submitted;
  try {
    submitted = readSubmittedSlurmJobs(dir);
  } catch (const InputError& e) {  // the status stands without the job numbers; a submission refuses the file
    std::fprintf(stderr, "omnicam: note: the jobs are not named: %s\n", oneLine(e.what()).c_str());
    return {};
  }
  if (submitted.arrayJob.empty()) return {};
  SubmittedJobsText text{"array job " + submitted.arrayJob, "squeue --jobs=" + submitted.arrayJob};
  if (!submitted.mergeJob.empty() && submitted.mergeJob != submitted.arrayJob) {
    text.jobs += " and merge job " + submitted.mergeJob;
    text.squeue += "," + submitted.mergeJob;
  }
  if (!submitted.cluster.empty()) text.squeue += " --clusters=" + submitted.cluster;
  return text;
}

// --status DIR: how many frames are finished, shard by shard before a merge; exit 0 complete, 1 not.
int printStatus(const std::string& dir) {
  const std::vector<int> shardCounts = shardCountsIn(dir);
  if (entryInside(dir, kManifestName) == EntryKind::Missing && !shardCounts.empty()) {
    // Shards rendering, not merged yet.
    int finished = 0;
    for (int count : shardCounts)
      for (const ShardState& state : shardStates(dir, count, false)) finished += state.finished;
    std::printf("%s: shards not merged yet: %d frames finished in the shards that have started (%s)\n", showPath(dir).c_str(), finished,
                nextStep(dir).c_str());
    if (const SubmittedJobsText submitted = submittedJobsText(dir); !submitted.jobs.empty())
      std::printf("  submitted to Slurm as %s: `%s` lists them while they are queued or running\n", submitted.jobs.c_str(),
                  submitted.squeue.c_str());
    for (int count : shardCounts) printShardStates(dir, count);
    return 1;
  }
  // Submitted to Slurm, no task started yet: the folder holds only its slurm/ scripts.
  if (entryInside(dir, kManifestName) == EntryKind::Missing && entryInside(dir, "slurm/render.sbatch") == EntryKind::File) {
    const SubmittedJobsText submitted = submittedJobsText(dir);
    if (submitted.jobs.empty())
      std::printf("%s: submitted to Slurm (slurm/render.sbatch), no shard has started yet: squeue lists the jobs, "
                  "slurm/shard-<I>.log each task's output\n", showPath(dir).c_str());
    else
      std::printf("%s: submitted to Slurm as %s (slurm/render.sbatch), no shard has started yet: `%s` lists them, "
                  "slurm/shard-<I>.log each task's output\n", showPath(dir).c_str(), submitted.jobs.c_str(), submitted.squeue.c_str());
    return 1;
  }
  const DatasetStatus s = datasetStatus(dir);
  std::printf("%s: %d of %d frames finished%s\n", showPath(dir).c_str(), s.finished, s.frames,
              s.complete ? " (complete, by its manifest; --verify re-hashes every file)" : (" (incomplete: " + nextStep(dir) + ")").c_str());
  if (!s.complete)
    for (int count : shardCountsIn(dir)) printShardStates(dir, count);
  return s.complete ? 0 : 1;
}

// SPEC -o DIR on this machine (all of it, or --shard I/N); exit 0, or 130 when interrupted.
int runLocal(const DatasetArgs& a, const CLI::App& cmd) {
  refuseUnless(cmd, "--shards", false, "--backend slurm or --merge");
  refuseUnless(cmd, "--slurm-args", false, "--backend slurm");
  refuseUnless(cmd, "--max-parallel", false, "--backend slurm");
  if (a.overwrite && !a.shard.empty())
    throw InputError("--overwrite: not with --shard (shards share the folder: remove the old dataset, then render the shards)");
  checkOutputFolder(a.out, "-o");
  DatasetRunOptions options;
  if (!a.shard.empty()) std::tie(options.shardIndex, options.shardCount) = parseShard(a.shard);
  DatasetSpec spec = loadDatasetSpec(a.spec);
  spec.allowOutsideFiles = a.load.allowOutsideFolder;
  options.dir = a.out;
  options.overwrite = a.overwrite;
  options.threads = a.threads;
  options.stopRequested = &interruptRequested();
  std::unique_ptr<Progress> progress;
  options.onNotes = [](const std::vector<std::string>& notes) {
    for (const std::string& note : notes) std::fprintf(stderr, "omnicam: note: %s\n", note.c_str());
  };
  options.onStart = [&](int kept, int total) { progress = std::make_unique<Progress>("dataset " + a.out, total, kept); };
  options.onFrame = [&](int done, int) { progress->advanceTo(done); };
  options.onWaitForShards = [&] {
    std::fprintf(stderr, "omnicam: waiting for another shard's check of %s (it holds shards/ until its manifest is written)\n",
                 showPath(a.out + "/shards").c_str());
  };
  // Ctrl-C finishes the frame in progress, writes the manifest and stops: the run resumes. An
  // external renderer at work is ended at once (base/interrupts.h), its frame given up.
  stopGracefullyOnInterrupt();
  std::string interruption;  // an external renderer ended by the signal
  const DatasetRunResult r = [&] {
    try {
      return runDataset(spec, options);
    } catch (const OtherDatasetError& e) {
      // --overwrite is not for shards, which share the folder.
      throw InputError("-o: " + std::string(e.what()) + (a.shard.empty() ? ": --overwrite replaces it, or give another folder"
                                                                          : ": give another folder, or remove that dataset first"));
    } catch (const Interrupted& e) {
      interruption = e.what();
      DatasetRunResult stopped;
      stopped.stopped = true;
      return stopped;
    }
  }();
  if (progress) progress->finish();
  if (!interruption.empty()) {
    // Before the folder was made (an engine checked first), there is nothing to resume.
    std::error_code ec;
    if (std::filesystem::is_directory(a.out, ec))
      std::fprintf(stderr, "omnicam: %s; the frames finished before are listed in %s: run the same command again to resume\n",
                   interruption.c_str(), showPath(a.out).c_str());
    else
      std::fprintf(stderr, "omnicam: %s before %s was made: nothing was written\n", interruption.c_str(), showPath(a.out).c_str());
    return 130;
  }
  if (r.stoppedWaiting) {
    std::fprintf(stderr, "omnicam: interrupted while waiting for another shard's check of %s/shards: this run wrote nothing; "
                 "run the same command again to go on\n", showPath(a.out).c_str());
    return 130;
  }
  if (r.stopped) {
    std::fprintf(stderr, "omnicam: interrupted: %d of %d frames finished in %s; run the same command again to resume\n",
                 r.kept + r.rendered, r.frames, showPath(a.out).c_str());
    return 130;
  }
  std::printf("wrote %s: %s (%d rendered, %d kept from an earlier run)\n", showPath(a.out).c_str(), countOf(r.frames, "frame").c_str(),
              r.rendered, r.kept);
  if (!a.shard.empty())  // a shard is part of a dataset: what makes it whole
    std::printf("shard %s of the dataset in %s: %s\n", a.shard.c_str(), showPath(a.out).c_str(), unmergedShardsNextStep(a.out).c_str());
  return 0;
}

void runDatasetVerb(const DatasetArgs& a, const CLI::App& cmd, int& exitCode) {
  const int verbs = !a.spec.empty() + !a.verify.empty() + !a.status.empty() + !a.merge.empty();
  if (verbs != 1) throw InputError("dataset: give a SPEC with -o DIR, or --verify DIR, --status DIR or --merge DIR");
  if (a.backend != "local" && a.backend != "slurm") throw InputError("--backend: must be local or slurm (got " + quote(a.backend) + ")");
  refuseUnless(cmd, "--allow-outside-files", !a.spec.empty(), "a SPEC");
  if (!a.merge.empty()) {
    exitCode = runMerge(a.merge, a.shards, cmd);
    return;
  }
  if (!a.verify.empty() || !a.status.empty()) {
    refuseUnless(cmd, "-o", false, "a SPEC");
    refuseUnless(cmd, "--overwrite", false, "a SPEC");
    refuseUnless(cmd, "--shards", false, "--backend slurm or --merge");
  }
  if (!a.verify.empty()) {
    exitCode = runVerify(a.verify);
    return;
  }
  if (!a.status.empty()) {
    exitCode = printStatus(a.status);
    return;
  }
  if (a.out.empty()) throw InputError("-o: a dataset needs an output folder");
  if (a.backend == "slurm") return runSlurm(a, cmd);
  exitCode = runLocal(a, cmd);
}

}  // namespace

void addDatasetCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<DatasetArgs>();
  CLI::App* cmd = app.add_subcommand("dataset", "Render a reference dataset from a spec (docs/dataset-format.md), "
                                                "resumably; or verify / report on one");
  cmd->add_option("spec", args->spec, "Dataset spec JSON (format omnicam-dataset/1)");
  cmd->add_option("-o,--output", args->out, "Dataset folder (created; an interrupted run resumes in it)");
  cmd->add_flag("--overwrite", args->overwrite, "Replace a dataset made from a different spec in the folder");
  addSceneLoadFlags(*cmd, args->load);
  cmd->add_option("--verify", args->verify, "Re-hash every file of dataset DIR against its manifest (exit 0 PASS / 1 FAIL; 2 if the manifest cannot be read)");
  cmd->add_option("--status", args->status, "Say how many frames of dataset DIR are finished (exit 0 complete / 1)");
  cmd->add_option("--shard", args->shard, "Render only shard I of N (I/N) into the shared folder (docs/cluster.md)");
  cmd->add_option("--backend", args->backend, "local (default) or slurm: submit the shards as a Slurm job array");
  cmd->add_option("--shards", args->shards, "Shards (array tasks) for --backend slurm; for --merge when not obvious")
      ->check(integerIn(1, kMaxShards));
  cmd->add_option("--slurm-args", args->slurmArgs, "Extra sbatch options for every job, e.g. \"--partition=gpu --time=2:00:00\"");
  cmd->add_option("--max-parallel", args->maxParallel, "At most K shards running at once (Slurm's --array=...%K)")
      ->check(integerIn(1, kMaxShards));
  cmd->add_option("--threads", args->threads, "Threads for rendering and encoding (POV-Ray's, Blender's too); 0: every "
                  "core, under --backend slurm: the task's CPUs")
      ->check(integerIn(0, limits::kMaxThreads));
  cmd->add_option("--merge", args->merge, "Merge the shard manifests of DIR into its manifest.json (exit 0 complete / 1)");
  cmd->callback([args, cmd, &exitCode] { runDatasetVerb(*args, *cmd, exitCode); });
}

}  // namespace omnicam::cli
