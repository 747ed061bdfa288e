#include "number_format.h"

#include <charconv>
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

}  // namespace omnicam
