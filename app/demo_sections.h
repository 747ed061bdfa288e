#pragma once
// The demo as sections, each rendered by a child `omnicam demo --section NAME` with a time budget
// scaled to what it renders. A section that fails or runs out of time is ended (its renderers
// with it), marked in the report with the reason and the command that reproduces it, and the
// report is still written; the exit code's bits say which sections fell short.
#include <functional>
#include <string>
#include <vector>

namespace omnicam::cli {

struct DemoSection {
  std::string name;   // for --section
  std::string title;  // as the report shows it
  // What it costs on an idle 2-core machine at 16 spp (measured), by engine; the budget scales it.
  double fastSeconds = 0, povraySeconds = 0, blenderSeconds = 0;
  bool scalesWithSpp = true;  // false: its renders use their own sample counts
};

struct DemoBudgetInputs {
  int spp = 16;
  bool povray = true, blender = true;
  double scale = 1.0;  // --budget-scale
};

// Seconds a section may take: a fixed allowance for start-up plus a margin over its measured cost
// (a machine half as fast, both cores busy with other work), times `scale`.
double sectionBudgetSeconds(const DemoSection& section, const DemoBudgetInputs& inputs);

// NotRun: left out by --sections (neither shown nor counted as short).
enum class SectionOutcome { Done, Failed, TimedOut, NotRun };

struct SectionRun {
  SectionOutcome outcome = SectionOutcome::Failed;
  double seconds = 0, budgetSeconds = 0;
  std::string reason;     // one line, for a section that fell short
  std::string logTail;    // its last output lines
  std::string command;    // reproduces the section alone
  std::string html;       // the section's report fragment, when done
};

// Runs `argv` (the child verb) for the section with its budget, its output echoed and logged to
// `<sectionsDir>/<name>.log`; the child writes `<sectionsDir>/<name>.html`.
SectionRun runDemoSection(const DemoSection& section, const std::vector<std::string>& argv, const std::string& sectionsDir,
                          double budgetSeconds);

// The exit code of a demo whose `runs` (in `sections` order, one bit per section from bit 0): 0
// when every section run is done, else 64 + the bits of those that fell short (65 to 127; 126 and
// 127, which shells also use, mean all sections but the glance, or all, fell short).
int demoExitCode(const std::vector<SectionRun>& runs);

// True for a section that was run and did not finish.
bool fellShort(const SectionRun& run);

// HTML for a section that fell short: its title, why, its last output and the command.
std::string shortSectionHtml(const DemoSection& section, const SectionRun& run);

}  // namespace omnicam::cli
