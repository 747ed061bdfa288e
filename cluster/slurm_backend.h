#pragma once
// `omnicam dataset SPEC -o DIR --backend slurm --shards N`: a Slurm job array renders the shards
// (dataset_shards.h) into the shared DIR, one task per shard, and a job that depends on the
// array merges the manifest. Slurm does the scheduling; a retry is a resubmission, which renders
// only the shards that are missing, unfinished or whose files no longer hash right.
//
// Files (in DIR/slurm/): render.sbatch, merge.sbatch, shard-<I>.log, merge.log, sbatch.log, and
// jobs.json (the last submission's job numbers: a submission while they are queued is refused).
#include <string>
#include <vector>

namespace omnicam {

struct SlurmSubmitOptions {
  std::string spec, dir;         // as given; made absolute in the scripts
  std::string omnicamBinary;     // absolute path of the omnicam the tasks run
  int shards = 1;
  int maxParallel = 0;           // 0: no throttle; K: --array=...%K
  // Threads per task; 0: the CPUs Slurm gave the task (SLURM_CPUS_PER_TASK, else
  // SLURM_CPUS_ON_NODE), so `--slurm-args "--cpus-per-task=C"` sizes every task.
  int threads = 0;
  std::vector<std::string> sbatchArgs;  // extra #SBATCH options, each one "--name[=value]"
  std::string sbatch = "sbatch";        // the submit command (PATH lookup)
  std::string squeue = "squeue";        // asks whether the last submission's jobs have ended (PATH lookup)
};

struct SlurmSubmission {
  std::vector<int> shards;       // submitted (empty: all were done; then merged here)
  std::string arrayJob, mergeJob;
  std::string renderScript, mergeScript;
  std::vector<std::string> notes;  // what the user should know of the run (DatasetPlan::notes), as a local run says
};

// The job numbers the last submission into a dataset folder recorded (slurm/jobs.json): empty
// when it has none. The folder is untrusted: a link or special file there, other JSON, a job
// number that is not digits or a cluster name that is not one is an InputError.
struct SubmittedSlurmJobs {
  std::string arrayJob, mergeJob;  // digits; mergeJob empty when none was queued
  std::string cluster;             // when sbatch answered "id;cluster"
};
SubmittedSlurmJobs readSubmittedSlurmJobs(const std::string& dir);

// Splits --slurm-args on whitespace; each word must start with '-' and hold no quote, newline or
// backslash (they become #SBATCH lines). InputError otherwise.
std::vector<std::string> parseSlurmArgs(const std::string& text);

// A Slurm array spec for `indices`, compressed to ranges ("0-3,5,7-9"), with "%K" when K > 0.
std::string slurmArraySpec(const std::vector<int>& indices, int maxParallel);

// Reads the spec, its scene and poses, and checks DIR, as each task will (InputError for a
// mistake, more shards than frames, a folder holding something else, the last submission's jobs
// still queued or running); then writes the scripts
// and submits them. ExternalError if sbatch is missing or refuses (with its message): then
// what this submission wrote is put back as it was.
SlurmSubmission submitDatasetToSlurm(const SlurmSubmitOptions& options);

}  // namespace omnicam
