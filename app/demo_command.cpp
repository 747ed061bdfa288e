// omnicam demo [-o out/demo] [--spp N] [--no-povray] [--no-blender]: the main job. Opens with a
// frame that fills the mirror (the field inside the thesis' hall, walls carrying a real photo) from
// the fast renderer beside POV-Ray's ground truth and their agreement; then renders robocup2006 at
// the thesis start pose (unlit and lit) with the fast renderer, POV-Ray (the physical camera and
// the exact mirror) and Blender, compares them, renders and measures the incidence-angle rings
// with every engine, shows a misaligned physical camera against the ideal one (with POV-Ray's
// truth and the best-fit central model's residual), shows physically based light (the fast path
// tracer's dataset frame beside Cycles' converged frame of the textured hall), renders a small
// two-camera dataset (depth, instance and landmark overlays), and writes PNGs, plots and index.html.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "atomic_file.h"
#include "cli_util.h"
#include "errors.h"
#include "commands.h"
#include "demo_dataset.h"
#include "demo_figures.h"
#include "demo_glance.h"
#include "demo_lenses.h"
#include "demo_light.h"
#include "demo_motion.h"
#include "demo_physical.h"
#include "demo_sections.h"
#include "demo_start_pose.h"
#include "demo_texture_realism.h"
#include "markup.h"
#include "scene_loader.h"
#include "safe_files.h"

