// Untrusted inputs of `omnicam dataset` and friends (docs/robustness.md, "Threat model"): JSON of
// any shape, a spec from someone else, numbers that size work, manifests that were forged or cut
// short, and sbatch options under other spellings. Each case: exit 2, exactly one line naming
// the file and field, and nothing written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "folder_snapshot.h"
#include "shell_command.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using testing::isOneLine;
using testing::readFile;
using nlohmann::json;

// Every entry under `dir` (links not followed) with its bytes: what "nothing written" compares.
std::map<std::string, std::string> snapshot(const fs::path& dir) { return test_support::folderSnapshot(dir); }

class InputTrustTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_input_trust_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fs::copy_file(OMNICAM_SOURCE_DIR "/tests/bad_inputs/datasets/box.json", dir_ / "box.json");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return path(name);
  }
  // A spec over box.json (one pose on path "p") with the root's fields replaced by `fields`.
  std::string spec(const json& fields, const std::string& name = "spec.json") const {
    json s = {{"format", "omnicam-dataset/1"}, {"scene", "box.json"}, {"poses", {{"path", "p"}}}, {"size", 16}};
    for (const auto& [key, value] : fields.items()) s[key] = value;
    return write(name, s.dump());
  }
  testing::CommandResult omnicam(const std::string& args) const {
    return testing::runShell(std::string(OMNICAM_BINARY) + " " + args + " 2>&1");
  }
  // The command ends with exit 2 and one line holding `fragment`, and the folder is as it was.
  void expectRefused(const std::string& args, const std::string& fragment) const {
    const auto before = snapshot(dir_);
    const auto [code, out] = omnicam(args);
    SCOPED_TRACE(args + "\n" + out);
    EXPECT_EQ(code, 2);
    EXPECT_TRUE(isOneLine(out)) << "one line, no control characters";
    EXPECT_NE(out.find(fragment), std::string::npos) << "expected: " << fragment;
    EXPECT_TRUE(snapshot(dir_) == before) << "wrote something";
  }
  void expectSpecRefused(const json& fields, const std::string& fragment) const {
    expectRefused("dataset " + spec(fields) + " -o " + path("ds"), fragment);
  }
  // A finished one-frame dataset in ds/ and its manifest, to forge.
  json renderDataset() const {
    const auto [code, out] = omnicam("dataset " + spec({{"outputs", {{"depth", false}, {"normal", false}}}}) + " -o " + path("ds"));
    EXPECT_EQ(code, 0) << out;
    return json::parse(readFile(dir_ / "ds" / "manifest.json"));
  }
  void expectForgedManifestRefused(const json& manifest, const std::string& fragment) const {
    write("ds/manifest.json", manifest.dump(1));
    expectRefused("dataset --verify " + path("ds"), "manifest.json: " + fragment);
  }
  fs::path dir_;
};

// JSON nested 100,000 levels deep used to overflow the stack (the spec is copied into the
// manifest by a recursive dump) after frames were written; every JSON input is refused at
// limits::kMaxJsonDepth before anything is done with it.
TEST_F(InputTrustTest, DeeplyNestedJsonIsRefusedBeforeAnyWork) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const std::string head = R"({"format": "omnicam-dataset/1", "scene": "box.json", "poses": {"path": "p"}, "comment": )";
  expectRefused("dataset " + write("deep.json", head + deep + "}") + " -o " + path("ds"),
                "deep.json: JSON nested deeper than 64 levels of objects and arrays");
  const std::string scene = R"({"format": "omnicam-scene/1", "materials": {"m": {}}, "objects": [], "comment": )";
  expectRefused("render " + write("deep_scene.json", scene + deep + "}") + " -o " + path("x.png"),
                "deep_scene.json: JSON nested deeper than 64 levels");
  // A glTF arena: tinygltf would walk deep "extras" recursively.
  write("deep.gltf", R"({"asset": {"version": "2.0"}, "extras": )" + deep + "}");
  const std::string gltfScene =
      R"({"format": "omnicam-scene/1", "materials": {"m": {}}, "objects": [{"type": "gltf", "file": "deep.gltf"}]})";
  expectRefused("render " + write("gltf_scene.json", gltfScene) + " -o " + path("x.png"),
                "deep.gltf: JSON nested deeper than 64 levels");
  write("dup.gltf", R"({"asset": {"version": "2.0"}, "scene": 0, "scene": 1})");
  expectRefused("render " + write("dup_scene.json", R"({"format": "omnicam-scene/1", "materials": {"m": {}},
      "objects": [{"type": "gltf", "file": "dup.gltf"}]})") + " -o " + path("x.png"),
                "dup.gltf: duplicate key \"scene\"");
}

