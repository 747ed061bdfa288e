#pragma once
// Lookups and number formats the texture-realism report's sections share.
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "texture_realism_results.h"
#include "number_format.h"

namespace omnicam {

inline const ConditionOutcome* findCondition(const TextureRealismResults& r, const std::string& key) {
  for (const ConditionOutcome& c : r.conditions)
    if (c.key() == key) return &c;
  return nullptr;
}

inline const EkfOutcome* findEkf(const TextureRealismResults& r, const std::string& condition) {
  for (const EkfOutcome& e : r.ekf)
    if (e.condition == condition) return &e;
  return nullptr;
}

// TP/FP: ∞ with true positives and no false ones; NaN (shown "–", never at least a bar) with neither.
inline double trueOverFalse(const ConditionOutcome& c) {
  if (c.falsePositives == 0) return c.truePositives ? INFINITY : NAN;
  return static_cast<double>(c.truePositives) / c.falsePositives;
}

inline std::string ratioText(double ratio) {
  return std::isnan(ratio) ? "–" : std::isinf(ratio) ? "∞" : fixedDecimals(ratio, 4);
}

// A mean over true positives, "–" where there were none.
inline std::string decimalsOrDash(const std::optional<double>& value, int decimals) {
  return value ? fixedDecimals(*value, decimals) : "–";
}

inline nlohmann::json jsonOrNull(const std::optional<double>& value) { return value ? nlohmann::json(*value) : nlohmann::json(); }

}  // namespace omnicam
