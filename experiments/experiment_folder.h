#pragma once
// An experiment's output folder: which study's results it holds (results.json's "study"), so a
// run never mixes its files into another experiment's folder or into files it did not write.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace omnicam {

// The results.json an earlier run left in `dir`, read without following a link; nullopt when
// there is none. InputError when `dir` holds the results of another study than `study`, or a
// results.json no omnicam experiment wrote (not JSON, or naming no study).
std::optional<nlohmann::json> earlierExperimentResults(const std::string& dir, const std::string& study);

}  // namespace omnicam