// Only the user's own flag lifts the scene-folder rule; a spec that asks is refused.
TEST_F(InputTrustTest, ASpecCannotLiftConfinementOnlyTheUsersFlagCan) {
  expectSpecRefused({{"allow_outside_files", true}},
                    "spec.json: allow_outside_files: a spec cannot let its scene pull in files from outside the scene's "
                    "folder; whoever runs it can (omnicam dataset --allow-outside-files; Python: run_dataset(..., "
                    "allow_outside_files=True))");
  fs::create_directories(dir_ / "scene");
  fs::copy_file(OMNICAM_SOURCE_DIR "/tests/bad_inputs/scenes/texture_outside.json", dir_ / "scene" / "scene.json");
  fs::copy_file(OMNICAM_SOURCE_DIR "/tests/bad_inputs/outside.png", dir_ / "outside.png");
  const std::string outside = spec({{"scene", "scene/scene.json"}, {"poses", {{"list", {{0, 0, 0}}}}}});
  expectRefused("dataset " + outside + " -o " + path("ds"), "\"../outside.png\" resolves outside the scene's folder");
  expectRefused("dataset " + outside + " -o " + path("ds") + " --allow-outside-files --backend slurm --shards 2",
                "--allow-outside-files: only with the local backend");
  expectRefused("dataset --verify " + path("ds") + " --allow-outside-files", "--allow-outside-files: only with a SPEC");
  const auto [code, out] = omnicam("dataset " + outside + " -o " + path("ds") + " --allow-outside-files");
  EXPECT_EQ(code, 0) << out;
}

// Every number that sizes work is checked against its documented range before work starts,
// integers are never wrapped, and messages name the field that is wrong (not a CLI flag).
TEST_F(InputTrustTest, NumbersAreCheckedAgainstTheirRangesAndNamedRight) {
  const json random = {{"count", 5}, {"seed", 1}, {"region", {-1, -1, 1, 1}}};
  json huge = random;
  huge["clearance"] = 1e200;  // was a SIGSEGV in the free-space sweep
  expectSpecRefused({{"poses", {{"random", huge}}}}, "spec.json: poses.random.clearance: must be in [0, 100] m (got 1e+200)");
  expectSpecRefused({{"recording", {{"jpeg_quality", 4294967346u}}}},  // was taken as 50
                    "spec.json: recording.jpeg_quality: must be an integer in [0, 100] (0: no JPEG) (got 4294967346)");
  expectSpecRefused({{"cameras", {{{"name", "c"}, {"mount", {{"y", 1000}}}}}}},  // was named mount.x
                    "spec.json: cameras[0].mount.y: must be in [-100, 100] m from the robot's centre (got 1000)");
  expectSpecRefused({{"size", 16384}, {"spp", 16}},  // was told about --spp
                    "spec.json: spp: size 16384^2 x spp 16 = 4294967296 samples per frame; the limit is 268435456");
  json seed = random;
  seed["seed"] = 9007199254740993u;  // 2^53 + 1 was read as a double: 2^53
  expectSpecRefused({{"poses", {{"random", seed}}}}, "spec.json: poses.random.seed: must be in [0, 9007199254740992]");
  json many = random;
  many["count"] = 60000;
  expectSpecRefused({{"poses", {{"random", many}}}, {"cameras", {{{"name", "a"}}, {{"name", "b"}}}}},
                    "spec.json: poses.random.count: 60000 frames x 2 cameras = 120000 camera-frames; the limit is 100000");
  expectSpecRefused({{"poses", {{"path", "p"}, {"frames", 4294967297u}}}}, "spec.json: poses.frames: must be in [1, 100000]");
  expectSpecRefused({{"engine", "povray"}, {"timeout_s", 1e300}}, "spec.json: timeout_s: must be in (0, 604800] s (got 1e+300)");
  expectSpecRefused({{"frame_interval_s", 1e300}}, "spec.json: frame_interval_s: must be in (0, 86400] s");
  expectSpecRefused({{"mode", "thesis-mesh"}, {"mode_options", {{"polygons", 17}}}},
                    "spec.json: mode_options.polygons: must be 16, 64, 256 or 1024 (got 17)");
  // The scene's rig gives the size: the check happens once the scene is read, still before
  // anything is written, and still names the spec's field.
  json scene = json::parse(readFile(dir_ / "box.json"));
  scene["rig"] = {{"image", {{"size", 16384}}}};
  write("big_rig.json", scene.dump());
  json bigRig = {{"format", "omnicam-dataset/1"}, {"scene", "big_rig.json"}, {"poses", {{"path", "p"}}}, {"spp", 16}};
  expectRefused("dataset " + write("big_rig_spec.json", bigRig.dump()) + " -o " + path("ds"),
                "big_rig_spec.json: spp: size 16384^2 x spp 16 = 4294967296 samples per frame");
  expectRefused("render " OMNICAM_SOURCE_DIR "/scenes/robocup2006.json --engine povray --timeout 1e300 -o " + path("x.png"),
                "--timeout");
}

