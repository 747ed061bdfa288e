// Output folders and Slurm scripts as a trust boundary (docs/robustness.md, "Output folders and
// clusters"): whatever is already inside a dataset folder, planted by someone else or left by an
// accident, never makes omnicam run a command, write or read outside the folder, delete what it
// did not write, block on a FIFO, read a huge file, or leave a short file under a final name.
// Every refusal is exit 2 with one line; files outside keep their bytes.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sha256.h"
#include "shell_command.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using testing::isOneLine;
using testing::readFile;
using nlohmann::json;

void writeFile(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// POSIX shell single quotes: nothing inside is special.
std::string sh(const std::string& text) {
  std::string out = "'";
  for (char ch : text) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

bool isLink(const fs::path& path) { return fs::is_symlink(fs::symlink_status(path)); }

// Every regular file under `dir`, relative path → bytes.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (fs::is_regular_file(entry.symlink_status())) files[fs::relative(entry.path(), dir).string()] = readFile(entry.path());
  return files;
}

struct Outcome {
  int code;
  std::string out, err;
};

class OutputFolderTrust : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_trust_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "bin");
    // A fake sbatch: records each call's arguments (one per line, "--" after the last) and
    // prints a job id, as `sbatch --parsable` does.
    writeFile(dir_ / "bin/sbatch", "#!/bin/sh\n{ for a in \"$@\"; do printf '%s\\n' \"$a\"; done; echo --; } >> " +
                                       sh(at("sbatch-calls.txt")) + "\necho 4242\n");
    fs::permissions(dir_ / "bin/sbatch", fs::perms::owner_all);
    writeFile(dir_ / "victim.txt", "the victim's bytes\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string at(const std::string& name) const { return (dir_ / name).string(); }
  // A spec over robocup2006: `size` px, `frames` frames of thesis-loop, and `extra` fields.
  std::string spec(const std::string& name, int frames, const std::string& extra = "", int size = 32) const {
    writeFile(dir_ / name, R"({"format": "omnicam-dataset/1", "scene": ")" OMNICAM_SOURCE_DIR R"(/scenes/robocup2006.json",
      "size": )" + std::to_string(size) + R"(, "poses": {"path": "thesis-loop", "frames": )" + std::to_string(frames) + "}" +
                               extra + "}");
    return at(name);
  }
  // omnicam with `args` (shell words, quoted by the caller) after `prefix` (environment,
  // prlimit), the fake sbatch first on PATH; `timeout` turns a hang into a failure.
  Outcome omnicam(const std::string& args, const std::string& prefix = "") const {
    const std::string err = at("stderr.txt");
    const auto r = testing::runShell("PATH=" + sh(at("bin") + ":" + std::getenv("PATH")) + " " + prefix + " timeout 120 " +
                                     sh(OMNICAM_BINARY) + " " + args + " 2>" + sh(err));
    return {r.code, r.out, readFile(err)};
  }
  // A finished dataset of `specPath` in `name`.
  fs::path dataset(const std::string& specPath, const std::string& name) const {
    const Outcome r = omnicam("dataset " + sh(specPath) + " -o " + sh(at(name)));
    EXPECT_EQ(r.code, 0) << r.err;
    return dir_ / name;
  }

  fs::path dir_;
};

#define EXPECT_REFUSED(run, fragment)                                                  \
  do {                                                                                 \
    const Outcome& r_ = (run);                                                             \
    EXPECT_EQ(r_.code, 2) << r_.out << r_.err;                                         \
    EXPECT_TRUE(isOneLine(r_.err)) << r_.err;                                          \
    EXPECT_NE(r_.err.find(fragment), std::string::npos) << "wanted: " << (fragment) << "\ngot: " << r_.err; \
  } while (0)

// The arguments of each recorded sbatch call.
std::vector<std::vector<std::string>> sbatchCalls(const fs::path& log) {
  std::vector<std::vector<std::string>> calls(1);
  std::istringstream lines(readFile(log));
  for (std::string line; std::getline(lines, line);)
    if (line == "--") calls.emplace_back();
    else calls.back().push_back(line);
  calls.pop_back();
  return calls;
}

