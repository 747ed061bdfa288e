#include "experiment_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "errors.h"
#include "scratch_folder.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

class ExperimentFolder : public ::testing::Test {
 protected:
  std::string errorOf(const std::string& study) const {
    try {
      checkExperimentFolder(dir_.string(), study);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  const test_support::ScratchFolder scratch_{"omnicam_experiment_folder"};
  const fs::path& dir_ = scratch_.path();
};

// A folder of the experiments' own layout and nothing else is an earlier run's that ended before
// its results, written before marks: taken up again (its Cycles frames reused). One file of the
// user's among them makes it a folder of other files.
TEST_F(ExperimentFolder, AnInterruptedRunsFolderFromBeforeMarksIsTakenUpAgain) {
  for (const char* folder : {"cycles", "arenas", "data", "figures", "frames", "scenes"}) fs::create_directories(dir_ / folder);
  EXPECT_EQ(errorOf("texture-realism"), "");
  std::ofstream(dir_ / "notes.txt") << "mine";
  EXPECT_EQ(errorOf("texture-realism"), dir_.string() + ": holds files no omnicam experiment wrote (\"notes.txt\"): give an empty or new folder");
  std::ofstream(dir_ / "a.txt") << "mine";
  EXPECT_EQ(errorOf("texture-realism"),
            dir_.string() + ": holds files no omnicam experiment wrote (\"a.txt\" and 1 more): give an empty or new folder");
}

// A mark names the folder's experiment: the same study takes it up, another is refused by name;
// a mark that names none, or is a link, is refused. markExperimentFolder leaves a mark it finds.
TEST_F(ExperimentFolder, AMarkTellsWhoseFolderItIs) {
  markExperimentFolder(dir_.string(), "calibration");
  EXPECT_EQ(errorOf("calibration"), "");
  EXPECT_EQ(errorOf("texture-realism"), (dir_ / kExperimentMark).string() +
                                            ": the folder is experiment \"calibration\"'s (its mark), not texture-realism's: give another folder");
  markExperimentFolder(dir_.string(), "texture-realism");  // a mark is never rewritten
  EXPECT_EQ(errorOf("calibration"), "");
  std::ofstream(dir_ / kExperimentMark) << R"({"by": "me"})";
  EXPECT_EQ(errorOf("calibration"), (dir_ / kExperimentMark).string() +
                                        ": not written by an omnicam experiment (it names no study): give another folder");
  fs::remove(dir_ / kExperimentMark);
  std::ofstream(dir_ / "elsewhere.json") << R"({"study": "calibration"})";
  fs::create_symlink(dir_ / "elsewhere.json", dir_ / kExperimentMark);
  EXPECT_EQ(errorOf("calibration"), (dir_ / kExperimentMark).string() + ": a link (omnicam follows none in its outputs): give another folder");
}

// A run without figures makes no figures/ (it would stay empty); one with them does.
TEST_F(ExperimentFolder, ARunMakesFiguresOnlyWhenItPlotsThem) {
  makeRunFolders(dir_.string(), {"arenas", "data"}, false);
  EXPECT_TRUE(fs::is_directory(dir_ / "arenas") && fs::is_directory(dir_ / "data"));
  EXPECT_FALSE(fs::exists(dir_ / "figures"));
  makeRunFolders(dir_.string(), {"arenas", "data"}, true);
  EXPECT_TRUE(fs::is_directory(dir_ / "figures"));
}

}  // namespace
}  // namespace omnicam