// A manifest is another user's file like any other: forged or cut short, it ends in exit 2 with
// one line naming the field, never an internal error (exit 4), and it names no file outside its
// cameras' folders.
TEST_F(InputTrustTest, ForgedAndTruncatedManifestsAreRefusedNamingTheField) {
  const json good = renderDataset();
  ASSERT_FALSE(good["frames"].empty());
  const std::string manifest = good.dump(1);
  write("ds/manifest.json", manifest.substr(0, manifest.size() / 2));
  expectRefused("dataset --verify " + path("ds"), "manifest.json: not valid JSON");
  const auto forged = [&](const std::string& pointer, const json& value) {
    json m = good;
    m[json::json_pointer(pointer)] = value;
    return m;
  };
  expectForgedManifestRefused(forged("/frame_count", "1"), "frame_count: must be an integer (got string)");
  expectForgedManifestRefused(forged("/frame_count", 1e300), "frame_count: must be in [0, 100000] (got 1e+300)");
  expectForgedManifestRefused(forged("/complete", 1), "complete: must be true or false");
  expectForgedManifestRefused(forged("/spec_sha256", 7), "spec_sha256: must be a string (got number)");
  expectForgedManifestRefused(forged("/frames/0/index", -1), "frames[0].index: must be in [0, 0] (got -1)");
  expectForgedManifestRefused(forged("/frames/0/index", 18446744073709551615u), "frames[0].index: must be in [0, 0]");
  expectForgedManifestRefused(forged("/frames/0/pose/x", 1e300), "frames[0].pose: x and y must be within ±10000 m");
  expectForgedManifestRefused(forged("/frames/0/cameras/cam0/files/rgb/path", "../x"),
                              "frames[0].cameras.cam0.files.rgb.path: must be a file in the dataset's camera folder cam0");
  expectForgedManifestRefused(forged("/frames/0/cameras/cam0/files/rgb/path", "/etc/passwd"),
                              "frames[0].cameras.cam0.files.rgb.path: must be a file in the dataset's camera folder");
  expectForgedManifestRefused(forged("/frames/0/cameras/cam0/files/rgb/path", "cam0/rgb/../../../x"),
                              "frames[0].cameras.cam0.files.rgb.path: must be a file in the dataset's camera folder");
  expectForgedManifestRefused(forged("/cameras/0/files/poses_tum/path", "cam0/../manifest.json"),
                              "cameras[0].files.poses_tum.path: must be a file in the dataset's camera folder");
  expectForgedManifestRefused(forged("/frames/0/cameras/cam0/files/rgb/sha256", "x"),
                              "frames[0].cameras.cam0.files.rgb.sha256: must be 64 lowercase hex digits");
  expectForgedManifestRefused(forged("/frames/0/cameras/other", good["frames"][0]["cameras"]["cam0"]),
                              "frames[0].cameras.other: not a camera of the manifest's cameras");
  expectForgedManifestRefused(forged("/shard", {{"index", 0}, {"count", 1}, {"first_frame", 0}, {"end_frame", 5}}),
                              "shard.end_frame: must be in [0, 1] (got 5)");
  json missing = good;
  missing["frames"][0].erase("pose");
  expectForgedManifestRefused(missing, "frames[0].pose: missing required field");
  json twice = good;
  twice["frames"].push_back(good["frames"][0]);
  expectForgedManifestRefused(twice, "frames[1].index: frame 0 listed twice");
  json wrongType = good;
  wrongType["frames"] = json::object();
  expectForgedManifestRefused(wrongType, "frames: must be an array");
  // The same reader serves --status and resuming.
  write("ds/manifest.json", forged("/frames/0/cameras/cam0/files/rgb/path", "../x").dump());
  expectRefused("dataset --status " + path("ds"), "frames[0].cameras.cam0.files.rgb.path");
}