// A script sbatch reads as written: the #SBATCH block (comments only before it ends) up to the
// one command, `exec`, on the last line.
void expectSbatchScript(const std::string& script, const std::vector<std::string>& options) {
  std::vector<std::string> lines;
  std::istringstream in(script);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_GE(lines.size(), 3u) << script;
  EXPECT_EQ(lines.front(), "#!/bin/bash");
  for (size_t i = 0; i + 1 < lines.size(); ++i) EXPECT_EQ(lines[i].rfind('#', 0), 0u) << "line " << i << ": " << lines[i];
  EXPECT_EQ(lines.back().rfind("exec ", 0), 0u) << lines.back();
  for (const std::string& option : options)
    EXPECT_NE(std::find(lines.begin(), lines.end(), "#SBATCH " + option), lines.end()) << option << " lost:\n" << script;
}

TEST_F(OutputFolderTrust, APathThatCannotBeOneQuotedScriptLineIsRefusedBeforeAnything) {
  const std::string specPath = spec("spec.json", 2);
  const std::string injected = at("x\ntouch " + at("PWNED") + " #");
  EXPECT_REFUSED(omnicam("dataset " + sh(specPath) + " -o " + sh(injected) + " --backend slurm --shards 2"),
                 "contains a control character");
  EXPECT_FALSE(fs::exists(injected));
  EXPECT_FALSE(fs::exists(at("x")));
  EXPECT_FALSE(fs::exists(at("PWNED")));
  EXPECT_FALSE(fs::exists(at("sbatch-calls.txt"))) << "sbatch was called";
  // Slurm expands '%' in log names; a spec path with a line break is refused too.
  EXPECT_REFUSED(omnicam("dataset " + sh(specPath) + " -o " + sh(at("ds%j")) + " --backend slurm --shards 2"),
                 "must not contain '%' or '\\'");
  EXPECT_FALSE(fs::exists(at("ds%j")));
  // A backslash turns Slurm's '%' expansion off: every task would log into one "shard-%a.log".
  EXPECT_REFUSED(omnicam("dataset " + sh(specPath) + " -o " + sh(at("ds\\x")) + " --backend slurm --shards 2"),
                 "must not contain '%' or '\\'");
  EXPECT_FALSE(fs::exists(at("ds\\x")));
  fs::copy_file(specPath, at("spec\r\nx.json"));
  EXPECT_REFUSED(omnicam("dataset " + sh(at("spec\r\nx.json")) + " -o " + sh(at("ds")) + " --backend slurm --shards 2"),
                 "contains a control character");
  EXPECT_FALSE(fs::exists(at("ds")));
  EXPECT_FALSE(fs::exists(at("sbatch-calls.txt")));
}

