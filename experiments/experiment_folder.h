#pragma once
// An experiment's output folder: which study's results it holds (results.json's "study"), so a
// run never mixes its files into another experiment's folder or into files it did not write.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace omnicam {

// The results.json an earlier run left in `dir`, read without following a link; nullopt when
// there is none. InputError when `dir` holds the results of another study than `study`, or a
// results.json no omnicam experiment wrote (not JSON, or naming no study).
std::optional<nlohmann::json> earlierExperimentResults(const std::string& dir, const std::string& study);

// Before a run of `study` writes into `dir`: InputError unless `dir` is missing, empty, or an
// earlier run's of the same study — told by the mark every run leaves (markExperimentFolder) or,
// for folders written before marks, by the study's results file (results.json's "study",
// convergence.json, path-convergence.json). A folder of other files, or of another study, is
// refused: runs into one folder never mix, and an interrupted run's folder is taken up again.
void checkExperimentFolder(const std::string& dir, const std::string& study);

// Marks `dir` (made, and checked by checkExperimentFolder) as `study`'s, before the run writes
// anything else into it.
void markExperimentFolder(const std::string& dir, const std::string& study);

// Makes a run's `folders` inside `dir` (no link followed), and figures/ when the run plots its
// figures: a run with --no-figures leaves no empty figures/ behind.
void makeRunFolders(const std::string& dir, std::vector<std::string> folders, bool plotsFigures);

// The file that marks an experiment's folder.
inline constexpr const char* kExperimentMark = ".omnicam-experiment.json";

}  // namespace omnicam
