// The calibration study's Markdown: docs/calibration-study.md is this text.
#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdio>
#include <functional>
#include <sstream>

#include "calibration_study.h"
#include "number_format.h"
#include "statistics.h"

namespace omnicam {

namespace {

constexpr double kGoodRmsPx = 0.3, kBadHeldOutPx = 1.0, kHeadlineDistanceM = 0.5;

// A rig's calibrations from one source: medians over the seeds that converged (a few seeds'
// detections can throw one calibration far off; the worst is shown beside).
struct SourceSummary {
  int runs = 0, failed = 0, diverged = 0;
  int partial = 0;  // converged, but its model has no ray for some imaged pixels (at the headline distance)
  double rms = 0.0, xi = 0.0, gammaX = 0.0, gammaY = 0.0, cx = 0.0, cy = 0.0;
  std::vector<double> heldOutPx, heldOutMrad;
  double worstHeldOutPx = 0.0;  // at the headline distance
  double triangulationMm = 0.0, triangulationP90Mm = 0.0;
};

double median(std::vector<double> v) { return medianOf(std::move(v)).value_or(0.0); }

SourceSummary summarise(const RigOutcome& rig, CornerSource source, const CalibrationStudyOptions& o) {
  SourceSummary s;
  const size_t distances = o.heldOutDistancesM.size();
  std::vector<std::vector<double>> columns(6 + 2 * distances + 2);
  for (const CalibrationRun& run : rig.runs) {
    if (run.source != source) continue;
    ++s.runs;
    if (!run.fit.converged) {
      ++s.failed;
      s.diverged += run.diverged;
      continue;
    }
    for (const HeldOutError& h : run.heldOut)
      if (h.distanceM == kHeadlineDistanceM && h.unmodelledShare > 0.0) ++s.partial;
    const double values[] = {run.fit.rms, run.fit.xi, run.fit.gammaX, run.fit.gammaY, run.fit.cx, run.fit.cy};
    for (size_t k = 0; k < 6; ++k) columns[k].push_back(values[k]);
    for (size_t d = 0; d < distances && d < run.heldOut.size(); ++d) {
      columns[6 + d].push_back(run.heldOut[d].rmsPx);
      columns[6 + distances + d].push_back(run.heldOut[d].rmsMrad);
    }
    columns[6 + 2 * distances].push_back(run.triangulation.medianMm);
    columns[7 + 2 * distances].push_back(run.triangulation.p90Mm);
  }
  if (s.failed == s.runs) return s;
  double* scalars[] = {&s.rms, &s.xi, &s.gammaX, &s.gammaY, &s.cx, &s.cy};
  for (size_t k = 0; k < 6; ++k) *scalars[k] = median(columns[k]);
  for (size_t d = 0; d < distances; ++d) {
    s.heldOutPx.push_back(median(columns[6 + d]));
    s.heldOutMrad.push_back(median(columns[6 + distances + d]));
  }
  for (size_t d = 0; d < distances; ++d)
    if (o.heldOutDistancesM[d] == kHeadlineDistanceM)
      s.worstHeldOutPx = *std::max_element(columns[6 + d].begin(), columns[6 + d].end());
  s.triangulationMm = median(columns[6 + 2 * distances]);
  s.triangulationP90Mm = median(columns[7 + 2 * distances]);
  return s;
}

size_t distanceIndex(const CalibrationStudyOptions& o, double distance) {
  for (size_t d = 0; d < o.heldOutDistancesM.size(); ++d)
    if (o.heldOutDistancesM[d] == distance) return d;
  return 0;
}


void sweepTable(std::ostringstream& md, const CalibrationStudyResults& r, const CalibrationStudyOptions& o, bool lens) {
  std::string distances;
  for (double d : o.heldOutDistancesM) distances += (distances.empty() ? "" : " / ") + fixedDecimals(d, d < 1 ? 1 : 0) + " m";
  md << "| rig | corners from | RMS px | held-out RMS px at " << distances << " | mrad at 0.5 m | triangulation at "
     << fixedDecimals(o.triangulationDistanceM, 0) << " m, mm (median / 90 %) | worst seed at 0.5 m, px | failed: initialisation / diverged; partial models |\n"
     << "|---|---|---:|---:|---:|---:|---:|---:|\n";
  const size_t half = distanceIndex(o, kHeadlineDistanceM);
  for (const RigOutcome& rig : r.rigs) {
    if (rig.misalignment.distorted != lens) continue;
    md << "| " << rig.misalignment.label() << " | best central model | — | ";
    for (size_t d = 0; d < rig.bestFitHeldOut.size(); ++d) md << (d ? " / " : "") << fixedDecimals(rig.bestFitHeldOut[d].rmsPx, 2);
    md << " | " << fixedDecimals(rig.bestFitHeldOut[half].rmsMrad, 2) << " | — | — | — |\n";
    for (CornerSource source : {CornerSource::Exact, CornerSource::Detected, CornerSource::DetectedNoisy}) {
      const SourceSummary s = summarise(rig, source, o);
      md << "| | " << cornerSourceTitle(source) << " | ";
      if (s.failed == s.runs) {
        md << "— | — | — | — | — | " << s.failed - s.diverged << " / " << s.diverged << " of " << s.runs << "; 0 |\n";
        continue;
      }
      md << fixedDecimals(s.rms, 3) << " | ";
      for (size_t d = 0; d < s.heldOutPx.size(); ++d) md << (d ? " / " : "") << fixedDecimals(s.heldOutPx[d], 2);
      md << " | " << fixedDecimals(s.heldOutMrad[half], 2) << " | " << fixedDecimals(s.triangulationMm, 1) << " / " << fixedDecimals(s.triangulationP90Mm, 1)
         << " | " << fixedDecimals(s.worstHeldOutPx, 2) << " | " << s.failed - s.diverged << " / " << s.diverged << " of " << s.runs << "; "
         << s.partial << " |\n";
    }
  }
}

// Where, along one kind of misalignment (no lens), a median over seeds first reaches
// `threshold`: linearly interpolated between the swept amounts (the ideal rig at 0); nullopt when
// it never does.
std::optional<double> crossing(const CalibrationStudyResults& r, const CalibrationStudyOptions& o, const std::string& kind,
                               CornerSource source, const std::function<double(const SourceSummary&)>& metric,
                               double threshold) {
  std::vector<std::pair<double, double>> curve;
  for (const RigOutcome& rig : r.rigs) {
    if (rig.misalignment.distorted || (rig.misalignment.kind != kind && rig.misalignment.kind != "ideal")) continue;
    const SourceSummary s = summarise(rig, source, o);
    if (s.failed < s.runs) curve.emplace_back(rig.misalignment.amount, metric(s));
  }
  std::sort(curve.begin(), curve.end());
  for (size_t k = 0; k < curve.size(); ++k) {
    if (curve[k].second < threshold) continue;
    if (k == 0) return curve[0].first;
    const auto& [a0, v0] = curve[k - 1];
    const auto& [a1, v1] = curve[k];
    return a0 + (threshold - v0) / (v1 - v0) * (a1 - a0);
  }
  return std::nullopt;
}

// "the training RMS reaches 0.3 px at ≈ 1.86 mm", or that it stays below it through the sweep.
std::string reaches(const std::string& what, const std::string& threshold, const std::optional<double>& amount, const std::string& unit) {
  return amount ? what + " reaches " + threshold + " at ≈ " + fixedDecimals(*amount, 2) + " " + unit
                : what + " stays below " + threshold + " through the sweep";
}

// The headline: where the model alone (exact corners) starts to err on held-out points while
// its RMS still looks fine, and how often detected corners do the same.
std::string headline(const CalibrationStudyResults& r, const CalibrationStudyOptions& o) {
  std::ostringstream md;
  const size_t half = distanceIndex(o, kHeadlineDistanceM), near = distanceIndex(o, 0.2);
  const auto rms = [](const SourceSummary& s) { return s.rms; };
  const auto atHalf = [&](const SourceSummary& s) { return s.heldOutPx[half]; };
  const auto atNear = [&](const SourceSummary& s) { return s.heldOutPx[near]; };
  for (const char* kind : {"lateral", "axial", "tilt"}) {
    if (std::none_of(r.rigs.begin(), r.rigs.end(), [&](const RigOutcome& rig) { return rig.misalignment.kind == kind; })) continue;
    const std::string unit = std::string(kind) == "tilt" ? "deg" : "mm";
    const std::optional<double> good = crossing(r, o, kind, CornerSource::Exact, rms, kGoodRmsPx);
    const std::optional<double> bad = crossing(r, o, kind, CornerSource::Exact, atHalf, kBadHeldOutPx);
    const std::optional<double> badNear = crossing(r, o, kind, CornerSource::Exact, atNear, kBadHeldOutPx);
    md << "- **" << kind << "** (model error alone, exact corners): "
       << reaches("the training RMS", fixedDecimals(kGoodRmsPx, 1) + " px", good, unit) << "; "
       << reaches("the held-out error at 0.5 m", fixedDecimals(kBadHeldOutPx, 0) + " px", bad, unit) << " ("
       << reaches("at 0.2 m it", fixedDecimals(kBadHeldOutPx, 0) + " px", badNear, unit) << ")";
    if (bad && (!good || *bad < *good))
      md << ". **From " << fixedDecimals(*bad, 2) << " " << unit << (good ? " to " + fixedDecimals(*good, 2) + " " + unit : std::string(" on"))
         << " the calibration looks fine and errs more than a pixel at 0.5 m.**\n";
    else if (bad)
      md << ": the training RMS flags it first.\n";
    else
      md << ": the central model absorbs it.\n";
  }
  // Detected corners: calibrations that look fine and are not, on every rig of the sweep (no lens).
  for (CornerSource source : {CornerSource::Detected, CornerSource::DetectedNoisy}) {
    int fine = 0, fineButOff = 0, fineButOffCentral = 0;
    for (const RigOutcome& rig : r.rigs) {
      if (rig.misalignment.distorted) continue;
      const SourceSummary exact = summarise(rig, CornerSource::Exact, o);
      const bool central = exact.failed < exact.runs && exact.heldOutPx[half] < 0.1;
      for (const CalibrationRun& run : rig.runs) {
        if (run.source != source || !run.fit.converged || !(run.fit.rms < kGoodRmsPx)) continue;
        ++fine;
        if (run.heldOut[half].rmsPx > kBadHeldOutPx) ++fineButOff, fineButOffCentral += central;
      }
    }
    md << "- **" << cornerSourceTitle(source) << "**: " << fineButOff << " of the " << fine << " calibrations with RMS < "
       << fixedDecimals(kGoodRmsPx, 1) << " px err more than " << fixedDecimals(kBadHeldOutPx, 0) << " px at 0.5 m; " << fineButOffCentral
       << " of them on rigs whose exact corners calibrate to < 0.1 px there (the detections' error, extrapolated).\n";
  }
  return md.str();
}

// The ideal rig's closed-form parameters and each corner source's calibration of them.
void idealRigTable(std::ostringstream& md, const CalibrationStudyResults& r, const CalibrationStudyOptions& o) {
  for (const RigOutcome& rig : r.rigs) {
    if (rig.misalignment.kind != "ideal" || rig.misalignment.distorted) continue;
    const MeiIntrinsics& t = rig.truth;
    md << "| closed form | " << fixedDecimals(t.xi, 6) << " | " << fixedDecimals(t.gammaX, 3) << " | " << fixedDecimals(t.gammaY, 3) << " | "
       << fixedDecimals(t.cx, 3) << " | " << fixedDecimals(t.cy, 3) << " | — |\n";
    for (CornerSource source : {CornerSource::Exact, CornerSource::Detected, CornerSource::DetectedNoisy}) {
      const SourceSummary s = summarise(rig, source, o);
      if (s.failed == s.runs) continue;
      // The change relative to the closed form: γy < 0 grown in magnitude reads + as γx does.
      const auto rel = [](double v, double truth) { return fixedDecimals(100.0 * (v - truth) / truth, 2) + " %"; };
      md << "| " << cornerSourceTitle(source) << " | " << fixedDecimals(s.xi, 6) << " (" << rel(s.xi, t.xi) << ") | " << fixedDecimals(s.gammaX, 3) << " ("
         << rel(s.gammaX, t.gammaX) << ") | " << fixedDecimals(s.gammaY, 3) << " (" << rel(s.gammaY, t.gammaY) << ") | " << fixedDecimals(s.cx, 3)
         << " | " << fixedDecimals(s.cy, 3) << " | " << fixedDecimals(s.rms, 3) << " |\n";
    }
  }
}

// The best central model's parameters beside the calibrations' medians, rig by rig (no lens).
void centralModelTable(std::ostringstream& md, const CalibrationStudyResults& r, const CalibrationStudyOptions& o) {
  for (const RigOutcome& rig : r.rigs) {
    if (rig.misalignment.distorted) continue;
    const SourceSummary exact = summarise(rig, CornerSource::Exact, o), noisy = summarise(rig, CornerSource::DetectedNoisy, o);
    const auto cell = [&](double best, double e, double n, int decimals) {
      return fixedDecimals(best, decimals) + " / " + (exact.failed < exact.runs ? fixedDecimals(e, decimals) : "—") + " / " +
             (noisy.failed < noisy.runs ? fixedDecimals(n, decimals) : "—");
    };
    const MeiIntrinsics& t = rig.truth;
    md << "| " << rig.misalignment.label() << " | " << cell(t.xi, exact.xi, noisy.xi, 4) << " | "
       << cell(t.gammaX, exact.gammaX, noisy.gammaX, 2) << " | " << cell(t.cx, exact.cx, noisy.cx, 2) << " | "
       << cell(t.cy, exact.cy, noisy.cy, 2) << " |\n";
  }
}

// The EKF's mean position error along thesis-loop through each model of each rig's camera.
void localisationTable(std::ostringstream& md, const CalibrationStudyResults& r) {
  for (const RigOutcome& rig : r.rigs) {
    const EkfComparison& e = rig.ekf;
    const auto cm = [](double v) { return std::isnan(v) ? std::string("— (no calibration)") : fixedDecimals(v, 1); };
    md << "| " << rig.misalignment.label() << " | " << fixedDecimals(e.odometryCm, 1) << " | " << fixedDecimals(e.trueRaysCm, 1) << " | "
       << fixedDecimals(e.nominalCm, 1) << " (" << fixedDecimals(100.0 * e.nominalUsedShare, 0) << " %) | " << cm(e.calibratedExactCm) << " | " << cm(e.calibratedCm) << " |\n";
  }
}

}  // namespace

std::string calibrationStudyMarkdown(const CalibrationStudyResults& r, const CalibrationStudyOptions& o, const std::string& command,
                                     bool figures) {
  // A figure, or where it would be: a run without figures links to nothing it did not write.
  const auto figure = [figures](const char* alt, const char* file) {
    return figures ? std::string("![") + alt + "](figures/" + file + ")\n\n"
                   : std::string("(") + alt + ": not drawn in this run)\n\n";
  };
  std::ostringstream md;
  md << "# The calibration study: what misalignment does to a calibrated omnicam\n\n"
     << "Generated by `" << command << "` (" << fixedDecimals(r.seconds / 60.0, 1) << " min on this machine); do not edit by hand.\n\n"
     << "A user calibrates the robot's omnicam as the tools teach: a Kalibr AprilGrid (6 × 6 tags of 88 mm) waved at " << o.views
     << " seeded poses 0.3–1.0 m from the camera, its corners found by AprilTag, `cv::omnidir::calibrate` (Mei's unified model with "
        "radial-tangential distortion, skew fixed) on them. omnicam repeats that on rigs whose camera is misaligned behind the "
        "mirror, with "
     << o.seeds << " seed" << (o.seeds > 1 ? "s" : "") << " each, from three sources of corners: the exact ones (the model's error "
     << "alone), those AprilTag detects in clean " << o.size << "-px renders, and in the recording camera's noisy frames (`RecordingCamera::webcam`: "
        "shot and read noise, vignetting, JPEG). Each calibrated model, placed by its own extrinsics, is then measured where no "
        "board was — every pixel of the image: the reprojection error of points on the true rays at each distance, the angle "
        "between its ray and the true one (mrad), and the error of points at "
     << fixedDecimals(o.triangulationDistanceM, 0) << " m triangulated after the robot drove " << fixedDecimals(o.triangulationBaselineM, 2)
     << " m. `best central model` is the best any central calibration can do (`camera/central_fit.h`: fitted to every ray); for "
        "the ideal rig it is the closed form. Numbers are medians over the seeds that converged (a seed's detections can "
        "throw its calibration far off: the worst seed's held-out error is shown beside).\n\n";
  md << "## Headline\n\nWhere a calibration looks fine (training RMS < " << fixedDecimals(kGoodRmsPx, 1) << " px) while it errs by more than "
     << fixedDecimals(kBadHeldOutPx, 0) << " px on held-out points 0.5 m away (amounts interpolated between the swept ones, medians over "
     << "seeds, no lens):\n\n"
     << (o.reduced ? "*A quick run (`--quick`: one offset each way, one seed): the amounts are interpolated between too few "
                     "rigs to be the study's; docs/calibration-study.md holds the full run's.*\n\n"
                   : "")
     << headline(r, o) << "\n";
  md << "## The ideal rig: recovered against the closed form\n\n| corners from | ξ | γx | γy | cx | cy | RMS px |\n|---|---:|---:|---:|---:|---:|---:|\n";
  idealRigTable(md, r, o);
  md << "\nWith its distortion estimated, OpenCV trades ξ against γ and k1 (they are strongly correlated over a partial view of the "
        "mirror): the RMS stays at the corners' noise while the parameters move; the held-out errors below show what that "
        "costs away from the boards.\n\n";
  md << "## Parameters against the best central model\n\nFor the misaligned rigs the truth a central calibration can "
        "reach is the best-fit central model; the calibrations' medians (exact corners / recorded detections) beside it:\n\n"
     << "| rig | ξ: best / exact / recorded | γx: best / exact / recorded | cx: best / exact / recorded | cy: best / exact / recorded |\n"
     << "|---|---:|---:|---:|---:|\n";
  centralModelTable(md, r, o);
  md << "\n";
  md << "## The sweep\n\n" << figure("held-out error against misalignment", "calibration_study_error.svg")
     << "*corners from*: the exact corners; corners detected in clean renders; or detected in recorded frames (through the recording camera: noise, JPEG; their residual files are named `_detected_noisy`). *failed*, of the seeds run: calibrations OpenCV could not start (initialisation: no first guess from the views) / that did not converge (diverged); *partial models*: converged, but the model has no ray for some pixels the camera images (at 0.5 m).\n\n"
     << "### Without lens distortion\n\n";
  sweepTable(md, r, o, false);
  if (o.distortedLens) {
    md << "\n### With a typical lens (k1 " << o.typicalLens.k1 << ", k2 " << o.typicalLens.k2 << ", p1 " << o.typicalLens.p1
       << ", p2 " << o.typicalLens.p2 << ")\n\n";
    sweepTable(md, r, o, true);
  }
  md << "\n## Where the error is\n\nReprojection error of held-out points 0.5 m away over the image (seed 1; exact corners and "
        "recorded detections):\n\n"
     << figure("residual maps", "calibration_study_residuals.png");
  md << "## What it does to the thesis' self-localisation\n\nThe thesis' EKF (`experiments/ekf_drive.h`) along `thesis-loop` on "
        "the RoboCup field with the same noisy odometry, every beacon the rig images measured (range and bearing of its "
        "centre) through a model of the camera: its true rays, the nominal ideal rig's (what the thesis assumed), or seed 1's "
        "calibrations. Mean position error (cm); a model whose measurements fail the EKF's validation gate "
        "leaves the robot to its odometry:\n\n"
     << "| rig | odometry alone | true rays | nominal model (measurements the gate let in) | calibrated, exact corners | "
        "calibrated, recorded detections |\n"
     << "|---|---:|---:|---:|---:|---:|\n";
  localisationTable(md, r);
  md << "\n`results.json` in the run's folder holds every calibration (parameters, per-distance median/RMS/max, triangulation, "
        "failures).\n";
  return md.str();
}

}  // namespace omnicam