TEST_F(OutputFolderTrust, SlurmScriptsRunAsWrittenWithEveryOptionAndNothingInjected) {
  // Quotes, command substitutions, a backslash, a semicolon: all legal in a path, all inert (the
  // backslash in the spec's: the dataset folder may hold none, as Slurm reads it in log names).
  fs::create_directories(dir_ / "it's a \\ spec");
  const std::string specPath = spec("it's a \\ spec/spec.json", 2);
  const fs::path out = dir_ / "it's \"a\" $(touch PWNED1) `touch PWNED2` ;touch PWNED3; x" / "ds";
  const std::vector<std::string> options{"--partition=debug", "--time=1:00", "--comment=trust"};
  const Outcome submitted = omnicam("dataset " + sh(specPath) + " -o " + sh(out.string()) +
                                " --backend slurm --shards 2 --max-parallel 1 --slurm-args " +
                                sh("--partition=debug --time=1:00 --comment=trust"));
  ASSERT_EQ(submitted.code, 0) << submitted.err;
  const auto calls = sbatchCalls(dir_ / "sbatch-calls.txt");
  ASSERT_EQ(calls.size(), 2u);
  const std::string slurm = (out / "slurm").string();
  EXPECT_EQ(calls[0], (std::vector<std::string>{"--parsable", "--array=0-1%1", "--output=" + slurm + "/shard-%a.log",
                                                slurm + "/render.sbatch"}));
  EXPECT_EQ(calls[1], (std::vector<std::string>{"--parsable", "--dependency=afterany:4242", "--output=" + slurm + "/merge.log",
                                                slurm + "/merge.sbatch"}));
  expectSbatchScript(readFile(out / "slurm/render.sbatch"), options);
  expectSbatchScript(readFile(out / "slurm/merge.sbatch"), options);
  EXPECT_NE(readFile(out / "slurm/sbatch.log").find("4242"), std::string::npos);

  // Run the scripts as Slurm would, from a working folder of their own: both shards, the merge.
  fs::create_directories(dir_ / "cwd");
  for (const std::string& run : {"SLURM_ARRAY_TASK_ID=0 bash " + sh(slurm + "/render.sbatch"),
                                "SLURM_ARRAY_TASK_ID=1 bash " + sh(slurm + "/render.sbatch"), "bash " + sh(slurm + "/merge.sbatch")}) {
    const auto r = testing::runShell("cd " + sh(at("cwd")) + " && " + run + " 2>&1");
    EXPECT_EQ(r.code, 0) << run << "\n" << r.out;
  }
  EXPECT_EQ(omnicam("dataset --verify " + sh(out.string())).code, 0);
  for (const char* name : {"PWNED1", "PWNED2", "PWNED3"}) {
    EXPECT_FALSE(fs::exists(dir_ / "cwd" / name)) << name;
    EXPECT_FALSE(fs::exists(dir_ / name)) << name;
  }
}

TEST_F(OutputFolderTrust, OverwriteNeverDeletesAFolderMerelyNamedLikeACamera) {
  const std::string cameras =
      R"(, "cameras": [{"name": "src"}, {"name": "Documents", "mount": {"x": -0.1, "y": 0, "yaw_deg": 180}}])";
  const std::string a = spec("a.json", 3, cameras), b = spec("b.json", 2, cameras);
  fs::create_directories(dir_ / "home/src");
  fs::create_directories(dir_ / "home/Documents");
  writeFile(dir_ / "home/src/main.c", "int main() {}\n");
  writeFile(dir_ / "home/Documents/thesis.tex", "\\chapter{One}\n");
  const auto before = snapshot(dir_ / "home");
  for (const char* flags : {"", " --overwrite"})
    EXPECT_REFUSED(omnicam("dataset " + sh(a) + " -o " + sh(at("home")) + flags), "folder is not empty and has no manifest.json");
  EXPECT_EQ(snapshot(dir_ / "home"), before);
  EXPECT_FALSE(fs::exists(dir_ / "home/src/rgb"));

  // In a dataset's folder, overwriting removes the old dataset's files and nothing of the user's
  // beside them, even in its camera and kind folders.
  const fs::path ds = dataset(a, "ds");
  writeFile(ds / "src/main.c", "int main() {}\n");
  writeFile(ds / "Documents/rgb/thesis.tex", "\\chapter{One}\n");
  const Outcome overwritten = omnicam("dataset " + sh(b) + " -o " + sh(ds.string()) + " --overwrite");
  ASSERT_EQ(overwritten.code, 0) << overwritten.err;
  EXPECT_EQ(readFile(ds / "src/main.c"), "int main() {}\n");
  EXPECT_EQ(readFile(ds / "Documents/rgb/thesis.tex"), "\\chapter{One}\n");
  EXPECT_FALSE(fs::exists(ds / "src/rgb/000002.png")) << "the old dataset's frame stayed";
  EXPECT_EQ(omnicam("dataset --verify " + sh(ds.string())).code, 0);

  // A manifest that lists the user's file as a frame's: still never removed.
  json manifest = json::parse(readFile(ds / "manifest.json"));
  manifest["frames"][0]["cameras"]["src"]["files"]["rgb"] = {{"path", "src/main.c"}, {"sha256", sha256OfBytes("int main() {}\n")}};
  writeFile(ds / "manifest.json", manifest.dump());
  const Outcome forged = omnicam("dataset " + sh(a) + " -o " + sh(ds.string()) + " --overwrite");
  EXPECT_EQ(forged.code, 2) << forged.err;  // a frame's record where omnicam names no frame file
  EXPECT_EQ(readFile(ds / "src/main.c"), "int main() {}\n");

  // A file at one of the dataset's own paths that no longer holds what the manifest says was
  // written there is not omnicam's: it stays, whether the manifest is the run's or forged.
  const fs::path again = dataset(a, "again");
  writeFile(again / "src/rgb/000002.png", "the user's own picture");
  const std::string asWritten = readFile(again / "manifest.json");
  json listed = json::parse(asWritten);
  writeFile(again / "src/data.csv", "the user's own table\n");
  // A record where omnicam names no file (the user's table as a frame's depth): the manifest is
  // refused as a whole, and nothing is replaced.
  listed["frames"][0]["cameras"]["src"]["files"]["depth"] = {{"path", "src/data.csv"}, {"sha256", std::string(64, '0')}};
  writeFile(again / "manifest.json", listed.dump());
  const Outcome refused = omnicam("dataset " + sh(b) + " -o " + sh(again.string()) + " --overwrite");
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_NE(refused.err.find("\"src/data.csv\" is not where omnicam names that file"), std::string::npos) << refused.err;
  EXPECT_EQ(readFile(again / "src/data.csv"), "the user's own table\n");
  EXPECT_TRUE(fs::exists(again / "Documents/rgb/000002.png"));
  writeFile(again / "manifest.json", asWritten);
  const Outcome replaced = omnicam("dataset " + sh(b) + " -o " + sh(again.string()) + " --overwrite");
  ASSERT_EQ(replaced.code, 0) << replaced.err;
  EXPECT_EQ(readFile(again / "src/rgb/000002.png"), "the user's own picture");
  EXPECT_FALSE(fs::exists(again / "Documents/rgb/000002.png")) << "the old dataset's own frame stayed";
}

