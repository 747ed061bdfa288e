// The parts of the Slurm backend that need no cluster: array specs and the sbatch options a user
// may pass (the real-Slurm end-to-end test is tests/slurm_cli_test.cpp).
#include "slurm_backend.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>


#include "errors.h"

namespace omnicam {
namespace {

TEST(SlurmBackend, ArraySpecsCompressRunsAndThrottle) {
  EXPECT_EQ(slurmArraySpec({0, 1, 2, 3}, 0), "0-3");
  EXPECT_EQ(slurmArraySpec({1}, 0), "1");
  EXPECT_EQ(slurmArraySpec({0, 2, 3, 4, 7, 9, 10}, 0), "0,2-4,7,9-10");
  EXPECT_EQ(slurmArraySpec({0, 1, 2, 3}, 2), "0-3%2");
}

TEST(SlurmBackend, SbatchOptionsAreWordsStartingWithADashAndNothingToExpand) {
  EXPECT_EQ(parseSlurmArgs("  --partition=cpu   --time=01:00:00 --account=proj1 "),
            (std::vector<std::string>{"--partition=cpu", "--time=01:00:00", "--account=proj1"}));
  EXPECT_TRUE(parseSlurmArgs("").empty());
  // A value as a separate word, shell syntax, and the options omnicam sets itself are refused.
  for (const char* bad : {"-A proj1", "--comment='x'", "--chdir=$HOME", "--job-name=`id`", "--array=0-3",
                          "--output=x.log", "--dependency=afterok:1", "--export=A\\nB"})
    EXPECT_THROW(parseSlurmArgs(bad), InputError) << bad;
  // A value given as its own word is shown joined to its option, as sbatch takes it in one word.
  const auto refusal = [](const std::string& text) {
    try {
      parseSlurmArgs(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal("--partition debug"), "--slurm-args: \"debug\": each word must be an sbatch option (starting with '-', without quotes, "
                                          "backslashes, '$' or '`'); write an option and its value as one word: \"--partition=debug\"");
  EXPECT_NE(refusal("-p debug").find("; write an option and its value as one word: \"-pdebug\""), std::string::npos);
  // Not where joining would be wrong: an option with its value, or one that takes none.
  for (const char* notAValue : {"--time=1:00 debug", "-pdebug gpu", "-v debug", "--partition 'debug'"})
    EXPECT_EQ(refusal(notAValue).find("one word"), std::string::npos) << notAValue;
}

TEST(SlurmBackend, ReservedOptionsAreRefusedUnderEverySpellingSbatchAccepts) {
  // Unambiguous prefixes of long options; short options with attached values, also after flags.
  for (const char* bad : {"--arr=0-3", "--a=1", "--out=x.log", "--outp=x", "--dep=afterok:1", "--er=e.log", "--wr=id",
                          "-a0-3", "-ox.log", "-o", "-dafterok:1", "-ee.log", "-Hox.log", "-vQa1", "--", "-", "--=x"})
    EXPECT_THROW(parseSlurmArgs(bad), InputError) << bad;
  // A value attached to another option is a value: "d" in "-pdebug" is not --dependency.
  for (const char* good : {"-pdebug", "-Jomnicam-data", "--partition=dev-a", "--export=ALL", "--open-mode=append",
                           "--exclusive", "-H", "-vv", "--account=array"})
    EXPECT_NO_THROW(parseSlurmArgs(good)) << good;
}

// A dataset of three frames (a submission reads its spec and scene as each task would).
void writeThreeFrameSpec(const std::filesystem::path& dir) {
  std::ofstream(dir / "scene.json") << R"({"format": "omnicam-scene/1", "materials": {"m": {"color": [0.5, 0.5, 0.5]}},
    "objects": [{"type": "sphere", "material": "m", "center": [1, 0, 0.3], "radius": 0.2}]})";
  std::ofstream(dir / "spec.json") << R"({"format": "omnicam-dataset/1", "scene": "scene.json", "size": 32,
    "poses": {"list": [[0, 0, 0], [0.1, 0, 0], [0.2, 0, 0]]}})";
}

// A submission of the three-frame spec in `dir` as 3 shards into dir/out, by the given sbatch.
SlurmSubmitOptions threeShardSubmission(const std::filesystem::path& dir, const std::filesystem::path& sbatch) {
  writeThreeFrameSpec(dir);
  SlurmSubmitOptions options;
  options.spec = (dir / "spec.json").string();
  options.dir = (dir / "out").string();
  options.omnicamBinary = "/usr/bin/true";
  options.shards = 3;
  options.sbatch = sbatch.string();
  return options;
}

