#pragma once
// The thesis' mirror polygon-count study (thesis §3.1.2, Figs. 3.4–3.5), measured: exact mode, the
// cube map (6 and 5 faces) and the thesis mesh at 16–1024 polygons against exact mode (PSNR,
// SSIM), against the exact model (incidence rings) and in frames/s. `omnicam study` writes its
// Markdown report, with its figures in figures/ beside it.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace omnicam {

struct PolygonStudyOptions {
  std::string arenaScene;      // scenes/robocup2006.json: quality and speed at its start pose
  std::string ringScene;       // scenes/incidence-rings.json: the rings against the exact model
  std::string report;          // FILE.md; its figures go to figures/FILE_* beside it
  int spp = 16;                // samples per pixel for the quality columns
  double timingSeconds = 1.0;  // timed per mode
  std::string command;         // the command that writes the report again, shown in it
};

// Every file a run writes: the report and its figures (to check before the work that they can be).
std::vector<std::string> polygonStudyFiles(const std::string& report);

// Measures every mode (`onMode` is told each one's label as it starts) and writes the figures and
// the report. The report's folder and figures/ beside it must exist.
void runPolygonStudy(const PolygonStudyOptions& options, const std::function<void(const std::string&)>& onMode);

}  // namespace omnicam