TEST_F(OutputFolderTrust, PlantedLinksAreNeverFollowed) {
  const std::string specPath = spec("spec.json", 3);
  const fs::path ds = dataset(specPath, "ds");
  const std::string victim = readFile(dir_ / "victim.txt");
  // --verify reports a frame that is a link, without reading what it points to.
  fs::remove(ds / "cam0/rgb/000001.png");
  fs::create_symlink(dir_ / "victim.txt", ds / "cam0/rgb/000001.png");
  const Outcome verify = omnicam("dataset --verify " + sh(ds.string()));
  EXPECT_EQ(verify.code, 1);
  EXPECT_NE(verify.out.find("cam0/rgb/000001.png: is a symbolic link"), std::string::npos) << verify.out;
  EXPECT_EQ(verify.out.find(sha256OfBytes(victim)), std::string::npos) << "the link's target was hashed: " << verify.out;
  // Resuming renders that frame again: the rename replaces the link, the victim keeps its bytes.
  EXPECT_EQ(omnicam("dataset " + sh(specPath) + " -o " + sh(ds.string())).code, 0);
  EXPECT_FALSE(isLink(ds / "cam0/rgb/000001.png"));
  EXPECT_EQ(readFile(dir_ / "victim.txt"), victim);
  EXPECT_EQ(omnicam("dataset --verify " + sh(ds.string())).code, 0);

  // A camera folder that is a link: refused, nothing written into its target.
  fs::create_directories(dir_ / "elsewhere");
  writeFile(dir_ / "elsewhere/keep.txt", "mine");
  fs::remove_all(ds / "cam0");
  fs::create_directory_symlink(dir_ / "elsewhere", ds / "cam0");
  EXPECT_REFUSED(omnicam("dataset " + sh(specPath) + " -o " + sh(ds.string())), "cam0: is a symbolic link");
  EXPECT_EQ(snapshot(dir_ / "elsewhere"), (std::map<std::string, std::string>{{"keep.txt", "mine"}}));

  // A manifest that is a link is not read; a shards/ that is a link is not written into.
  fs::create_directories(dir_ / "linked");
  fs::create_symlink(dir_ / "victim.txt", dir_ / "linked/manifest.json");
  EXPECT_REFUSED(omnicam("dataset --status " + sh(at("linked"))), "manifest.json: is a symbolic link");
  EXPECT_REFUSED(omnicam("dataset --verify " + sh(at("linked"))), "manifest.json: is a symbolic link");
  fs::create_directories(dir_ / "sharded");
  fs::create_directory_symlink(dir_ / "elsewhere", dir_ / "sharded/shards");
  EXPECT_REFUSED(omnicam("dataset " + sh(specPath) + " -o " + sh(at("sharded")) + " --shard 0/2"), "shards: is a symbolic link");
  EXPECT_EQ(snapshot(dir_ / "elsewhere"), (std::map<std::string, std::string>{{"keep.txt", "mine"}}));
  EXPECT_EQ(readFile(dir_ / "victim.txt"), victim);
}

