#pragma once
// Lookups and number formats the texture-realism report's sections share.
#include <cmath>
#include <iomanip>
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

inline double trueOverFalse(const ConditionOutcome& c) {
  return c.falsePositives ? static_cast<double>(c.truePositives) / c.falsePositives : INFINITY;
}

inline std::string ratioText(double ratio) { return std::isinf(ratio) ? "∞" : fixedDecimals(ratio, 4); }

}  // namespace omnicam