// sbatch takes unambiguous prefixes of long options and short options with their value attached
// (also after other flags): every spelling of the options omnicam sets itself is refused.
TEST_F(InputTrustTest, ReservedSbatchOptionsAreRefusedUnderEverySpelling) {
  const std::string base = "dataset " + spec({}) + " -o " + path("ds") + " --backend slurm --shards 2 --slurm-args=";
  for (const auto& [words, option] : std::map<std::string, std::string>{{"--out=x.log", "--output"},
                                                                          {"--o=x.log", "--output"},
                                                                          {"-ox.log", "--output"},
                                                                          {"-o", "--output"},
                                                                          {"-Hox.log", "--output"},
                                                                          {"-dafterok:1", "--dependency"},
                                                                          {"--dep=afterok:1", "--dependency"},
                                                                          {"--arr=0-9", "--array"},
                                                                          {"-a0-9", "--array"},
                                                                          {"--er=e.log", "--error"},
                                                                          {"-vee.log", "--error"},
                                                                          {"--wr=id", "--wrap"}})
    expectRefused(base + "'--partition=cpu " + words + "'", "sbatch reads it as " + option + "; omnicam sets --array");
}

// Every output name a verb writes — the image's sidecar, every texture of an arena, a report's
// image folder — and every option is checked before the first byte is written: a refusal leaves
// the folder as it was (docs/robustness.md, "One line, exit 2, nothing written").
TEST_F(InputTrustTest, OutputNamesAndOptionsAreCheckedBeforeTheFirstByte) {
  fs::create_directories(dir_ / "r.exr.json");
  expectRefused("camera-rays " + path("box.json") + " -o " + path("r.exr") + " --size 8", "-o (its sidecar): ");
  fs::create_directories(dir_ / "x.png.json");
  expectRefused("render " + path("box.json") + " --size 8 -o " + path("x.png"), "-o (its sidecar): ");
  fs::create_directories(dir_ / "z.panorama.png.json");
  expectRefused("render " + path("box.json") + " --size 8 --view panorama -o " + path("z.png"), "--view (its sidecar): ");
  // A later texture's name taken by a folder: no texture and no scene written.
  const std::string photo = "/usr/share/blender/datafiles/studiolights/world/interior.exr";
  ASSERT_TRUE(fs::exists(photo)) << photo << " is missing: make deps installs blender-data";
  fs::create_directories(dir_ / "hall_textures" / "hall_wall_east.png");
  expectRefused("arena hall --photo " + photo + " -o " + path("hall.json"), "hall_wall_east.png is an existing folder");
  // Options of an experiment before its folder.
  expectRefused("experiment texture-realism --quick --bins 1 -o " + path("ex"), "--bins: must be an integer in [2, 256] (got \"1\")");
  EXPECT_FALSE(fs::exists(dir_ / "ex"));
  expectRefused("experiment realistic-convergence --quick --theta 2 -o " + path("ex"), "--theta: only with");
  EXPECT_FALSE(fs::exists(dir_ / "ex"));
  expectRefused("demo --spp 5 -o " + path("demo"), "--spp: must be a perfect square");
  EXPECT_FALSE(fs::exists(dir_ / "demo"));
  // A POV-Ray job's last file name taken: not even scene.pov is written.
  fs::create_directories(dir_ / "job" / "render.ini");
  expectRefused("export " + path("box.json") + " --to povray --size 8 -o " + path("job"), "render.ini is an existing folder");
  // A folder path through a file: refused as input, before any work.
  write("afile", "x");
  expectRefused("arena hall -o " + path("afile/sub/hall.json"), "afile exists and is not a folder");
  expectRefused("export " + path("box.json") + " --to gltf -o " + path("afile/sub"), "afile exists and is not a folder");
  // A link to nothing where the folder goes is named as what it is.
  fs::create_symlink(dir_ / "nowhere", dir_ / "dangling");
  expectRefused("export " + path("box.json") + " --to gltf -o " + path("dangling"),
                "-o: " + path("dangling") + " is a symbolic link to nothing: remove it, or give another folder");
  // A write that fails after the folders were made removes the folders it made, empty.
  const auto before = snapshot(dir_);
  const auto [code, out] = testing::runShell("ulimit -f 1; " + std::string(OMNICAM_BINARY) + " export " + path("box.json") +
                                             " --to gltf -o " + path("g1/g2/g3") + " 2>&1");
  EXPECT_EQ(code, 5) << out;
  EXPECT_FALSE(fs::exists(dir_ / "g1")) << out;
  EXPECT_TRUE(snapshot(dir_) == before);

  // A POV-Ray job is its scene, its textures and render.ini: all of them or none. Its scene.pov
  // fits under the limit, its texture does not.
  ASSERT_EQ(testing::runShell(std::string(OMNICAM_BINARY) + " render " + path("box.json") + " --size 128 -o " + path("tex.png")).code, 0);
  json textured = json::parse(testing::readFile(dir_ / "box.json"));
  textured["materials"]["grey"]["texture"] = {{"file", "tex.png"}};
  write("textured.json", textured.dump());
  const auto withTexture = snapshot(dir_);
  const auto job = testing::runShell("ulimit -f 8; " + std::string(OMNICAM_BINARY) + " export " + path("textured.json") +
                                     " --to povray --size 8 -o " + path("p1/p2") + " 2>&1");
  EXPECT_EQ(job.code, 5) << job.out;
  EXPECT_NE(job.out.find("tex_0.exr: cannot write (File too large)"), std::string::npos) << job.out;
  EXPECT_FALSE(fs::exists(dir_ / "p1")) << job.out;
  EXPECT_TRUE(snapshot(dir_) == withTexture);
  ASSERT_EQ(testing::runShell(std::string(OMNICAM_BINARY) + " export " + path("textured.json") + " --to povray --size 8 -o " +
                              path("p1/p2")).code, 0);
  for (const char* name : {"scene.pov", "render.ini", "tex_0.exr"}) EXPECT_TRUE(fs::exists(dir_ / "p1/p2" / name)) << name;
  EXPECT_LT(fs::file_size(dir_ / "p1/p2/scene.pov"), 8u << 10) << "the limit no longer separates the scene from its texture";
}