// The other verbs that fill a folder: `experiment`, `demo` and `study` make their subfolders and
// `arena hall` its texture folder without following a link planted under their names, before
// writing (or removing) anything.
TEST_F(OutputFolderTrust, ExperimentAndArenaFoldersAreNotFollowedThroughLinks) {
  fs::create_directories(dir_ / "elsewhere");
  writeFile(dir_ / "elsewhere/keep.txt", "mine");
  const std::map<std::string, std::string> untouched{{"keep.txt", "mine"}};
  fs::create_directories(dir_ / "run");
  fs::create_directory_symlink(dir_ / "elsewhere", dir_ / "run/data");
  EXPECT_REFUSED(omnicam("experiment texture-realism --quick -o " + sh(at("run"))), "run/data: is a symbolic link");
  EXPECT_EQ(snapshot(dir_ / "elsewhere"), untouched);
  EXPECT_FALSE(fs::exists(dir_ / "run/arenas")) << "a folder was made before the check";
  fs::create_directories(dir_ / "lab");
  fs::create_directory_symlink(dir_ / "elsewhere", dir_ / "lab/hall_textures");
  EXPECT_REFUSED(omnicam("arena hall --photo /usr/share/blender/datafiles/studiolights/world/interior.exr -o " + sh(at("lab/hall.json"))),
                 "hall_textures: is a symbolic link");
  EXPECT_EQ(snapshot(dir_ / "elsewhere"), untouched);
  EXPECT_FALSE(fs::exists(dir_ / "lab/hall.json"));

  fs::create_directories(dir_ / "paths");
  fs::create_directory_symlink(dir_ / "elsewhere", dir_ / "paths/scenes");
  EXPECT_REFUSED(omnicam("experiment path-convergence --quick -o " + sh(at("paths"))), "paths/scenes: is a symbolic link");
  EXPECT_FALSE(fs::exists(dir_ / "paths/data")) << "a folder was made before the check";

  // The demo removes its earlier files by name: a file the link's target holds under one of
  // them stays, for the whole demo and for one section.
  writeFile(dir_ / "elsewhere/start-pose-rings.json", "mine");
  writeFile(dir_ / "elsewhere/glance.fragment", "mine");
  const std::map<std::string, std::string> withNames{
      {"keep.txt", "mine"}, {"start-pose-rings.json", "mine"}, {"glance.fragment", "mine"}};
  for (const char* planted : {"sections", "hall"}) {
    const fs::path demo = dir_ / (std::string("demo_") + planted);
    fs::create_directories(demo);
    fs::create_directory_symlink(dir_ / "elsewhere", demo / planted);
    for (const char* section : {"", " --section start-pose"}) {
      const Outcome run = omnicam("demo --no-povray --no-blender --spp 1" + std::string(section) + " -o " + sh(demo.string()));
      EXPECT_REFUSED(run, std::string(planted) + ": is a symbolic link");
      EXPECT_EQ(snapshot(dir_ / "elsewhere"), withNames) << planted << section;
    }
    EXPECT_EQ(snapshot(demo), (std::map<std::string, std::string>{})) << "the demo wrote before the check";
  }
  fs::create_directories(dir_ / "docs");
  fs::create_directory_symlink(dir_ / "elsewhere", dir_ / "docs/figures");
  EXPECT_REFUSED(omnicam("study --spp 1 -o " + sh(at("docs/study.md"))), "figures: is a symbolic link");
  EXPECT_EQ(snapshot(dir_ / "elsewhere"), withNames);
  EXPECT_FALSE(fs::exists(dir_ / "docs/study.md"));
}