namespace omnicam::cli {

namespace {

struct DemoArgs {
  std::string out = "out/demo";
  int spp = 16;
  bool povray = true, blender = true;
  double budgetScale = 1.0;
  std::vector<std::string> only;  // --sections: run these, leave the others out
  std::string section;  // a child renders this one section (demo_sections.h)
};

// The sections in report order; a section's bit in the exit code is its place here. Costs are
// what each renders on an idle 2-core machine at 16 spp, by engine (measured 2026-11-28 with
// `omnicam demo`, `--no-blender` and `--no-povray --no-blender`; the whole demo took 54 s).
const std::vector<DemoSection>& demoSections() {
  static const std::vector<DemoSection> sections = {
      {"glance", "At a glance", 1.5, 2.0, 0.0, true},
      {"start-pose", "The thesis camera at its start pose: renders, rings, the thesis' method, views", 3.0, 8.5, 11.5, true},
      {"light", "Light: physically based at the fast renderer's speed", 2.0, 0.0, 15.0, false},
      {"physical", "The physical camera", 1.0, 1.6, 0.0, true},
      {"lenses", "Lens cameras", 2.0, 2.3, 2.2, true},
      {"robot", "Time in the camera, a reference dataset, texture realism", 2.0, 0.0, 0.0, true},
  };
  return sections;
}

// The start-pose section runs first: the glance cites its rings.
const std::vector<std::string> kRunOrder = {"start-pose", "glance", "light", "physical", "lenses", "robot"};

// What a child `omnicam demo --section NAME` renders; returns the section's HTML. Run alone (to
// reproduce it), a section writes the shared hall itself.
std::string sectionHtml(const DemoArgs& a) {
  const std::string dir = scenesDir();
  const bool needsHall = a.section == "glance" || a.section == "light" || a.section == "robot";
  if (needsHall && !std::filesystem::exists(std::filesystem::symlink_status(hallScenePath(a.out))))
    writeDemoHall(a.out, dir + "/robocup2006.json");
  if (a.section == "start-pose") return demoStartPose(a.out, a.spp, a.povray, a.blender);
  if (a.section == "glance") return demoGlance(a.out, a.spp, a.povray, readRingSummary(a.out));
  if (a.section == "light") return demoLight(a.out, hallScenePath(a.out), a.blender);
  const Scene arena = loadScene(dir + "/robocup2006.json");
  if (a.section == "physical") return demoPhysicalCamera(a.out, arena, a.spp, a.povray);
  if (a.section == "lenses") return demoLenses(a.out, arena, a.spp, a.povray, a.blender);
  if (a.section == "robot") {  // one after the other, as the progress lines say
    const std::string motion = demoMotion(a.out, arena, a.spp);
    const std::string dataset = demoDataset(a.out, dir + "/robocup2006.json");
    return motion + dataset + demoTexturedHall(a.out, dir + "/robocup2006.json");
  }
  throw std::logic_error("unknown demo section " + a.section);  // checked by checkSectionNames
}

// Refuses names that are not sections, before anything is written.
void checkSectionNames(const std::vector<std::string>& names, const std::string& flag) {
  std::string known;
  for (const DemoSection& s : demoSections()) known += (known.empty() ? "" : ", ") + s.name;
  for (const std::string& name : names)
    if (std::none_of(demoSections().begin(), demoSections().end(), [&](const DemoSection& s) { return s.name == name; }))
      throw InputError(flag + ": unknown section " + quote(name) + " (the sections are " + known + ")");
}

// The demo's own folders, made without following a link planted under their names: what the
// sections write and remove stays inside the demo's folder.
void makeDemoFolders(const std::string& out) { makeAllFoldersInside(out, {"sections", "hall"}); }

void renderOneSection(const DemoArgs& a) {
  // Line by line into the section's log: a section ended on its budget keeps what it said.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  makeDemoFolders(a.out);
  const std::string html = sectionHtml(a);
  writeTextAtomically(a.out + "/sections/" + a.section + ".fragment", html);
}

std::vector<std::string> sectionCommand(const DemoArgs& a, const std::string& section) {
  std::vector<std::string> argv{std::filesystem::read_symlink("/proc/self/exe").string(), "demo", "--section", section,
                                "-o", std::filesystem::absolute(a.out).string(), "--spp", std::to_string(a.spp)};
  if (!a.povray) argv.push_back("--no-povray");
  if (!a.blender) argv.push_back("--no-blender");
  return argv;
}

const char* kReportHead = R"(<!doctype html><html><head><meta charset="utf-8"><title>omnicam demo</title>
<style>body{font-family:sans-serif;max-width:1150px;margin:2em auto;color:#222}
figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top;max-width:380px}figcaption{font-size:90%;color:#555}
img{image-rendering:pixelated;background:#444}table{border-collapse:collapse;font-size:85%}
td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}
.short{border-left:6px solid #d62728;background:#fdf0f0;padding:0.3em 1em}pre{white-space:pre-wrap;font-size:80%}</style></head><body>
<h1>omnicam demo</h1>
)";

// The sections' table at the end: what each took against its budget.
std::string sectionsTable(const std::vector<SectionRun>& runs) {
  std::ostringstream html;
  html << "<h3>How this report was made</h3><p>Each section ran as its own <code>omnicam demo --section</code> "
          "with a time budget scaled to what it renders (<code>--budget-scale</code> stretches them); a section that "
          "fails or runs out of time is ended with its renderers and marked, and the others are kept.</p><table>"
          "<tr><th>section</th><th>outcome</th><th>seconds</th><th>budget (s)</th></tr>\n";
  for (size_t k = 0; k < runs.size(); ++k)
    html << "<tr><td>" << demoSections()[k].name << "</td><td>"
         << (runs[k].outcome == SectionOutcome::Done ? "done" : escapeMarkup(runs[k].reason)) << "</td>"
         << formatNumbers("<td>%.1f</td><td>%.3g</td></tr>\n", runs[k].seconds, runs[k].budgetSeconds);
  html << "</table>\n";
  return html.str();
}

int runDemo(const DemoArgs& a) {
  namespace fs = std::filesystem;
  checkSpp(a.spp, "--spp");  // before any folder is made
  if (!a.section.empty()) checkSectionNames({a.section}, "--section");
  checkSectionNames(a.only, "--sections");
  ensureDirectory(a.out, "-o");
  if (!a.section.empty()) {
    renderOneSection(a);
    return 0;
  }
  makeDemoFolders(a.out);
  try {
    writeDemoHall(a.out, scenesDir() + "/robocup2006.json");
  } catch (const std::exception& e) {  // the sections that need the hall fail, are marked, and say why
    std::printf("demo: the textured hall could not be written: %s\n", oneLine(e.what()).c_str());
  }
  const DemoBudgetInputs budget{a.spp, a.povray, a.blender, a.budgetScale};
  const std::vector<DemoSection>& sections = demoSections();
  std::vector<SectionRun> runs(sections.size());
  const auto chosen = [&](const std::string& name) { return a.only.empty() || std::find(a.only.begin(), a.only.end(), name) != a.only.end(); };
  const size_t toRun = static_cast<size_t>(std::count_if(kRunOrder.begin(), kRunOrder.end(), [&](const auto& name) { return chosen(name); }));
  size_t started = 0;  // the progress lines count the sections that run (--sections)
  for (size_t n = 0; n < kRunOrder.size(); ++n) {
    const size_t k = static_cast<size_t>(
        std::find_if(sections.begin(), sections.end(), [&](const DemoSection& s) { return s.name == kRunOrder[n]; }) -
        sections.begin());
    if (!chosen(sections[k].name)) {
      runs[k].outcome = SectionOutcome::NotRun;
      runs[k].reason = "not run (--sections)";
      continue;
    }
    const double seconds = sectionBudgetSeconds(sections[k], budget);
    std::printf("demo: section %zu/%zu, %s (budget %.3g s)\n", ++started, toRun, sections[k].name.c_str(), seconds);
    std::fflush(stdout);
    runs[k] = runDemoSection(sections[k], sectionCommand(a, sections[k].name),
                             (fs::absolute(a.out) / "sections").string(), seconds);
    if (runs[k].outcome == SectionOutcome::Done)
      std::printf("demo: section %s done in %.1f s\n", sections[k].name.c_str(), runs[k].seconds);
    else
      std::printf("demo: section %s fell short: it %s; reproduce with: %s\n", sections[k].name.c_str(),
                  runs[k].reason.c_str(), runs[k].command.c_str());
  }
  std::ostringstream html;
  html << kReportHead;
  std::string shortfalls;
  for (size_t k = 0; k < runs.size(); ++k)
    if (fellShort(runs[k]))
      shortfalls += (shortfalls.empty() ? "" : ", ") + escapeMarkup(sections[k].name) + " (" + escapeMarkup(runs[k].reason) + ")";
  if (!shortfalls.empty())
    html << "<p class=\"short\"><b>Sections that fell short:</b> " << shortfalls
         << ". They are marked below; the rest of the report is complete.</p>\n";
  for (size_t k = 0; k < runs.size(); ++k)
    if (runs[k].outcome != SectionOutcome::NotRun)
      html << (runs[k].outcome == SectionOutcome::Done ? runs[k].html : shortSectionHtml(sections[k], runs[k]));
  html << R"(
<p>Every image has a sidecar (<code>*.png.json</code>): engine and version, scene SHA-256, pose, rig, spp, seconds,
and OpenCV <code>cv::omnidir</code> intrinsics.</p>
)" << sectionsTable(runs)
       << "</body></html>\n";
  writeTextAtomically(a.out + "/index.html", html.str());
  const int code = demoExitCode(runs);
  if (code != 0) std::printf("demo: sections that fell short: %s (exit %d)\n", shortfalls.c_str(), code);
  std::printf("demo: open %s\n", (fs::absolute(a.out) / "index.html").string().c_str());
  return code;
}

}  // namespace

void addDemoCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* cmd = app.add_subcommand("demo", "Main job: fast vs POV-Ray renders and rings, the physical and lens cameras "
                                             "(mirror, fisheye, panorama), with an HTML report. Exit 0, or 64 + one bit "
                                             "per section that fell short (docs/conventions.md)");
  cmd->add_option("-o,--output", args->out, "Report folder (default out/demo)");
  addSppOption(*cmd, args->spp, "Samples per pixel, n*n (default 16)");
  cmd->add_flag_callback("--no-povray", [args] { args->povray = false; }, "Skip the POV-Ray ground truth");
  cmd->add_flag_callback("--no-blender", [args] { args->blender = false; }, "Skip the Blender ground truth");
  cmd->add_option("--budget-scale", args->budgetScale,
                  "Multiply every section's time budget (default 1; a slow or busy machine: 2 or more)")
      ->check(numberIn(0, 1000, true));
  cmd->add_option("--sections", args->only, "Run only these sections (comma-separated: glance, start-pose, light, "
                  "physical, lenses, robot); the report lists the others as not run")
      ->delimiter(',');
  cmd->add_option("--section", args->section,
                  "Run one section alone, without a time budget, into the report folder: its images and "
                  "sections/NAME.fragment, no index.html (what the demo runs for each; a section that falls short "
                  "says to reproduce it so)");
  cmd->callback([args, cmd, &exitCode] {
    refuseUnless(*cmd, "--sections", args->section.empty(), "the whole demo (not with --section)");
    refuseUnless(*cmd, "--budget-scale", args->section.empty(), "the whole demo (not with --section)");
    exitCode = runDemo(*args);
  });
}

}  // namespace omnicam::cli
