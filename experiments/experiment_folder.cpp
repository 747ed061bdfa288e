#include "experiment_folder.h"

#include <algorithm>
#include <filesystem>
#include <set>
#include <utility>
#include <vector>

#include "errors.h"
#include "input_limits.h"
#include "json_text.h"
#include "safe_files.h"

namespace omnicam {

namespace {

// The study a results.json belongs to: its "study", or for texture-realism runs written before
// it carried one, their "conditions".
std::optional<std::string> studyOf(const nlohmann::json& results) {
  if (!results.is_object()) return std::nullopt;
  if (results.contains("study")) {
    if (!results["study"].is_string()) return std::nullopt;
    return results["study"].get<std::string>();
  }
  if (results.contains("conditions")) return "texture-realism";
  return std::nullopt;
}

// A JSON file an experiment wrote into `dir` (its mark, its results.json): nullopt if missing;
// InputError for a link, something not a file, or text that is not JSON.
std::optional<nlohmann::json> experimentFile(const std::string& dir, const std::string& name) {
  const EntryKind kind = entryInside(dir, name);
  if (kind == EntryKind::Missing) return std::nullopt;
  const std::string where = showPath(dir + "/" + name);
  if (kind != EntryKind::File)
    throw InputError(where + (kind == EntryKind::Link ? ": a link (omnicam follows none in its outputs)" : ": not a regular file") +
                     ": give another folder");
  return parseJsonText(readFileInside(dir, name, limits::kMaxJsonFileBytes), where);
}

[[noreturn]] void refuseNoStudy(const std::string& file) {
  throw InputError(showPath(file) + ": not written by an omnicam experiment (it names no study): give another folder");
}

// The results file by which a folder written before marks tells its study, for the studies
// whose results.json names none.
constexpr std::pair<const char*, const char*> kResultsFileOfStudy[] = {{"convergence.json", "realistic-convergence"},
                                                                       {"path-convergence.json", "path-convergence"}};

// The folders omnicam's experiments make at a folder's top (each study's makeAllFoldersInside,
// the Cycles frame cache's cycles/): a folder of these alone, without a mark, is an earlier run's
// that ended before its results (written before marks).
const std::set<std::string>& experimentLayout() {
  static const std::set<std::string> names = {"arenas", "cycles", "data", "figures", "frames", "scenes"};
  return names;
}

// The entries of `dir` that no experiment writes, in name order.
std::vector<std::string> foreignEntries(const std::string& dir) {
  std::vector<std::string> foreign;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (!experimentLayout().count(entry.path().filename().string())) foreign.push_back(entry.path().filename().string());
  std::sort(foreign.begin(), foreign.end());
  return foreign;
}

}  // namespace

void checkExperimentFolder(const std::string& dir, const std::string& study) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec) || std::filesystem::is_empty(dir, ec)) return;
  const std::string markFile = dir + "/" + kExperimentMark;
  if (const std::optional<nlohmann::json> mark = experimentFile(dir, kExperimentMark)) {
    if (!mark->is_object() || !mark->contains("study") || !(*mark)["study"].is_string()) refuseNoStudy(markFile);
    const std::string marked = (*mark)["study"].get<std::string>();
    if (marked != study)
      throw InputError(showPath(markFile) + ": the folder is experiment " + quote(marked) + "'s (its mark), not " + study +
                       "'s: give another folder");
    earlierExperimentResults(dir, study);  // its results, if any, are the study's too
    return;
  }
  if (earlierExperimentResults(dir, study)) return;
  for (const auto& [file, theirs] : kResultsFileOfStudy)
    if (entryInside(dir, file) == EntryKind::File) {
      if (theirs != study)
        throw InputError(showPath(dir + "/" + file) + ": holds the results of experiment " + quote(theirs) + ", not " + study +
                         ": give another folder");
      return;
    }
  const std::vector<std::string> foreign = foreignEntries(dir);
  if (foreign.empty()) return;  // an interrupted run's, from before marks: its frames are reused
  throw InputError(showPath(dir) + ": holds files no omnicam experiment wrote (" + quote(foreign.front()) +
                   (foreign.size() > 1 ? " and " + std::to_string(foreign.size() - 1) + " more" : std::string()) +
                   "): give an empty or new folder");
}

void markExperimentFolder(const std::string& dir, const std::string& study) {
  if (entryInside(dir, kExperimentMark) == EntryKind::File) return;
  SafeFolder(dir).writeFile(kExperimentMark, nlohmann::json({{"study", study}}).dump(1) + "\n", Durability::Synced);
}

std::optional<nlohmann::json> earlierExperimentResults(const std::string& dir, const std::string& study) {
  const std::optional<nlohmann::json> results = experimentFile(dir, "results.json");
  if (!results) return std::nullopt;
  const std::optional<std::string> theirs = studyOf(*results);
  if (!theirs) refuseNoStudy(dir + "/results.json");
  if (*theirs != study)
    throw InputError(showPath(dir + "/results.json") + ": holds the results of experiment " + quote(*theirs) + ", not " + study +
                     ": give another folder");
  return results;
}

void makeRunFolders(const std::string& dir, std::vector<std::string> folders, bool plotsFigures) {
  if (plotsFigures) folders.push_back("figures");
  makeAllFoldersInside(dir, folders);
}

}  // namespace omnicam