TEST_F(OutputFolderTrust, PlantedLinksInTheSlurmFolderAreReplacedOrRefused) {
  const std::string specPath = spec("spec.json", 2);
  const std::string victim = readFile(dir_ / "victim.txt");
  // omnicam's own files (scripts, sbatch.log) are written to a temporary and renamed over
  // whatever holds their name.
  fs::create_directories(dir_ / "ds/shards");
  fs::create_directories(dir_ / "ds/slurm");
  fs::create_symlink(dir_ / "victim.txt", dir_ / "ds/slurm/sbatch.log");
  fs::create_symlink(dir_ / "victim.txt", dir_ / "ds/slurm/render.sbatch");
  const Outcome replaced = omnicam("dataset " + sh(specPath) + " -o " + sh(at("ds")) + " --backend slurm --shards 2");
  EXPECT_EQ(replaced.code, 0) << replaced.err;
  EXPECT_FALSE(isLink(dir_ / "ds/slurm/sbatch.log"));
  EXPECT_FALSE(isLink(dir_ / "ds/slurm/render.sbatch"));
  EXPECT_NE(readFile(dir_ / "ds/slurm/sbatch.log").find("4242"), std::string::npos);
  EXPECT_EQ(readFile(dir_ / "victim.txt"), victim);
  // Slurm opens its logs itself, following links: a link where one goes is refused before
  // anything is submitted.
  fs::remove(dir_ / "sbatch-calls.txt");
  fs::create_directories(dir_ / "ds2/shards");
  fs::create_directories(dir_ / "ds2/slurm");
  fs::create_symlink(dir_ / "victim.txt", dir_ / "ds2/slurm/shard-1.log");
  EXPECT_REFUSED(omnicam("dataset " + sh(specPath) + " -o " + sh(at("ds2")) + " --backend slurm --shards 2"),
                 "slurm/shard-1.log: is a symbolic link; Slurm would write its log through it");
  EXPECT_FALSE(fs::exists(dir_ / "sbatch-calls.txt")) << "sbatch was called";
  EXPECT_FALSE(fs::exists(dir_ / "ds2/slurm/render.sbatch"));
  EXPECT_EQ(readFile(dir_ / "victim.txt"), victim);
}

TEST_F(OutputFolderTrust, FifosAndHugeFilesWhereFramesGoAreNeverOpenedOrRead) {
  const std::string specPath = spec("spec.json", 3, R"(, "outputs": {"normal": false, "instance": false})");
  const fs::path ds = dataset(specPath, "ds");
  fs::remove(ds / "cam0/depth/000000.exr");
  ASSERT_EQ(::mkfifo((ds / "cam0/depth/000000.exr").c_str(), 0644), 0);
  // Sparse: 6 GiB on paper, nothing on disk; above any frame omnicam writes.
  fs::resize_file(ds / "cam0/rgb/000002.png", uintmax_t{6} << 30);
  const Outcome verify = omnicam("dataset --verify " + sh(ds.string()));
  EXPECT_EQ(verify.code, 1) << verify.out << verify.err;
  EXPECT_NE(verify.out.find("cam0/depth/000000.exr: is not a regular file"), std::string::npos) << verify.out;
  EXPECT_NE(verify.out.find("cam0/rgb/000002.png: is larger than"), std::string::npos) << verify.out;
  EXPECT_REFUSED(omnicam("compare " + sh(ds.string()) + " " + sh(ds.string())), "cam0/rgb/000002.png: is larger than");
  // A folder in the dataset layout without a manifest: its images are read the same way.
  fs::create_directories(dir_ / "mine/cam0/rgb");
  ASSERT_EQ(::mkfifo((dir_ / "mine/cam0/rgb/000000.png").c_str(), 0644), 0);
  const fs::path fresh = dataset(spec("small.json", 1), "fresh");
  EXPECT_REFUSED(omnicam("compare " + sh(fresh.string()) + " " + sh(at("mine"))), "cam0/rgb/000000.png: is not a regular file");
  fs::remove(dir_ / "mine/cam0/rgb/000000.png");
  fs::create_symlink(dir_ / "victim.txt", dir_ / "mine/cam0/rgb/000000.png");
  EXPECT_REFUSED(omnicam("compare " + sh(fresh.string()) + " " + sh(at("mine"))), "cam0/rgb/000000.png: is a symbolic link");
  // Resuming renders both frames again and replaces what was planted.
  EXPECT_EQ(omnicam("dataset " + sh(specPath) + " -o " + sh(ds.string())).code, 0);
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(ds / "cam0/depth/000000.exr")));
  EXPECT_LT(fs::file_size(ds / "cam0/rgb/000002.png"), uintmax_t{1} << 20);
  EXPECT_EQ(omnicam("dataset --verify " + sh(ds.string())).code, 0);
}

