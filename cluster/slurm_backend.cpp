#include "slurm_backend.h"

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "atomic_file.h"
#include "dataset_plan.h"
#include "dataset_runner.h"
#include "dataset_shards.h"
#include "dataset_spec.h"
#include "errors.h"
#include "external_process.h"
#include "job_folder.h"
#include "json_text.h"
#include "manifest.h"
#include "markup.h"
#include "safe_files.h"

namespace omnicam {

namespace fs = std::filesystem;

namespace {

// Paths go into the scripts single-quoted (shellQuote) and into sbatch's log options, where
// Slurm expands '%' — and a backslash anywhere turns that off (sbatch(1), "filename pattern"): every
// task would log into one file named shard-%a.log. A line break would end a comment or the quoted
// word's line, so every path must be one printable line: control characters are refused, and
// '%' and '\' in the dataset folder.
void checkScriptPath(const std::string& path, bool holdsLogs) {
  for (const unsigned char ch : path)
    if (ch < 0x20 || ch == 0x7f)
      throw InputError(showPath(path) + ": contains a control character; a path in a Slurm script must be one printable line");
  if (holdsLogs && path.find_first_of("%\\") != std::string::npos)
    throw InputError(showPath(path) + ": a dataset folder for Slurm must not contain '%' or '\\' (Slurm reads them in log names)");
}

// Slurm opens the logs itself when the jobs start, following links: a link or a special file
// planted where a log goes is refused before anything is submitted.
void checkLogName(const fs::path& dir, const std::string& relative) {
  const EntryKind kind = entryInside(dir.string(), relative);
  if (kind != EntryKind::Missing && kind != EntryKind::File)
    throw InputError(showPath((dir / relative).string()) + ": " +
                     (kind == EntryKind::Link ? "is a symbolic link" : "is not a regular file") +
                     "; Slurm would write its log through it");
}

// sbatch missing, or exiting non-zero: nothing was queued (a timeout or an answer without a job
// id may have queued the job all the same, and are plain ExternalErrors).
class SbatchRefused : public ExternalError {
 public:
  using ExternalError::ExternalError;
};

// A job as sbatch --parsable names it: "<jobid>" or "<jobid>;<cluster>" (a job sent to another
// cluster of a federation, whose squeue must be asked with --clusters). The same patterns check
// what slurm/jobs.json holds.
struct SubmittedJob {
  std::string id, cluster;
  std::string logProblem;  // why slurm/sbatch.log could not be kept ("" when it was)
};
constexpr const char* kJobNumberPattern = R"(\d{1,18})";
constexpr const char* kClusterNamePattern = R"([A-Za-z0-9][A-Za-z0-9_.-]{0,63})";

// sbatch's output goes to a temporary created exclusively in DIR/slurm, then becomes sbatch.log
// by an atomic write: whatever was planted as sbatch.log is replaced, never written through.
SubmittedJob submit(const std::vector<std::string>& argv, const fs::path& dir, const std::string& what) {
  const fs::path slurmDir = dir / "slurm";
  const std::string tmpName = "slurm/" + atomicTemporaryName("sbatch.log");
  writeFileInside(dir.string(), tmpName, "", Durability::Unsynced);
  const std::string tmp = (dir / tmpName).string();
  // The temporary goes however this ends (an interrupt while sbatch runs included).
  struct RemoveTemporary {
    const fs::path& dir;
    const std::string& name;
    ~RemoveTemporary() {
      try {
        removeFileInside(dir.string(), name);
      } catch (...) {  // a destructor throws nothing: the next run's cleanup takes what is left
      }
    }
  } removeTemporary{dir, tmpName};
  const ProcessResult r = runProcess(argv, slurmDir.string(), tmp, 120.0);
  const std::string output = tailOfFile(tmp, 5);
  // sbatch.log is a copy for people to read: failing to keep it (a folder planted there, a full
  // disk) must not lose the number of a job Slurm has queued, so it is said, not thrown.
  std::string logProblem;
  try {
    writeFileInside(dir.string(), "slurm/sbatch.log", readFileInside(dir.string(), tmpName, int64_t{1} << 20), Durability::Unsynced);
  } catch (const InputError& e) {
    logProblem = e.what();
  } catch (const OutputError& e) {
    logProblem = e.what();
  }
  if (r.notFound) throw SbatchRefused(showPath(argv[0]) + ": not found (make deps installs slurm-client; on a cluster, load its module)");
  if (r.timedOut)
    throw ExternalError("sbatch did not answer for the " + what + " within 120 s; it may have been submitted all the same (squeue "
                        "lists it): " + r.logTail);
  if (r.exitCode != 0) throw SbatchRefused("sbatch refused the " + what + " (exit " + std::to_string(r.exitCode) + "): " + r.logTail);
  std::istringstream lines(output);
  std::string line;
  const std::regex jobId("(" + std::string(kJobNumberPattern) + ")(;(" + kClusterNamePattern + "))?");
  while (std::getline(lines, line)) {
    std::smatch m;
    if (std::regex_match(line, m, jobId)) return {m[1], m[3], logProblem};
  }
  throw ExternalError("sbatch gave no job id for the " + what + ": " + r.logTail);
}

// The jobs of the last submission into DIR, as sbatch numbered them (slurm/jobs.json), so that
// a second submission does not queue the same shards while the first's are still queued: two
// tasks of one shard would fight over it, and the merge would run twice.
constexpr const char* kJobsFile = "slurm/jobs.json";

void recordJobs(const fs::path& dir, const SubmittedJob& array, const std::string& mergeJob) {
  nlohmann::json jobs = {{"array_job", array.id}};
  if (!mergeJob.empty()) jobs["merge_job"] = mergeJob;
  if (!array.cluster.empty()) jobs["cluster"] = array.cluster;
  writeFileInside(dir.string(), kJobsFile, jobs.dump(2) + "\n", Durability::Synced);
}

// Whether Slurm still lists job `id` (its tasks, for an array) as pending, running, suspended or
// completing. squeue runs in a private folder (its output there, out of others' reach) without
// its SQUEUE_* defaults, which could widen (SQUEUE_STATES=all) or narrow (SQUEUE_USERS) the list.
bool stillListed(const std::string& squeue, const std::string& id, const std::string& cluster, const std::string& what) {
  const JobFolder folder("omnicam-squeue", false);
  const std::string log = folder.path() + "/squeue.log";
  std::vector<std::string> argv = {squeue, "--noheader", "--format=%i", "--states=PENDING,CONFIGURING,RUNNING,SUSPENDED,COMPLETING",
                                   "--jobs=" + id};
  if (!cluster.empty()) argv.push_back("--clusters=" + cluster);
  ProcessOptions options;
  options.timeoutSeconds = 120.0;
  options.withoutVariables = {"SQUEUE_"};
  const ProcessResult r = runProcess(argv, folder.path(), log, options);
  const std::string output = tailOfFile(log, 20);
  // A job Slurm has forgotten (MinJobAge after it ended) is an invalid id to squeue.
  if (r.exitCode > 0 && output.find("Invalid job id specified") != std::string::npos) return false;
  if (r.notFound || r.timedOut || r.exitCode != 0)
    throw ExternalError("squeue could not tell whether " + what + " has ended: " +
                        (r.notFound ? showPath(squeue) + ": not found"
                                    : r.timedOut ? "it did not answer within 120 s" : "exit " + std::to_string(r.exitCode) + ": " + r.logTail));
  // Its lines are the job's ("123", or an array's tasks "123_4", "123_[5-9]"); anything else
  // (a warning) says nothing of it.
  std::istringstream lines(output);
  std::string line;
  const std::regex listed(id + R"((_\S+)?\s*)");
  while (std::getline(lines, line))
    if (std::regex_match(line, listed)) return true;
  return false;
}

}  // namespace

SubmittedSlurmJobs readSubmittedSlurmJobs(const std::string& folder) {
  const fs::path dir(folder);
  const std::string where = showPath((dir / kJobsFile).string());
  const EntryKind kind = entryInside(dir.string(), kJobsFile);
  if (kind == EntryKind::Missing) return {};
  if (kind != EntryKind::File)
    throw InputError(where + ": " + (kind == EntryKind::Link ? "is a symbolic link" : "is not a regular file") +
                     "; omnicam keeps the last submission's job numbers there");
  nlohmann::json jobs;
  try {  // as every JSON omnicam reads: no key twice (which would pick one job), bounded depth
    jobs = parseJsonText(readFileInside(dir.string(), kJobsFile, int64_t{1} << 16), (dir / kJobsFile).string());
  } catch (const InputError& e) {  // "<file>: what is wrong": said of the file once
    std::string what = e.what();
    if (what.rfind(where + ": ", 0) == 0) what.erase(0, where.size() + 2);
    throw InputError(where + ": not the job list omnicam writes (" + what + ")");
  }
  if (!jobs.is_object() || !jobs.contains("array_job")) throw InputError(where + ": not the job list omnicam writes (no array_job)");
  SubmittedSlurmJobs submitted;
  if (jobs.contains("cluster")) {
    const nlohmann::json& name = jobs.at("cluster");
    if (!name.is_string() || !std::regex_match(name.get<std::string>(), std::regex(kClusterNamePattern)))
      throw InputError(where + ": cluster: not a Slurm cluster's name");
    submitted.cluster = name.get<std::string>();
  }
  for (const auto& [field, job] : {std::pair<const char*, std::string*>{"array_job", &submitted.arrayJob}, {"merge_job", &submitted.mergeJob}}) {
    if (!jobs.contains(field)) continue;
    const nlohmann::json& id = jobs.at(field);
    if (!id.is_string() || !std::regex_match(id.get<std::string>(), std::regex(kJobNumberPattern)))
      throw InputError(where + ": " + field + ": not a Slurm job number");
    *job = id.get<std::string>();
  }
  return submitted;
}

namespace {

// The earlier submission's jobs that Slurm still lists. The file is the folder's, which others
// may write: only job numbers and a cluster's name are taken from it, each checked.
struct QueuedJobs {
  std::vector<std::string> ids;
  std::string cluster;
};
QueuedJobs earlierJobsNotEnded(const fs::path& dir, const std::string& squeue) {
  const SubmittedSlurmJobs submitted = readSubmittedSlurmJobs(dir.string());
  const std::string where = showPath((dir / kJobsFile).string());
  QueuedJobs notEnded{{}, submitted.cluster};
  for (const auto& [kind, job] : {std::pair<const char*, std::string>{"array", submitted.arrayJob}, {"merge", submitted.mergeJob}}) {
    if (job.empty()) continue;
    const std::string what = std::string("the earlier submission's ") + kind + " job " + job + " (" + where + ")";
    if (std::find(notEnded.ids.begin(), notEnded.ids.end(), job) == notEnded.ids.end() &&
        stillListed(squeue, job, submitted.cluster, what))
      notEnded.ids.push_back(job);
  }
  return notEnded;
}

// What a submission changes in DIR before sbatch takes the array, as it was: when nothing was
// queued (sbatch refused it, or a script could not be written), it is put back, so that the
// folder does not look submitted (--status reads the scripts) nor loses an earlier submission's.
class SubmissionUndo {
 public:
  explicit SubmissionUndo(const fs::path& dir) : dir_(dir.string()) {
    std::error_code ec;
    dirExisted_ = fs::exists(dir, ec);
    shardsExisted_ = entryInside(dir_, "shards") == EntryKind::Folder;
    slurmExisted_ = entryInside(dir_, "slurm") == EntryKind::Folder;
    for (const char* file : kFiles)
      if (entryInside(dir_, file) == EntryKind::File) before_[file] = readFileInside(dir_, file, int64_t{1} << 20);
  }
  void undo() const {
    for (const char* file : kFiles) {
      const auto old = before_.find(file);
      if (old != before_.end()) writeFileInside(dir_, file, old->second, Durability::Unsynced);
      else removeFileInside(dir_, file);
    }
    if (!slurmExisted_) removeEmptyFolderInside(dir_, "slurm");
    if (!shardsExisted_) removeEmptyFolderInside(dir_, "shards");
    std::error_code ec;
    if (!dirExisted_ && fs::is_directory(fs::symlink_status(dir_, ec)) && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
  }

 private:
  static constexpr const char* kFiles[] = {"slurm/render.sbatch", "slurm/merge.sbatch", "slurm/sbatch.log"};
  std::string dir_;
  bool dirExisted_ = false, shardsExisted_ = false, slurmExisted_ = false;
  std::map<std::string, std::string> before_;
};

}  // namespace

namespace {

// sbatch's short options that take a value (getopt's "x:"), besides the reserved a, o, d and e.
constexpr const char* kShortOptionsWithValue = "AbBcCDFGiJkLmMnNpqStwx";

// The sbatch options omnicam sets itself (--array, --output, --dependency) or that would take the
// job's log or script away from it (--error, --wrap).
constexpr const char* kReservedSbatchOptions[] = {"array", "output", "dependency", "error", "wrap"};

// The reserved option `word` sets for sbatch (getopt_long), or "" if none: a long option by any
// prefix of its name (getopt_long takes unambiguous prefixes: --arr=, --out=), a short one
// anywhere in a cluster of flags ("-Ho x.log" is -H -o; -dafterok:1 is -d afterok:1).
std::string reservedSbatchOption(const std::string& word) {
  if (word.rfind("--", 0) == 0) {
    const std::string name = word.substr(2, word.find('=') - 2);
    for (const char* reserved : kReservedSbatchOptions)
      if (!name.empty() && std::string(reserved).rfind(name, 0) == 0) return reserved;
    return "";
  }
  // sbatch's short options that take a value: the rest of the word is that value.
  const std::string withValue = kShortOptionsWithValue;
  for (size_t k = 1; k < word.size(); ++k) {
    switch (word[k]) {
      case 'a': return "array";
      case 'o': return "output";
      case 'd': return "dependency";
      case 'e': return "error";
      default:
        if (withValue.find(word[k]) != std::string::npos) return "";
    }
  }
  return "";
}

}  // namespace

std::vector<std::string> parseSlurmArgs(const std::string& text) {
  std::vector<std::string> args;
  std::istringstream words(text);
  std::string word;
  while (words >> word) {
    if (word.size() < 2 || word[0] != '-' || word == "--" || word.rfind("--=", 0) == 0 ||
        word.find_first_of("'\"\\\n\r`$") != std::string::npos) {
      // "--partition debug", "-p debug": the value of the option before, as its own word (each
      // word is a #SBATCH line). Said when the word would do as a value and the option before
      // is one that takes one, alone: a long option without "=", or a short one of sbatch's that
      // takes a value.
      const std::string previous = args.empty() ? "" : args.back();
      const bool plainValue = word[0] != '-' && word.find_first_of("'\"\\\n\r`$") == std::string::npos;
      const bool longAlone = previous.rfind("--", 0) == 0 && previous.find('=') == std::string::npos;
      const bool shortAlone = previous.size() == 2 && previous[0] == '-' && std::string(kShortOptionsWithValue).find(previous[1]) != std::string::npos;
      const bool valueOfPrevious = plainValue && (longAlone || shortAlone);
      const std::string joined = previous + (longAlone ? "=" : "") + word;
      throw InputError("--slurm-args: " + quote(word) + ": each word must be an sbatch option (starting with '-', "
                       "without quotes, backslashes, '$' or '`')" +
                       (valueOfPrevious ? "; write an option and its value as one word: " + quote(joined) : ""));
    }
    if (const std::string reserved = reservedSbatchOption(word); !reserved.empty())
      throw InputError("--slurm-args: " + quote(word) + ": sbatch reads it as --" + reserved +
                       "; omnicam sets --array (use --max-parallel for %K), --output and --dependency itself, and "
                       "keeps --error and --wrap (the job's log and script) its own");
    args.push_back(word);
  }
  return args;
}

std::string slurmArraySpec(const std::vector<int>& indices, int maxParallel) {
  std::ostringstream spec;
  for (size_t k = 0; k < indices.size();) {
    size_t end = k;
    while (end + 1 < indices.size() && indices[end + 1] == indices[end] + 1) ++end;
    spec << (k ? "," : "") << indices[k];
    if (end > k) spec << '-' << indices[end];
    k = end + 1;
  }
  if (maxParallel > 0) spec << '%' << maxParallel;
  return spec.str();
}

namespace {

// The array's job script: each task renders its shard (SLURM_ARRAY_TASK_ID) on the cores Slurm
// gave it.
std::string renderScriptText(const SlurmSubmitOptions& o, const fs::path& spec, const fs::path& dir, const std::vector<int>& shards) {
  const fs::path slurmDir = dir / "slurm";
  std::ostringstream render;
  render << "#!/bin/bash\n"
         << "# Written by `omnicam dataset --backend slurm`: one array task per dataset shard (docs/cluster.md).\n"
         << "# Submitted as: sbatch --array=" << slurmArraySpec(shards, o.maxParallel)
         << " --output=" << shellQuote((slurmDir / "shard-%a.log").string()) << " render.sbatch\n"
         << "#SBATCH --job-name=omnicam-dataset\n";
  for (const std::string& arg : o.sbatchArgs) render << "#SBATCH " << arg << "\n";
  render << "exec " << shellQuote(o.omnicamBinary) << " dataset " << shellQuote(spec.string()) << " -o "
         << shellQuote(dir.string()) << " --shard \"${SLURM_ARRAY_TASK_ID}/" << o.shards << "\" --threads ";
  if (o.threads > 0) render << o.threads << "\n";
  else render << "\"${SLURM_CPUS_PER_TASK:-${SLURM_CPUS_ON_NODE:-0}}\"\n";
  return render.str();
}

// The merge job's script, run once the array has ended.
std::string mergeScriptText(const SlurmSubmitOptions& o, const fs::path& dir) {
  std::ostringstream merge;
  merge << "#!/bin/bash\n"
        << "# Written by `omnicam dataset --backend slurm`: merges the shards' manifests once the array has ended.\n"
        << "#SBATCH --job-name=omnicam-dataset-merge\n";
  for (const std::string& arg : o.sbatchArgs) merge << "#SBATCH " << arg << "\n";
  merge << "exec " << shellQuote(o.omnicamBinary) << " dataset --merge " << shellQuote(dir.string()) << " --shards "
        << o.shards << "\n";
  return merge.str();
}

}  // namespace

SlurmSubmission submitDatasetToSlurm(const SlurmSubmitOptions& o) {
  if (o.shards < 1 || o.shards > kMaxShards)
    throw InputError("shard count " + std::to_string(o.shards) + ": must be in [1, " + std::to_string(kMaxShards) + "]");
  if (o.maxParallel < 0) throw InputError("shards at once: " + std::to_string(o.maxParallel) + ": must be at least 1 (0: no limit)");
  const fs::path dir = fs::absolute(o.dir).lexically_normal();
  const fs::path spec = fs::absolute(o.spec).lexically_normal();
  checkScriptPath(dir.string(), true);
  checkScriptPath(spec.string(), false);
  checkScriptPath(o.omnicamBinary, false);
  // The spec, its scene, poses and engine as each task will read them: a mistake, or more shards
  // than frames, is refused here before anything is queued, not by every task of the array.
  const DatasetSpec datasetSpec = loadDatasetSpec(o.spec);
  DatasetRunOptions shardRun;
  shardRun.dir = o.dir;
  shardRun.shardCount = o.shards;
  const DatasetPlan plan(datasetSpec, shardRun);
  std::error_code ec;
  const bool dirExisted = fs::exists(dir, ec);
  for (const char* folder : {"shards", "slurm"}) checkFoldersInside(dir.string(), folder);  // a link there is named
  if (dirExisted && !fs::is_empty(dir, ec) && entryInside(dir.string(), kManifestName) != EntryKind::File &&
      entryInside(dir.string(), "shards") != EntryKind::Folder)
    throw InputError(showPath(dir.string()) + ": folder is not empty and holds no dataset (no " + std::string(kManifestName) +
                     ", no shards/)");
  // Each task would refuse another dataset's manifest, or another spec's or count's shards:
  // refused here, before anything is queued. A ground truth's identity holds its renderer's
  // version, which is the nodes' (this machine's may differ, or have none): its tasks check that.
  if (datasetSpec.request.engine == "fast") checkShardsMayJoin(dir.string(), plan.header(), o.shards);
  else if (const std::string conflict = shardCountConflict(dir.string(), o.shards); !conflict.empty())
    throw InputError(showPath(dir.string()) + ": " + conflict);

  if (const QueuedJobs queued = earlierJobsNotEnded(dir, o.squeue); !queued.ids.empty()) {
    std::string list, words;
    for (const std::string& job : queued.ids) {
      list += (list.empty() ? "" : ",") + job;
      words += " " + job;
    }
    const std::string onCluster = queued.cluster.empty() ? "" : " --clusters=" + queued.cluster;
    const bool one = queued.ids.size() == 1;
    throw InputError(showPath(dir.string()) + ": the earlier submission's " + (one ? "job " : "jobs ") + list +
                     (one ? " is" : " are") + " still queued or running (squeue --jobs=" + list + onCluster + "): submit again once " +
                     (one ? "it has" : "they have") + " ended, or cancel with `scancel" + onCluster + words + "` first");
  }

  SlurmSubmission s;
  s.notes = plan.notes();
  for (const ShardState& state : shardStates(dir.string(), o.shards, true))
    if (!state.complete) s.shards.push_back(state.index);
  if (s.shards.empty()) {
    if (const MergeResult merged = mergeDatasetShards(dir.string(), o.shards); !merged.complete())
      throw InputError(showPath(dir.string()) + ": every shard of " + std::to_string(o.shards) + " is complete, yet their merge lists " +
                       std::to_string(merged.finished) + " of " + std::to_string(merged.frames) + " frames");
    return s;
  }
  for (const int shard : s.shards) checkLogName(dir, "slurm/shard-" + std::to_string(shard) + ".log");
  checkLogName(dir, "slurm/merge.log");
  const fs::path slurmDir = dir / "slurm";
  s.renderScript = (slurmDir / "render.sbatch").string();
  s.mergeScript = (slurmDir / "merge.sbatch").string();
  const SubmissionUndo before(dir);
  SubmittedJob array;
  try {
    for (const char* folder : {"shards", "slurm"}) makeFoldersInside(dir.string(), folder);
    writeFileInside(dir.string(), "slurm/render.sbatch", renderScriptText(o, spec, dir, s.shards), Durability::Synced);
    writeFileInside(dir.string(), "slurm/merge.sbatch", mergeScriptText(o, dir), Durability::Synced);
    array = submit({o.sbatch, "--parsable", "--array=" + slurmArraySpec(s.shards, o.maxParallel),
                    "--output=" + (slurmDir / "shard-%a.log").string(), s.renderScript},
                   dir, "array job");
    s.arrayJob = array.id;
    if (!array.logProblem.empty()) s.notes.push_back("sbatch's answer was not kept as slurm/sbatch.log: " + array.logProblem);
  } catch (const SbatchRefused&) {  // sbatch's words are in the message
    before.undo();
    throw;
  } catch (const OutputError&) {
    before.undo();
    throw;
  }
  const std::string cancel = "`scancel" + (array.cluster.empty() ? "" : " --clusters=" + array.cluster) + " " + s.arrayJob + "`";
  // afterany: the merge also runs when a task failed, and lists what is missing.
  try {
    recordJobs(dir, array, "");
    const SubmittedJob merge = submit({o.sbatch, "--parsable", "--dependency=afterany:" + s.arrayJob,
                                       "--output=" + (slurmDir / "merge.log").string(), s.mergeScript},
                                      dir, "merge job");
    s.mergeJob = merge.id;
    if (!merge.logProblem.empty()) s.notes.push_back("sbatch's answer was not kept as slurm/sbatch.log: " + merge.logProblem);
  } catch (const std::runtime_error& e) {
    // The array is queued and its shards are good work: said first, with what finishes or undoes
    // it, then what failed.
    throw ExternalError("the array job " + s.arrayJob + " is queued and renders the shards, but its merge job was not submitted: " +
                        "once the array has ended, merge them with `" + shellPath(o.omnicamBinary) + " dataset --merge " +
                        shellPath(dir.string()) + " --shards " + std::to_string(o.shards) + "`, or cancel it with " + cancel + "; " +
                        e.what());
  }
  try {
    recordJobs(dir, array, s.mergeJob);
  } catch (const OutputError& e) {
    throw OutputError("the array job " + s.arrayJob + " and its merge job " + s.mergeJob + " are queued, but their numbers were not " +
                      "recorded, so a submission into this folder cannot see them: " + e.what());
  }
  return s;
}

}  // namespace omnicam
