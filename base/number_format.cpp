#include "number_format.h"

#include <algorithm>
#include <charconv>
#include <iomanip>
#include <locale>
#include <sstream>
#include <stdexcept>

namespace omnicam {

std::string roundTrip(double value) {
  char buf[64];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value);
  if (ec != std::errc()) throw std::runtime_error("number formatting failed");
  return std::string(buf, end);
}

std::string shortNumber(double value) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << value;
  return s.str();
}

std::string fixedDecimals(double value, int decimals) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << std::fixed << std::setprecision(decimals) << value;
  return s.str();
}

std::string yamlFloat(double value) {
  // A rotation's exact zeros come out signed (-0): the same number, written as tools write it.
  std::string text = roundTrip(value == 0.0 ? 0.0 : value);
  if (text.find_first_of("in") != std::string::npos) return text;  // nan, inf: no digits to mend
  if (text.find('.') == std::string::npos) text.insert(std::min(text.find('e'), text.size()), ".0");
  return text;
}

std::string yamlFloatList(const std::vector<double>& values) {
  std::string text = "[";
  for (size_t k = 0; k < values.size(); ++k) text += (k ? ", " : "") + yamlFloat(values[k]);
  return text + "]";
}

std::string countOf(long long count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace omnicam
