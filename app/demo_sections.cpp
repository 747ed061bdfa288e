#include "demo_sections.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "external_process.h"
#include "markup.h"
#include "safe_files.h"

namespace omnicam::cli {

namespace {

// Start-up of a child omnicam and of the renderers it launches, on any machine.
constexpr double kStartupAllowanceSeconds = 60.0;
// A machine half as fast as the one the costs were measured on, both its cores shared with
// other work, and room beyond that.
constexpr double kCostMargin = 8.0;

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Words that need no quotes keep none, so the command reads as typed.
std::string quoteArgument(const std::string& argument) {
  const bool plain = !argument.empty() && argument.find_first_not_of(
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=,:+") == std::string::npos;
  return plain ? argument : shellQuote(argument);
}

}  // namespace

double sectionBudgetSeconds(const DemoSection& section, const DemoBudgetInputs& inputs) {
  const double samples = section.scalesWithSpp ? std::max(1.0, inputs.spp / 16.0) : 1.0;
  const double cost = section.fastSeconds + (inputs.povray ? section.povraySeconds : 0.0) +
                      (inputs.blender ? section.blenderSeconds : 0.0);
  return inputs.scale * (kStartupAllowanceSeconds + kCostMargin * cost * samples);
}

SectionRun runDemoSection(const DemoSection& section, const std::vector<std::string>& argv, const std::string& sectionsDir,
                          double budgetSeconds) {
  namespace fs = std::filesystem;
  SectionRun run;
  run.budgetSeconds = budgetSeconds;
  run.command = "omnicam";
  for (size_t k = 1; k < argv.size(); ++k) run.command += " " + quoteArgument(argv[k]);
  // A fragment of index.html (its links are relative to the demo folder): not a page to open.
  const std::string html = sectionsDir + "/" + section.name + ".fragment";
  removeFileInside(sectionsDir, section.name + ".fragment");  // an earlier run's: only this run's may be shown
  ProcessOptions options;
  options.timeoutSeconds = budgetSeconds;
  options.echoOutput = true;
  // Longer than a renderer's own grace (external_process.h): a section ended by its budget or an
  // interrupt first ends its renderer, whose process group the section's SIGKILL would not reach.
  options.terminationGraceSeconds = 30.0;
  const auto start = std::chrono::steady_clock::now();
  const ProcessResult result = runProcess(argv, sectionsDir, sectionsDir + "/" + section.name + ".log", options);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.logTail = result.logTail;
  char line[256];
  if (result.timedOut) {
    run.outcome = SectionOutcome::TimedOut;
    std::snprintf(line, sizeof line, "ran out of its budget of %.3g s and was ended", budgetSeconds);
    run.reason = line;
  } else if (result.endedBySignal) {
    std::snprintf(line, sizeof line, "was ended by signal %d", result.endedBySignal);
    run.reason = line;
  } else if (result.exitCode < 0) {
    run.reason = "could not be started (" + result.logTail + ")";
  } else if (result.exitCode != 0) {
    std::snprintf(line, sizeof line, "failed (exit %d)", result.exitCode);
    run.reason = line;
  } else if (!fs::is_regular_file(fs::symlink_status(html))) {
    run.reason = "wrote no report fragment";
  } else {
    run.outcome = SectionOutcome::Done;
    run.html = readText(html);
  }
  return run;
}

bool fellShort(const SectionRun& run) {
  return run.outcome == SectionOutcome::Failed || run.outcome == SectionOutcome::TimedOut;
}

int demoExitCode(const std::vector<SectionRun>& runs) {
  int bits = 0;
  for (size_t k = 0; k < runs.size(); ++k)
    if (fellShort(runs[k])) bits |= 1 << k;
  return bits == 0 ? 0 : 64 + bits;
}

std::string shortSectionHtml(const DemoSection& section, const SectionRun& run) {
  char seconds[96];
  std::snprintf(seconds, sizeof seconds, " after %.1f s (budget %.3g s)", run.seconds, run.budgetSeconds);
  return "<h2>" + escapeMarkup(section.title) + "</h2>\n<div class=\"short\"><p><b>This section fell short:</b> it " +
         escapeMarkup(run.reason) + seconds + ". Reproduce it alone with <code>" + escapeMarkup(run.command) +
         "</code>; its whole output is in <code>sections/" + escapeMarkup(section.name) +
         ".log</code>. Its last lines:</p><pre>" + escapeMarkup(run.logTail) + "</pre></div>\n";
}

}  // namespace omnicam::cli
