#pragma once
// Locale-independent, round-trip number text for generated files (docs/robustness.md).
#include <string>

namespace omnicam {
// Shortest text that parses back to exactly `value` ("0.1", "1e-07"); never uses the locale.
std::string roundTrip(double value);
}  // namespace omnicam
