#include "slurm_backend.h"

#include <filesystem>
#include <regex>
#include <sstream>

#include "atomic_file.h"
#include "dataset_shards.h"
#include "errors.h"
#include "external_process.h"
#include "manifest.h"

namespace omnicam {

namespace fs = std::filesystem;

namespace {

// POSIX shell single quotes: nothing inside is special; a quote is closed, escaped and reopened.
std::string shellQuote(const std::string& text) {
  std::string out = "'";
  for (char ch : text) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

// sbatch --parsable prints "<jobid>" or "<jobid>;<cluster>".
std::string submit(const std::vector<std::string>& argv, const fs::path& slurmDir, const std::string& what) {
  const std::string log = (slurmDir / "sbatch.log").string();
  const ProcessResult r = runProcess(argv, slurmDir.string(), log, 120.0);
  if (r.notFound) throw ExternalError(showPath(argv[0]) + ": not found (make deps installs slurm-client; on a cluster, load its module)");
  if (r.exitCode != 0) throw ExternalError("sbatch refused the " + what + " (exit " + std::to_string(r.exitCode) + "): " + r.logTail);
  std::istringstream lines(tailOfFile(log, 5));
  std::string line;
  const std::regex jobId(R"((\d+)(;.*)?)");
  while (std::getline(lines, line)) {
    std::smatch m;
    if (std::regex_match(line, m, jobId)) return m[1];
  }
  throw ExternalError("sbatch gave no job id for the " + what + ": " + r.logTail);
}

}  // namespace

std::vector<std::string> parseSlurmArgs(const std::string& text) {
  std::vector<std::string> args;
  std::istringstream words(text);
  std::string word;
  while (words >> word) {
    if (word[0] != '-' || word.find_first_of("'\"\\\n\r`$") != std::string::npos)
      throw InputError("--slurm-args: " + quote(word) + ": each word must be an sbatch option (starting with '-', "
                       "without quotes, backslashes, '$' or '`')");
    if (word.rfind("--array", 0) == 0 || word.rfind("-a", 0) == 0 || word.rfind("--output", 0) == 0 ||
        word.rfind("--dependency", 0) == 0)
      throw InputError("--slurm-args: " + quote(word) + ": omnicam sets --array (use --max-parallel for %K), --output "
                       "and --dependency itself");
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

SlurmSubmission submitDatasetToSlurm(const SlurmSubmitOptions& o) {
  if (o.shards < 1 || o.shards > 100000) throw InputError("--shards: must be in [1, 100000]");
  if (o.maxParallel < 0) throw InputError("--max-parallel: must be at least 1");
  const fs::path dir = fs::absolute(o.dir).lexically_normal();
  const fs::path spec = fs::absolute(o.spec).lexically_normal();
  // Slurm expands %-patterns in log paths: a folder name with '%' would be rewritten.
  if (dir.string().find('%') != std::string::npos)
    throw InputError("-o: " + showPath(o.dir) + ": a folder for Slurm must not contain '%' (Slurm expands it in log names)");
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_empty(dir, ec) && !fs::exists(dir / kManifestName, ec) &&
      !fs::is_directory(dir / "shards", ec))
    throw InputError("-o: " + showPath(o.dir) + ": folder is not empty and holds no dataset (no " + std::string(kManifestName) +
                     ", no shards/)");
  const fs::path slurmDir = dir / "slurm";
  fs::create_directories(dir / "shards", ec);
  fs::create_directories(slurmDir, ec);
  if (ec) throw OutputError("-o: " + showPath(o.dir) + ": cannot create folder (" + ec.message() + ")");

  SlurmSubmission s;
  for (const ShardState& state : shardStates(dir.string(), o.shards, true))
    if (!state.complete) s.shards.push_back(state.index);
  if (s.shards.empty()) {
    mergeDatasetShards(dir.string(), o.shards);
    return s;
  }

  std::ostringstream render;
  render << "#!/bin/bash\n"
         << "# Written by `omnicam dataset --backend slurm`: one array task per dataset shard (docs/cluster.md).\n"
         << "# Submitted as: sbatch --array=" << slurmArraySpec(s.shards, o.maxParallel)
         << " --output=" << (slurmDir / "shard-%a.log").string() << " render.sbatch\n"
         << "#SBATCH --job-name=omnicam-dataset\n";
  for (const std::string& arg : o.sbatchArgs) render << "#SBATCH " << arg << "\n";
  render << "exec " << shellQuote(o.omnicamBinary) << " dataset " << shellQuote(spec.string()) << " -o "
         << shellQuote(dir.string()) << " --shard \"${SLURM_ARRAY_TASK_ID}/" << o.shards << "\" --threads ";
  if (o.threads > 0) render << o.threads << "\n";
  else render << "\"${SLURM_CPUS_PER_TASK:-${SLURM_CPUS_ON_NODE:-0}}\"\n";
  std::ostringstream merge;
  merge << "#!/bin/bash\n"
        << "# Written by `omnicam dataset --backend slurm`: merges the shards' manifests once the array has ended.\n"
        << "#SBATCH --job-name=omnicam-dataset-merge\n";
  for (const std::string& arg : o.sbatchArgs) merge << "#SBATCH " << arg << "\n";
  merge << "exec " << shellQuote(o.omnicamBinary) << " dataset --merge " << shellQuote(dir.string()) << " --shards "
        << o.shards << "\n";
  s.renderScript = (slurmDir / "render.sbatch").string();
  s.mergeScript = (slurmDir / "merge.sbatch").string();
  writeTextAtomically(s.renderScript, render.str());
  writeTextAtomically(s.mergeScript, merge.str());

  s.arrayJob = submit({o.sbatch, "--parsable", "--array=" + slurmArraySpec(s.shards, o.maxParallel),
                       "--output=" + (slurmDir / "shard-%a.log").string(), s.renderScript},
                      slurmDir, "array job");
  // afterany: the merge also runs when a task failed, and lists what is missing.
  s.mergeJob = submit({o.sbatch, "--parsable", "--dependency=afterany:" + s.arrayJob,
                       "--output=" + (slurmDir / "merge.log").string(), s.mergeScript},
                      slurmDir, "merge job");
  return s;
}

}  // namespace omnicam
