// realistic_convergence: its results file round-trips, is read as untrusted input, and its
// Markdown shows the means and worst cases computed by hand.
#include "realistic_convergence.h"

#include <gtest/gtest.h>

#include "errors.h"

namespace omnicam {
namespace {

ConvergenceResults sample() {
  ConvergenceResults r;
  r.setups = {"before", "physical", "today"};
  r.setupDescriptions = {"point lamps", "lamps of real size", "lamps of real size, indirect light filtered"};
  auto point = [](const std::string& setup, int pose, int spp, double db, double outliers) {
    ConvergencePoint p{setup, pose, spp, {}};
    p.noise.psnrDb = db;
    p.noise.outlierShare = outliers;
    p.noise.pixels = 3000;
    return p;
  };
  r.ladder = {point("before", 0, 16, 20.0, 0.07), point("before", 33, 16, 22.0, 0.05),
              point("physical", 0, 16, 25.0, 0.02), point("physical", 33, 16, 26.0, 0.02),
              point("today", 0, 16, 27.0, 0.01), point("today", 33, 16, 29.0, 0.03),
              point("physical", 0, 64, 31.0, 0.0), point("physical", 33, 64, 33.0, 0.0),
              point("today", 0, 64, 38.0, 0.0), point("today", 33, 64, 41.0, 0.0)};
  r.paths = {{"before", "point lamps, everything traced", 18.0, 18.0 + 3.0103, 0.07},
             {"today_direct", "lamps of real size, only \"ceiling_0\" on", 28.0, 28.0 + 3.0103, 0.009}};
  r.clampIndirect = 1.0;
  r.clampBiasPsnrDb = 29.5;
  r.clampBiasLuminancePercent = -2.5;
  r.experimentSize = 360;
  r.experimentSpp = 36;
  r.experimentReferenceSpp = 1024;
  r.experimentPsnrDb = {34.3, 36.2};
  r.size = 64;
  r.referenceSpp = 8192;
  r.seconds = 600;
  return r;
}

TEST(RealisticConvergence, ResultsRoundTripThroughJson) {
  const ConvergenceResults r = sample();
  const ConvergenceResults back = convergenceFromJson(convergenceJson(r), "c.json");
  EXPECT_EQ(convergenceJson(back), convergenceJson(r));
  EXPECT_EQ(convergenceMarkdown(back, "f.svg"), convergenceMarkdown(r, "f.svg"));
  ConvergenceResults quick = sample();
  quick.quick = true;
  EXPECT_TRUE(convergenceFromJson(convergenceJson(quick), "c.json").quick);
  // A file from before runs said whether they were quick: told by its check's size.
  nlohmann::json old = convergenceJson(quick);
  old.erase("quick");
  EXPECT_FALSE(convergenceFromJson(old, "c.json").quick);  // 360 px: the experiment's own
  old["experiment_check"]["size"] = 64;
  EXPECT_TRUE(convergenceFromJson(old, "c.json").quick);
}

TEST(RealisticConvergence, MarkdownShowsMeansWorstCasesAndTheTargetVerdict) {
  const std::string md = convergenceMarkdown(sample(), "figures/c.svg");
  // spp 16: before mean 21.0 (worst 20.0), outliers 6.00 %; physical 25.5 (25.0), 2.00 %; today 28.0 (27.0), 2.00 %.
  EXPECT_NE(md.find("| 16 | 21.0 (20.0) | 6.00 | 25.5 (25.0) | 2.00 | 28.0 (27.0) | 2.00 |"), std::string::npos) << md;
  // The filter's bias is read at the top rung, 64 spp: today 39.5 (38.0), physical 32.0.
  EXPECT_NE(md.find("at 64 spp, the ladder's top, filtered frames are 39.5 dB (worst 38.0)"), std::string::npos) << md;
  EXPECT_NE(md.find("unfiltered ones 32.0 dB, at 64 px, where a pixel spans 5.6×"), std::string::npos) << md;
  EXPECT_NE(md.find("poses 0 and 33 of thesis-loop"), std::string::npos) << md;
  EXPECT_NE(md.find("](figures/c.svg)"), std::string::npos);
  // Worst experiment frame 34.3 dB against its reference: short of 35 dB.
  EXPECT_NE(md.find("At the experiment's own 360 px and 36 spp"), std::string::npos) << md;
  EXPECT_NE(md.find("unfiltered 1024-spp references: worst 34.3 dB"), std::string::npos) << md;
  EXPECT_NE(md.find("short of the 35 dB target"), std::string::npos);
  ConvergenceResults better = sample();
  better.experimentPsnrDb = {35.0, 40.0};
  EXPECT_NE(convergenceMarkdown(better, "").find("the 35 dB target is met"), std::string::npos);
  EXPECT_NE(md.find("Measured by `omnicam experiment realistic-convergence -o DIR` ("), std::string::npos) << md;
  // A quick run (64 px for the experiment's check) says so, and judges no target.
  ConvergenceResults quick = sample();
  quick.experimentSize = 64;
  quick.quick = true;
  const std::string quickMd = convergenceMarkdown(quick, "");
  EXPECT_NE(quickMd.find("Measured by `omnicam experiment realistic-convergence -o DIR --quick`"), std::string::npos) << quickMd;
  EXPECT_NE(quickMd.find("At a quick run's 64 px (the experiment renders 360 px) and 36 spp"), std::string::npos) << quickMd;
  EXPECT_NE(quickMd.find("not a measure of the 35 dB target, which a run without --quick checks"), std::string::npos) << quickMd;
  EXPECT_EQ(quickMd.find("short of the 35 dB target"), std::string::npos) << quickMd;
  EXPECT_NE(md.find("-2.5 %"), std::string::npos);
}

TEST(RealisticConvergence, AResultsFileIsUntrustedInput) {
  nlohmann::json j = convergenceJson(sample());
  j["setups"][0]["description"] = "<script>alert(1)</script>";
  EXPECT_THROW(convergenceFromJson(j, "c.json"), InputError);
  j = convergenceJson(sample());
  j["ladder"][0]["psnr_db"] = "high";
  EXPECT_THROW(convergenceFromJson(j, "c.json"), InputError);
  j = convergenceJson(sample());
  j["format"] = "other";
  EXPECT_THROW(convergenceFromJson(j, "c.json"), InputError);
  EXPECT_THROW(convergenceFromJson(nlohmann::json::array(), "c.json"), InputError);
}

}  // namespace
}  // namespace omnicam