// An image, its views and their sidecars appear together or not at all: a sidecar that does not
// fit (the file-size limit; a full disk alike) leaves no image without it, in a single render
// and in a path's frames.
TEST_F(InputTrustTest, AnImageItsViewsAndTheirSidecarsAppearTogetherOrNotAtAll) {
  fs::create_directories(dir_ / "frames");
  const auto before = snapshot(dir_);
  const std::string limited = "ulimit -f 1; " + std::string(OMNICAM_BINARY) + " render " + path("box.json") + " --size 16 ";
  const auto single = testing::runShell(limited + "--view birdseye -o " + path("x.png") + " 2>&1");
  EXPECT_EQ(single.code, 5) << single.out;
  EXPECT_NE(single.out.find("x.png.json: cannot write (File too large)"), std::string::npos) << single.out;
  EXPECT_TRUE(snapshot(dir_) == before) << single.out;
  const auto frames = testing::runShell(limited + "--path p --view birdseye -o " + path("frames") + " 2>&1");
  EXPECT_EQ(frames.code, 5) << frames.out;
  EXPECT_TRUE(snapshot(dir_) == before) << frames.out;
  // A folder the file system will not make (/sys takes no new folders, even from root) is an
  // output that cannot be written: exit 5, as for a file, not bad input.
  for (const std::string& verb : {"render " + path("box.json") + " --size 16 --path p", "export " + path("box.json") + " --to gltf"}) {
    const auto made = testing::runShell(std::string(OMNICAM_BINARY) + " " + verb + " -o /sys/omnicam_trust_" + std::to_string(::getpid()) + " 2>&1");
    EXPECT_EQ(made.code, 5) << verb << ": " << made.out;
    EXPECT_NE(made.out.find("-o: cannot create folder /sys/omnicam_trust_"), std::string::npos) << made.out;
  }
  // Without the limit, all of them.
  ASSERT_EQ(testing::runShell(std::string(OMNICAM_BINARY) + " render " + path("box.json") + " --size 16 --view birdseye -o " + path("x.png")).code, 0);
  for (const char* name : {"x.png", "x.png.json", "x.birdseye.png", "x.birdseye.png.json"}) EXPECT_TRUE(fs::exists(dir_ / name)) << name;
  // `view` of that image: the view and its sidecar together, or neither.
  const auto view = testing::runShell("ulimit -f 1; " + std::string(OMNICAM_BINARY) + " view " + path("x.png") +
                                      " --as panorama --size 16x8 -o " + path("pano.png") + " 2>&1");
  EXPECT_EQ(view.code, 5) << view.out;
  EXPECT_FALSE(fs::exists(dir_ / "pano.png")) << view.out;
}

