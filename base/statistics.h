#pragma once
// Summaries of a sample: one definition each, so that every report means the same by them.
#include <algorithm>
#include <optional>
#include <vector>

namespace omnicam {

// The arithmetic mean; none for an empty sample.
inline std::optional<double> meanOf(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

// The median (of an even count, the mean of the middle two); none for an empty sample.
inline std::optional<double> medianOf(std::vector<double> values) {
  if (values.empty()) return std::nullopt;
  const size_t n = values.size();
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(n / 2), values.end());
  const double upper = values[n / 2];
  if (n % 2) return upper;
  return 0.5 * (*std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(n / 2)) + upper);
}

}  // namespace omnicam