// With a file-size limit the depth files cannot be written but the colour images can: the run
// fails (exit 5) in its first window of frames, rendered in parallel. Every file then under a
// final name is the one an unlimited run writes, byte for byte — the frame that failed and its
// neighbours, cancelled mid-render or mid-encode, leave nothing short or empty — and the same
// command without the limit finishes the dataset. Several runs, since which frame fails first
// and how far its neighbours got varies.
TEST_F(OutputFolderTrust, AFailedWriteLeavesNoShortFileUnderAFinalName) {
  const std::string specPath = spec("spec.json", 16, R"(, "spp": 4,
    "outputs": {"rgb": "png", "depth": true, "instance": false, "semantic": false, "normal": false, "landmarks": false})", 256);
  ASSERT_EQ(omnicam("dataset " + sh(specPath) + " -o " + sh(at("whole")) + " --threads 4").code, 0);
  const auto whole = snapshot(dir_ / "whole");
  uintmax_t largestOther = 0, smallestDepth = UINTMAX_MAX;
  for (const auto& [name, bytes] : whole)
    if (name.find("/depth/") != std::string::npos) smallestDepth = std::min<uintmax_t>(smallestDepth, bytes.size());
    else if (name != "manifest.json") largestOther = std::max<uintmax_t>(largestOther, bytes.size());
  // The first manifest, written before any frame, lists none.
  json first = json::parse(whole.at("manifest.json"));
  first["frames"] = json::array();
  largestOther = std::max<uintmax_t>(largestOther, first.dump(1).size() + 1);
  ASSERT_LT(largestOther, smallestDepth) << "no file-size limit separates the colour images from the depth files";
  const std::string limit = std::to_string((largestOther + smallestDepth) / 2);
  for (int run = 0; run < 6; ++run) {
    const fs::path ds = dir_ / ("limited" + std::to_string(run));
    const Outcome failed = omnicam("dataset " + sh(specPath) + " -o " + sh(ds.string()) + " --threads 4",
                               "prlimit --fsize=" + limit + ":" + limit);
    EXPECT_EQ(failed.code, 5) << failed.err;
    EXPECT_TRUE(isOneLine(failed.err)) << failed.err;
    EXPECT_NE(failed.err.find("cannot write (File too large)"), std::string::npos) << failed.err;
    size_t frames = 0;
    for (const auto& entry : fs::recursive_directory_iterator(ds)) {
      if (!entry.is_regular_file()) continue;
      const std::string name = fs::relative(entry.path(), ds).string();
      EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name << " was left behind";
      if (name == "manifest.json") continue;
      ASSERT_TRUE(whole.count(name)) << name;
      EXPECT_TRUE(readFile(entry.path()) == whole.at(name)) << name << " is not what an unlimited run writes";
      frames += name.find("/rgb/") != std::string::npos;
    }
    EXPECT_GE(frames, 1u) << "no colour image was written before the failure";
    const Outcome verify = omnicam("dataset --verify " + sh(ds.string()));
    EXPECT_EQ(verify.out.find(": SHA-256"), std::string::npos) << verify.out;
    EXPECT_EQ(verify.out.find(": missing"), std::string::npos) << verify.out;
  }
  ASSERT_EQ(omnicam("dataset " + sh(specPath) + " -o " + sh(at("limited0"))).code, 0);
  EXPECT_EQ(snapshot(dir_ / "limited0"), whole);
}