// Integer flags are read as written, like the spec reader's JSON integers: never wrapped
// (2^64 → 0, −1 → 2^64 − 1), clamped, or read as octal or hex.
TEST_F(InputTrustTest, IntegerFlagsAreReadExactly) {
  for (const std::string seed : {"18446744073709551616", "99999999999999999999999", "-1", "0x10", "+5", "1e3", "' 5'", "''"})
    expectRefused("arena mapping --seed " + seed + " -o " + path("m.json"), "--seed: must be an integer in [0, 18446744073709551615]");
  // A leading zero is said (the range's words would not explain why 010 is refused).
  expectRefused("arena mapping --seed 010 -o " + path("m.json"), "--seed: must be written without a leading zero (got \"010\")");
  expectRefused("render " + path("box.json") + " --size 010 -o " + path("x.png"), "--size: must be written without a leading zero (got \"010\")");
  expectRefused("render " + path("box.json") + " --spp 04 -o " + path("x.png"), "--spp: must be written without a leading zero (got \"04\")");
  expectRefused("render " + path("box.json") + " --size 4294967304 -o " + path("x.png"), "--size: must be an integer in [8, 16384]");
  expectRefused("render " + path("box.json") + " --mode cubemap --faces 0x5 -o " + path("x.png"), "--faces: must be an integer, 5 or 6 (got \"0x5\")");
  // Past 2^31 the rule sees the value as given: never clamped to 2147483647 first.
  expectRefused("render " + path("box.json") + " --mode cubemap --faces 4294967301 -o " + path("x.png"), "--faces: must be 5 or 6 (got 4294967301)");
  expectRefused("dataset " + spec({}) + " -o " + path("ds") + " --threads 4097", "--threads: must be an integer in [0, 4096] (got \"4097\")");
  expectRefused("dataset " + spec({}) + " -o " + path("ds") + " --shard 01/2", "--shard: must be I/N");
  expectRefused("dataset " + spec({}) + " -o " + path("ds") + " --shard ' 1/2'", "--shard: must be I/N");
  expectRefused("view " + path("box.json") + " --as panorama --size 0400x300 -o " + path("v.png"), "--size: must be WIDTHxHEIGHT");
  expectRefused("bench --seconds nan", "--seconds: must be a number in (0, 3600] (got \"nan\")");
  expectRefused("compare " + path("box.json") + " " + path("box.json") + " --tol inf", "--tol: must be a number in [0, 1e+06] (got \"inf\")");
  expectRefused("view " + path("box.json") + " --zw 0x10 -o " + path("v.png"), "--zw: must be a number in (0, 1e+06] (got \"0x10\")");
  expectRefused("view " + path("box.json") + " --as perspective --pitch ' 5' -o " + path("v.png"), "--pitch: must be a number");
  // The largest seed is a seed.
  const auto [code, out] = omnicam("arena mapping --seed 18446744073709551615 -o " + path("m.json"));
  EXPECT_EQ(code, 0) << out;
  EXPECT_NE(out.find("seed 18446744073709551615"), std::string::npos) << out;
}

