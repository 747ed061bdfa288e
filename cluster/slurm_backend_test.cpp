// The parts of the Slurm backend that need no cluster: array specs and the sbatch options a user
// may pass (the real-Slurm end-to-end test is tests/slurm_cli_test.cpp).
#include "slurm_backend.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace omnicam