TEST_F(OutputFolderTrust, FilesInTheWayOfFoldersEndInExitTwoWithOneLine) {
  const std::string specPath = spec("spec.json", 2);
  const fs::path ds = dataset(specPath, "ds");
  fs::remove_all(ds / "cam0/depth");
  writeFile(ds / "cam0/depth", "planted");
  EXPECT_REFUSED(omnicam("dataset " + sh(specPath) + " -o " + sh(ds.string())), "cam0/depth: is not a folder");
  EXPECT_EQ(readFile(ds / "cam0/depth"), "planted");
  writeFile(ds / "slurm", "planted");
  EXPECT_REFUSED(omnicam("dataset " + sh(specPath) + " -o " + sh(ds.string()) + " --backend slurm --shards 2"),
                 "slurm: is not a folder");
  EXPECT_FALSE(fs::exists(dir_ / "sbatch-calls.txt"));
  fs::create_directories(dir_ / "odd/manifest.json");
  EXPECT_REFUSED(omnicam("dataset " + sh(specPath) + " -o " + sh(at("odd"))), "manifest.json: is not a regular file");
  EXPECT_REFUSED(omnicam("dataset " + sh(specPath) + " -o " + sh(at("victim.txt"))), "exists and is not a folder");
}

TEST_F(OutputFolderTrust, BadOptionsAreRefusedBeforeAnyFolderIsCreated) {
  const std::string specPath = spec("spec.json", 2);
  for (const char* options :
       {"--shard 2/2", "--shard 0/2000000000", "--threads 5000", "--shards 2", "--overwrite --shard 0/2", "--backend pbs",
        "--backend slurm", "--backend slurm --shards 0", "--backend slurm --shards 100001",
        "--backend slurm --shards 2 --max-parallel 0", "--backend slurm --shards 2 --slurm-args nope"}) {
    const Outcome r = omnicam("dataset " + sh(specPath) + " -o " + sh(at("ds")) + " " + options);
    EXPECT_EQ(r.code, 2) << options << ": " << r.err;
    EXPECT_TRUE(isOneLine(r.err)) << options << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "ds")) << options << " left the folder behind";
  }
  EXPECT_FALSE(fs::exists(dir_ / "sbatch-calls.txt"));
}

TEST_F(OutputFolderTrust, ShardCountsAreBoundedBeforeAnyWork) {
  fs::create_directories(dir_ / "ds/shards");
  EXPECT_REFUSED(omnicam("dataset --merge " + sh(at("ds")) + " --shards 2000000000"), "--shards: must be an integer in [1, 100000] (got \"2000000000\")");
  EXPECT_REFUSED(omnicam("dataset --status " + sh(at("ds")) + " --shards 2"), "--shards: only with");
  EXPECT_REFUSED(omnicam("dataset --verify " + sh(at("ds")) + " --shards 2"), "--shards: only with");
  EXPECT_REFUSED(omnicam("dataset --merge " + sh(at("ds")) + " --shards 100000"), "no shard of 100000 has started");
  // A planted shard manifest of a count beyond the bound does not count.
  writeFile(dir_ / "ds/shards/shard-0-of-999999.json", "{}");
  EXPECT_REFUSED(omnicam("dataset --merge " + sh(at("ds"))), "holds no shard manifests (shards/shard-I-of-N.json)");
  EXPECT_FALSE(fs::exists(dir_ / "ds/manifest.json"));
}

}  // namespace
}  // namespace omnicam