// Work whose size the input sets, within the documented limits, but more than this machine (here:
// a 4 GiB address space) can hold, is refused before it is allocated: exit 5, one line saying
// what it needs, nothing written — never "internal error: out of memory".
TEST_F(InputTrustTest, WorkBeyondTheMachinesMemoryIsRefusedBeforeItIsAllocated) {
  const auto refusedForMemory = [&](const std::string& command) {
    const auto before = snapshot(dir_);
    const auto [code, out] = testing::runShell("ulimit -v 4194304; " + std::string(OMNICAM_BINARY) + " " + command + " 2>&1");
    SCOPED_TRACE(command + "\n" + out);
    EXPECT_EQ(code, 5);
    EXPECT_TRUE(isOneLine(out));
    EXPECT_NE(out.find(" of memory, and the program 256 MiB more; "), std::string::npos);
    EXPECT_NE(out.find("limited by the address-space limit (ulimit -v)"), std::string::npos);
    EXPECT_TRUE(snapshot(dir_) == before) << "wrote something";
  };
  refusedForMemory("camera-rays " + path("box.json") + " -o " + path("rays.exr") + " --size 16384");
  // Two 16384 x 8192 images (a few hundred KB each as PNG): 2 GiB each as floats.
  for (const char* name : {"a.png", "b.png"}) {
    const auto [code, out] = testing::runShell("oiiotool --create 16384x8192 4 -o " + path(name) + " 2>&1");
    ASSERT_EQ(code, 0) << "oiiotool (openimageio-tools, make deps): " << out;
  }
  // Two such images compare streamed, in bounded memory (issue #45); their heat map needs them whole.
  {
    const auto [code, out] = testing::runShell("ulimit -v 4194304; " + std::string(OMNICAM_BINARY) + " compare " +
                                               path("a.png") + " " + path("b.png") + " 2>&1");
    EXPECT_EQ(code, 0) << out;
    EXPECT_NE(out.find("compared 134217728 pixels"), std::string::npos) << out;
  }
  refusedForMemory("compare " + path("a.png") + " " + path("b.png") + " --diff " + path("d.png"));
  // Datasets: B (a folder in the dataset layout) holds such a frame where A's 16-pixel one is.
  renderDataset();
  fs::create_directories(dir_ / "b" / "cam0" / "rgb");
  fs::copy_file(dir_ / "a.png", dir_ / "b" / "cam0" / "rgb" / "000000.png");
  // Streamed too: the frames' sizes are compared first, and B's frame is named.
  {
    const auto [code, out] = testing::runShell("ulimit -v 4194304; " + std::string(OMNICAM_BINARY) + " compare " +
                                               path("ds") + " " + path("b") + " 2>&1");
    EXPECT_EQ(code, 2) << out;
    EXPECT_TRUE(isOneLine(out)) << out;
    EXPECT_NE(out.find("000000.png: frame 0 of camera \"cam0\" is 16384x8192, A's is 16x16"), std::string::npos) << out;
  }
  // Multilayer: B's frame file a valid 16384 x 8192 OpenEXR (half RGBA, a few hundred KB): the
  // frame reader sizes it per channel, and a shortage stays a shortage (exit 5), not bad input.
  const auto [made, madeOut] = omnicam("dataset " + spec({{"layout", "multilayer"}, {"outputs", json::object()}}, "ml.json") +
                                       " -o " + path("ml"));
  ASSERT_EQ(made, 0) << madeOut;
  fs::copy(dir_ / "ml", dir_ / "mlb", fs::copy_options::recursive);
  const auto [created, createdOut] = testing::runShell("oiiotool --create 16384x8192 4 -d half --compression zip -o " +
                                                       path("mlb/cam0/multilayer/000000.exr") + " 2>&1");
  ASSERT_EQ(created, 0) << createdOut;
  refusedForMemory("compare " + path("ml") + " " + path("mlb"));
}

}  // namespace
}  // namespace omnicam