// An sbatch that refuses the array job: nothing is queued, so what the submission wrote is put
// back as it was (its scripts would make --status say "submitted"); sbatch's words are in the
// message.
TEST(SlurmBackend, AnArrayJobRefusedLeavesNothingBehind) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("omnicam_slurm_array_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path sbatch = dir / "sbatch";
  std::ofstream(sbatch) << "#!/bin/sh\necho 'sbatch: error: invalid partition specified: nosuch' >&2\nexit 1\n";
  fs::permissions(sbatch, fs::perms::owner_all);
  SlurmSubmitOptions options = threeShardSubmission(dir, sbatch);
  // A new folder goes whole; in one submitted to before (its shards/ and slurm/ there, with the
  // earlier submission's scripts and a file of the user's), the earlier scripts are put back.
  fs::create_directories(dir / "mine" / "shards");
  fs::create_directories(dir / "mine" / "slurm");
  std::ofstream(dir / "mine" / "slurm" / "notes.txt") << "mine";
  for (const char* script : {"render.sbatch", "merge.sbatch", "sbatch.log"}) std::ofstream(dir / "mine" / "slurm" / script) << "earlier";
  for (const char* out : {"new", "mine"}) {
    options.dir = (dir / out).string();
    try {
      submitDatasetToSlurm(options);
      ADD_FAILURE() << "the refused array job was not said";
    } catch (const ExternalError& e) {
      EXPECT_NE(std::string(e.what()).find("sbatch refused the array job (exit 1): "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("invalid partition specified: nosuch"), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(dir / "new"));
  EXPECT_TRUE(fs::exists(dir / "mine" / "shards"));
  for (const char* script : {"render.sbatch", "merge.sbatch", "sbatch.log"}) {
    std::ifstream in(dir / "mine" / "slurm" / script);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "earlier") << script;
  }
  EXPECT_TRUE(fs::exists(dir / "mine" / "slurm" / "notes.txt"));
  // An sbatch that exits 0 without a job id may have queued the array all the same: what the
  // tasks need (the scripts, the log folders) stays.
  std::ofstream(sbatch) << "#!/bin/sh\nexit 0\n";
  options.dir = (dir / "unsure").string();
  try {
    submitDatasetToSlurm(options);
    ADD_FAILURE() << "an answer without a job id was not said";
  } catch (const ExternalError& e) {
    EXPECT_NE(std::string(e.what()).find("sbatch gave no job id for the array job"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::exists(dir / "unsure" / "slurm" / "render.sbatch"));
  EXPECT_TRUE(fs::exists(dir / "unsure" / "shards"));
  fs::remove_all(dir);
}

// An sbatch that takes the array job and then refuses the merge job: the array is queued and
// renders the shards, so the message gives its id with what finishes it (the merge by hand) and
// what undoes it (scancel), instead of leaving a job nobody was told of.
TEST(SlurmBackend, AMergeJobRefusedNamesTheQueuedArrayJobAndWhatFinishesOrCancelsIt) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("omnicam_slurm_merge_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path sbatch = dir / "sbatch";
  std::ofstream(sbatch) << "#!/bin/sh\ncase \"$*\" in *--dependency*) echo 'sbatch: error: QOSMaxSubmitJobPerUserLimit' >&2; exit 1;; esac\n"
                           "echo 4711\n";
  fs::permissions(sbatch, fs::perms::owner_all);
  const SlurmSubmitOptions options = threeShardSubmission(dir, sbatch);
  try {
    submitDatasetToSlurm(options);
    ADD_FAILURE() << "the refused merge job was not said";
  } catch (const ExternalError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("the array job 4711 is queued and renders the shards, but its merge job was not submitted: once the "
                            "array has ended, merge them with `/usr/bin/true dataset --merge " + (dir / "out").string() +
                            " --shards 3`, or cancel it with `scancel 4711`; sbatch refused the merge job (exit 1): ", 0),
              0u) << message;
    EXPECT_NE(message.find("QOSMaxSubmitJobPerUserLimit"), std::string::npos) << message;
  }
  fs::remove_all(dir);
}

// sbatch.log is a copy of sbatch's answer for people: when it cannot be kept (a folder planted
// under its name), the jobs Slurm queued are still recorded (slurm/jobs.json) and returned, with a
// note — never an error that loses the number of a queued array.
TEST(SlurmBackend, AnSbatchLogThatCannotBeKeptLosesNoQueuedJob) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("omnicam_slurm_log_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path sbatch = dir / "sbatch";
  std::ofstream(sbatch) << "#!/bin/sh\ncase \"$*\" in *--dependency*) echo 4712;; *) echo 4711;; esac\n";
  fs::permissions(sbatch, fs::perms::owner_all);
  const SlurmSubmitOptions options = threeShardSubmission(dir, sbatch);
  fs::create_directories(fs::path(options.dir) / "shards");  // a folder submitted to before
  fs::create_directories(fs::path(options.dir) / "slurm" / "sbatch.log");
  const SlurmSubmission s = submitDatasetToSlurm(options);
  EXPECT_EQ(s.arrayJob, "4711");
  EXPECT_EQ(s.mergeJob, "4712");
  const SubmittedSlurmJobs recorded = readSubmittedSlurmJobs(options.dir);
  EXPECT_EQ(recorded.arrayJob, "4711");
  EXPECT_EQ(recorded.mergeJob, "4712");
  EXPECT_TRUE(std::any_of(s.notes.begin(), s.notes.end(), [](const std::string& note) {
    return note.find("sbatch's answer was not kept as slurm/sbatch.log: ") == 0;
  })) << "no note of the log";
  fs::remove_all(dir);
}

// A second submission while the first's jobs are still queued or running (slurm/jobs.json, asked
// of squeue) is refused before anything is written or queued: its tasks would render the same
// shards beside the first's. Jobs squeue no longer lists, or has forgotten, are ended.
TEST(SlurmBackend, ASubmissionWhileTheLastOnesJobsAreQueuedIsRefused) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("omnicam_slurm_queued_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto script = [&](const char* name, const std::string& body) {
    std::ofstream(dir / name) << "#!/bin/sh\n" << body;
    fs::permissions(dir / name, fs::perms::owner_all);
  };
  const auto readText = [](const fs::path& file) {
    std::ifstream in(file);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  // The stand-in sbatch counts its calls; the array is job 4711, its merge 4712.
  script("sbatch", "echo x >> " + (dir / "sbatch_calls").string() + "\ncase \"$*\" in *--dependency*) echo 4712;; *) echo 4711;; esac\n");
  // The stand-in squeue logs its arguments and the SQUEUE_STATES it got, then answers as `answer`
  // (a script's body, given the arguments) says.
  const auto squeueAnswers = [&](const std::string& answer) {
    script("squeue", "echo \"$* SQUEUE_STATES=$SQUEUE_STATES\" >> " + (dir / "squeue_calls").string() + "\n" + answer);
  };
  SlurmSubmitOptions options = threeShardSubmission(dir, dir / "sbatch");
  options.squeue = (dir / "squeue").string();
  const auto sbatchCalls = [&] {
    const std::string calls = readText(dir / "sbatch_calls");
    return static_cast<int>(std::count(calls.begin(), calls.end(), '\n'));
  };
  const auto refusal = [&]() -> std::string {
    try {
      submitDatasetToSlurm(options);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(submitted)";
  };
  const SlurmSubmission first = submitDatasetToSlurm(options);
  EXPECT_EQ(first.arrayJob, "4711");
  EXPECT_EQ(first.mergeJob, "4712");
  const fs::path jobsFile = dir / "out/slurm/jobs.json";
  EXPECT_EQ(nlohmann::json::parse(readText(jobsFile)), nlohmann::json({{"array_job", "4711"}, {"merge_job", "4712"}}));
  ASSERT_EQ(sbatchCalls(), 2);

  // The array's tasks still listed, as squeue prints them: refused, nothing queued. squeue is
  // asked for the listed states itself, without the user's SQUEUE_STATES (=all would list ended
  // jobs too).
  ::setenv("SQUEUE_STATES", "all", 1);
  squeueAnswers("case \"$*\" in *--jobs=4711*) echo '4711_[1-2]'; echo 4711_0;; esac\n");
  EXPECT_EQ(refusal(), (dir / "out").string() + ": the earlier submission's job 4711 is still queued or running "
                       "(squeue --jobs=4711): submit again once it has ended, or cancel with `scancel 4711` first");
  ::unsetenv("SQUEUE_STATES");
  EXPECT_EQ(readText(dir / "squeue_calls"),
            "--noheader --format=%i --states=PENDING,CONFIGURING,RUNNING,SUSPENDED,COMPLETING --jobs=4711 SQUEUE_STATES=\n"
            "--noheader --format=%i --states=PENDING,CONFIGURING,RUNNING,SUSPENDED,COMPLETING --jobs=4712 SQUEUE_STATES=\n");
  // Both listed (the merge waits for the array): both named.
  squeueAnswers("echo \"${4#--jobs=}\"\n");
  EXPECT_EQ(refusal(), (dir / "out").string() + ": the earlier submission's jobs 4711,4712 are still queued or running "
                       "(squeue --jobs=4711,4712): submit again once they have ended, or cancel with `scancel 4711 4712` first");
  // A warning squeue prints says nothing of the jobs.
  squeueAnswers("echo 'squeue: warning: Could not find a valid sackd'\n");
  EXPECT_EQ(submitDatasetToSlurm(options).arrayJob, "4711");
  EXPECT_EQ(sbatchCalls(), 4);
  // squeue unable to answer: said, with its words; nothing queued.
  squeueAnswers("echo 'squeue: error: Unable to contact slurm controller' >&2\nexit 1\n");
  try {
    submitDatasetToSlurm(options);
    ADD_FAILURE() << "squeue's failure was not said";
  } catch (const ExternalError& e) {
    EXPECT_NE(std::string(e.what()).find("squeue could not tell whether the earlier submission's array job 4711 (" + jobsFile.string() +
                                         ") has ended: exit 1: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Unable to contact slurm controller"), std::string::npos) << e.what();
  }
  EXPECT_EQ(sbatchCalls(), 4);
  // Forgotten by Slurm (an invalid id to squeue): ended, so submitted.
  squeueAnswers("echo 'slurm_load_jobs error: Invalid job id specified' >&2\nexit 1\n");
  EXPECT_EQ(submitDatasetToSlurm(options).arrayJob, "4711");
  EXPECT_EQ(sbatchCalls(), 6);

  // What the folder holds there is untrusted: anything but omnicam's job list is refused before
  // squeue or sbatch is called.
  fs::remove(dir / "squeue_calls");
  for (const auto& [text, why] : std::vector<std::pair<std::string, std::string>>{
           {R"({"array_job": "4711; touch pwned"})", "array_job: not a Slurm job number"},
           {R"({"array_job": "4711", "cluster": "--all"})", "cluster: not a Slurm cluster's name"},
           {R"({"merge_job": "4712"})", "not the job list omnicam writes (no array_job)"},
           {"[]", "not the job list omnicam writes (no array_job)"},
           {"{", "not the job list omnicam writes (not valid JSON ("},
           {R"({"array_job": "4711", "array_job": "4712"})", "not the job list omnicam writes (duplicate key \"array_job\")"}}) {
    std::ofstream(jobsFile, std::ios::trunc) << text;
    const std::string said = refusal(), expected = jobsFile.string() + ": " + why;
    EXPECT_EQ(said.substr(0, expected.size()), expected) << text;
  }
  fs::remove(jobsFile);
  fs::create_symlink(dir / "spec.json", jobsFile);
  EXPECT_EQ(refusal(), jobsFile.string() + ": is a symbolic link; omnicam keeps the last submission's job numbers there");
  fs::remove(jobsFile);
  fs::create_directory(jobsFile);
  EXPECT_EQ(refusal(), jobsFile.string() + ": is not a regular file; omnicam keeps the last submission's job numbers there");
  fs::remove(jobsFile);
  EXPECT_FALSE(fs::exists(dir / "squeue_calls"));
  EXPECT_EQ(sbatchCalls(), 6);

  // A job sbatch sent to another cluster ("id;cluster") is asked of that cluster's squeue.
  script("sbatch", "case \"$*\" in *--dependency*) echo '4714;west';; *) echo '4713;west';; esac\n");
  EXPECT_EQ(submitDatasetToSlurm(options).arrayJob, "4713");
  EXPECT_EQ(nlohmann::json::parse(readText(jobsFile)),
            nlohmann::json({{"array_job", "4713"}, {"merge_job", "4714"}, {"cluster", "west"}}));
  squeueAnswers("echo 4713\n");
  EXPECT_EQ(refusal(), (dir / "out").string() + ": the earlier submission's job 4713 is still queued or running "
                       "(squeue --jobs=4713 --clusters=west): submit again once it has ended, or cancel with "
                       "`scancel --clusters=west 4713` first");
  EXPECT_NE(readText(dir / "squeue_calls").find("--jobs=4713 --clusters=west"), std::string::npos) << readText(dir / "squeue_calls");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace omnicam
