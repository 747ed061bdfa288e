#include "realistic_convergence.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "errors.h"
#include "indirect_filter.h"
#include "json_text.h"
#include "number_format.h"

namespace omnicam {

nlohmann::json convergenceJson(const ConvergenceResults& r) {
  nlohmann::json ladder = nlohmann::json::array(), paths = nlohmann::json::array(), setups = nlohmann::json::array();
  for (size_t k = 0; k < r.setups.size(); ++k) setups.push_back({{"name", r.setups[k]}, {"description", r.setupDescriptions[k]}});
  for (const ConvergencePoint& p : r.ladder)
    ladder.push_back({{"setup", p.setup}, {"pose", p.pose}, {"spp", p.spp}, {"psnr_db", p.noise.psnrDb},
                      {"outlier_share", p.noise.outlierShare}, {"pixels", p.noise.pixels}});
  for (const PathVariant& v : r.paths)
    paths.push_back({{"name", v.name}, {"description", v.description}, {"pair_psnr_db", v.pairPsnrDb},
                     {"estimated_psnr_db", v.estimatedPsnrDb}, {"outlier_share", v.outlierShare}});
  return {{"format", "omnicam-realistic-convergence-2"},
          {"size", r.size},
          {"reference_spp", r.referenceSpp},
          {"setups", setups},
          {"ladder", ladder},
          {"paths", paths},
          {"clamp_bias", {{"clamp_indirect", r.clampIndirect}, {"psnr_db", r.clampBiasPsnrDb}, {"luminance_percent", r.clampBiasLuminancePercent}}},
          {"experiment_check",
           {{"size", r.experimentSize}, {"spp", r.experimentSpp}, {"reference_spp", r.experimentReferenceSpp}, {"psnr_db", r.experimentPsnrDb}}},
          {"seconds", r.seconds},
          {"quick", r.quick}};
}

namespace {

// Strings from a results file end up in Markdown: plain words only.
std::string plainText(const nlohmann::json& value, const std::string& file, const std::string& field) {
  const std::string text = value.get<std::string>();
  if (text.empty() || text.size() > 200 ||
      std::any_of(text.begin(), text.end(), [](char c) {
        return static_cast<unsigned char>(c) < 0x20 || std::string("<>|`[]\\*&").find(c) != std::string::npos;
      }))
    throw InputError(showPath(file) + ": " + field + ": not plain text: " + quote(text));
  return text;
}

}  // namespace

ConvergenceResults convergenceFromJson(const nlohmann::json& j, const std::string& file) {
  ConvergenceResults r;
  try {
    if (j.at("format") != "omnicam-realistic-convergence-2")
      throw InputError(showPath(file) + ": format: not omnicam-realistic-convergence-2");
    r.size = j.at("size").get<int>();
    r.referenceSpp = j.at("reference_spp").get<int>();
    for (const auto& s : j.at("setups")) {
      r.setups.push_back(plainText(s.at("name"), file, "setups.name"));
      r.setupDescriptions.push_back(plainText(s.at("description"), file, "setups.description"));
    }
    for (const auto& p : j.at("ladder")) {
      ConvergencePoint point{plainText(p.at("setup"), file, "ladder.setup"), p.at("pose").get<int>(), p.at("spp").get<int>(), {}};
      point.noise.psnrDb = p.at("psnr_db").get<double>();
      point.noise.outlierShare = p.at("outlier_share").get<double>();
      point.noise.pixels = p.at("pixels").get<long>();
      r.ladder.push_back(point);
    }
    for (const auto& v : j.at("paths"))
      r.paths.push_back({plainText(v.at("name"), file, "paths.name"), plainText(v.at("description"), file, "paths.description"),
                         v.at("pair_psnr_db").get<double>(), v.at("estimated_psnr_db").get<double>(),
                         v.at("outlier_share").get<double>()});
    r.clampIndirect = j.at("clamp_bias").at("clamp_indirect").get<double>();
    r.clampBiasPsnrDb = j.at("clamp_bias").at("psnr_db").get<double>();
    r.clampBiasLuminancePercent = j.at("clamp_bias").at("luminance_percent").get<double>();
    r.experimentSize = j.at("experiment_check").at("size").get<int>();
    r.experimentSpp = j.at("experiment_check").at("spp").get<int>();
    r.experimentReferenceSpp = j.at("experiment_check").at("reference_spp").get<int>();
    r.experimentPsnrDb = j.at("experiment_check").at("psnr_db").get<std::vector<double>>();
    r.seconds = j.at("seconds").get<double>();
    // Written before runs said whether they were quick: a quick one's check was smaller than the experiment's frames.
    r.quick = j.contains("quick") ? j.at("quick").get<bool>() : r.experimentSize != ConvergenceOptions().experimentSize;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(showPath(file) + ": not a realistic-convergence result: " + jsonErrorText(oneLine(e.what())));
  }
  return r;
}

namespace {

// Mean and minimum PSNR and the mean outlier share of one setup at one rung, over the poses.
struct RungSummary {
  double meanPsnr = 0.0, minPsnr = 1e9, outliers = 0.0;
  int poses = 0;
};

RungSummary summarise(const ConvergenceResults& r, const std::string& setup, int spp) {
  RungSummary s;
  for (const ConvergencePoint& p : r.ladder)
    if (p.setup == setup && p.spp == spp) {
      s.meanPsnr += p.noise.psnrDb;
      s.minPsnr = std::min(s.minPsnr, p.noise.psnrDb);
      s.outliers += p.noise.outlierShare;
      ++s.poses;
    }
  if (s.poses) {
    s.meanPsnr /= s.poses;
    s.outliers /= s.poses;
  }
  return s;
}

const PathVariant* findVariant(const ConvergenceResults& r, const std::string& name) {
  for (const PathVariant& v : r.paths)
    if (v.name == name) return &v;
  return nullptr;
}

// The filter of the experiment's setup: what it is, its bias (read at the ladder's top rung) and
// the check at the experiment's own size.
std::string filterMarkdown(const ConvergenceResults& r) {
  std::ostringstream md;
  int top = 0;
  for (const ConvergencePoint& p : r.ladder) top = std::max(top, p.spp);
  const RungSummary filtered = summarise(r, "today", top), unfiltered = summarise(r, "physical", top);
  const IndirectFilterParameters f;
  md << "\nFiltering the indirect light (`today`, denoise/indirect_filter.h): Cycles renders each frame twice with the same "
        "seed, once with every path and once ending at the first surface seen in the mirror (its direct light), with its "
        "albedo, normal and depth passes, which pass through the sharp mirror. The difference, the indirect light, is "
        "divided by the albedo, averaged over the "
     << f.window() << "×" << f.window() << " window of pixels that see the same surface (Gaussian of " << fixedDecimals(f.spatialSigmaPx, 0)
     << " px, weighted by the agreement of normals to the power " << fixedDecimals(f.normalExponent, 0) << " and of depths within "
     << fixedDecimals(100.0 * f.relativeDepthSigma, 0)
     << " %) and multiplied back; direct light and textures stay as traced, and so do pixels that straddle two surfaces. "
        "Each sample costs about 1.8× an unfiltered one.";
  if (filtered.poses && unfiltered.poses)
    md << " Its bias: at " << top << " spp, the ladder's top, filtered frames are " << fixedDecimals(filtered.meanPsnr, 1)
       << " dB (worst " << fixedDecimals(filtered.minPsnr, 1) << ") from the unfiltered converged reference, unfiltered ones "
       << fixedDecimals(unfiltered.meanPsnr, 1) << " dB, at " << r.size << " px, where a pixel spans " << fixedDecimals(360.0 / r.size, 1)
       << "× more of the hall than at 360 px (the window with it).";
  md << '\n';
  if (!r.experimentPsnrDb.empty()) {
    double worst = 1e9;
    for (double p : r.experimentPsnrDb) worst = std::min(worst, p);
    // A quick run's images are smaller than the experiment's: its check is of the pipeline, not of the target.
    const int experimentSize = ConvergenceOptions().experimentSize;
    const bool quick = r.quick;
    md << "\nAt " << (quick ? "a quick run's " : "the experiment's own ") << r.experimentSize << " px"
       << (quick ? " (the experiment renders " + std::to_string(experimentSize) + " px)" : "") << " and " << r.experimentSpp
       << " spp, the experiment's frames of the same poses against unfiltered " << r.experimentReferenceSpp
       << "-spp references: worst " << fixedDecimals(worst, 1)
       << " dB (a lower bound: the reference's own noise counts against the frame) — "
       << (quick ? "not a measure of the 35 dB target, which a run without --quick checks"
                 : worst >= 35.0 ? "the 35 dB target is met" : "short of the 35 dB target")
       << ".\n";
  }
  return md.str();
}

}  // namespace

std::string convergenceMarkdown(const ConvergenceResults& r, const std::string& figure) {
  std::vector<int> ladder, poses;
  for (const ConvergencePoint& p : r.ladder) {
    if (std::find(ladder.begin(), ladder.end(), p.spp) == ladder.end()) ladder.push_back(p.spp);
    if (std::find(poses.begin(), poses.end(), p.pose) == poses.end()) poses.push_back(p.pose);
  }
  std::string poseList;
  for (size_t k = 0; k < poses.size(); ++k)
    poseList += (k == 0 ? "" : k + 1 == poses.size() ? " and " : ", ") + std::to_string(poses[k]);
  std::ostringstream md;
  md << "## Are the realistic frames converged?\n\n"
     << "Measured by `omnicam experiment realistic-convergence -o DIR"
     << (r.quick ? " --quick" : "") << "` (experiments/realistic_convergence.h; "
     << fixedDecimals(r.seconds / 60.0, 0) << " min): Blender renders of the textured hall at " << r.size << "×" << r.size
     << " px for pose" << (poses.size() == 1 ? " " : "s ") << poseList << " of thesis-loop, against a converged reference of " << r.referenceSpp
     << " spp per setup (" << (r.referenceSpp > 1024 ? "independent 1024-spp renders averaged; " : "")
     << "a filtered setup's is the unfiltered one), compared as 8-bit sRGB inside the mirror disc. "
     << "Outliers: pixels further from their 3×3 median than the reference's pixel is from its own, by more than "
     << kOutlierLevels << " levels (speckle; edges the reference shares do not count).\n\n";
  for (size_t k = 0; k < r.setups.size(); ++k) md << "- `" << r.setups[k] << "`: " << r.setupDescriptions[k] << ".\n";
  md << "\nPSNR in dB (mean over the poses, worst in brackets) and outliers in %:\n\n| spp |";
  for (const std::string& s : r.setups) md << ' ' << s << " PSNR | " << s << " outliers |";
  md << "\n|---:|";
  for (size_t k = 0; k < r.setups.size(); ++k) md << "---:|---:|";
  md << '\n';
  for (int spp : ladder) {
    md << "| " << spp << " |";
    for (const std::string& s : r.setups) {
      const RungSummary sum = summarise(r, s, spp);
      md << ' ' << fixedDecimals(sum.meanPsnr, 1) << " (" << fixedDecimals(sum.minPsnr, 1) << ") | " << fixedDecimals(100.0 * sum.outliers, 2) << " |";
    }
    md << '\n';
  }
  if (!figure.empty()) md << "\n![PSNR against the converged reference per spp](" << figure << ")\n";
  md << "\nWhich paths carry the noise: the PSNR of two renders that differ only in their seed, at the same spp ("
     << "the PSNR of either against a converged frame is 3.0 dB higher), mean over the poses:\n\n"
     << "| variant | seed pair PSNR dB | implied PSNR vs converged dB | outliers % |\n|---|---:|---:|---:|\n";
  for (const PathVariant& v : r.paths)
    md << "| " << v.description << " | " << fixedDecimals(v.pairPsnrDb, 1) << " | " << fixedDecimals(v.estimatedPsnrDb, 1) << " | "
       << fixedDecimals(100.0 * v.outlierShare, 2) << " |\n";
  const PathVariant* all = findVariant(r, "before");
  const PathVariant* direct = findVariant(r, "before_direct");
  const PathVariant* glossy = findVariant(r, "before_glossy");
  const PathVariant* hidden = findVariant(r, "before_mirror_hidden");
  const PathVariant* physical = findVariant(r, "physical");
  const PathVariant* clampedPair = findVariant(r, "physical_clamped");
  if (all && direct && glossy && hidden && physical) {
    md << "\nRead from this table: with point lamps, direct light alone is " << fixedDecimals(direct->pairPsnrDb - all->pairPsnrDb, 1)
       << " dB cleaner than all paths; glossy bounces bring it to " << fixedDecimals(glossy->pairPsnrDb, 1)
       << " dB and diffuse bounces the rest, so the speckle is light that reaches a surface after a bounce. "
       << "Hiding the mirror from bounces changes the pair PSNR by " << fixedDecimals(hidden->pairPsnrDb - all->pairPsnrDb, 2)
       << " dB. Lamps of real size, which light nothing above them, gain "
       << fixedDecimals(physical->pairPsnrDb - all->pairPsnrDb, 1) << " dB at the same spp.\n";
  }
  md << "\nClamping: Cycles counts everything seen in the mirror as indirect light, so clamping indirect samples at "
     << fixedDecimals(r.clampIndirect, 1) << " clamps the directly lit field too: its converged frames differ from unclamped "
     << "ones by " << fixedDecimals(r.clampBiasPsnrDb, 1) << " dB, mean luminance " << (r.clampBiasLuminancePercent >= 0 ? "+" : "")
     << fixedDecimals(r.clampBiasLuminancePercent, 1) << " %";
  if (clampedPair && physical)
    md << ", for " << fixedDecimals(clampedPair->pairPsnrDb - physical->pairPsnrDb, 1) << " dB less noise at the same spp";
  md << ". The realistic frames are not clamped.\n";
  md << filterMarkdown(r);
  return md.str();
}

}  // namespace omnicam
