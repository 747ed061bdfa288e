#include "svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace omnicam {

namespace {
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}
std::string tick(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
// A "nice" tick step for a range.
double niceStep(double range) {
  const double raw = range / 6.0;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * p) return m * p;
  return 10.0 * p;
}
}  // namespace

std::string svgPlot(const PlotSpec& spec) {
  double x0 = std::numeric_limits<double>::max(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : spec.series)
    for (size_t i = 0; i < s.x.size(); ++i) {
      x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]);
      y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
    }
  if (y1 - y0 < 1e-12) y1 = y0 + 1.0;
  const double pad = 0.05 * (y1 - y0);
  y0 -= pad, y1 += pad;
  const double left = 70, right = 20, top = 40, bottom = 50;
  const double pw = spec.width - left - right, ph = spec.height - top - bottom;
  auto X = [&](double v) { return left + (v - x0) / (x1 - x0) * pw; };
  auto Y = [&](double v) { return top + (1.0 - (v - y0) / (y1 - y0)) * ph; };
  std::ostringstream o;
  o << "<svg xmlns='http://www.w3.org/2000/svg' width='" << spec.width << "' height='" << spec.height
    << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
  o << "<text x='" << spec.width / 2 << "' y='22' text-anchor='middle' font-size='14'>" << spec.title << "</text>\n";
  const double xs = niceStep(x1 - x0), ys = niceStep(y1 - y0);
  for (double v = std::ceil(x0 / xs) * xs; v <= x1 + 1e-9; v += xs)
    o << "<line x1='" << num(X(v)) << "' y1='" << top << "' x2='" << num(X(v)) << "' y2='" << top + ph
      << "' stroke='#eee'/><text x='" << num(X(v)) << "' y='" << top + ph + 16 << "' text-anchor='middle'>" << tick(v)
      << "</text>\n";
  for (double v = std::ceil(y0 / ys) * ys; v <= y1 + 1e-9; v += ys)
    o << "<line x1='" << left << "' y1='" << num(Y(v)) << "' x2='" << left + pw << "' y2='" << num(Y(v))
      << "' stroke='#eee'/><text x='" << left - 6 << "' y='" << num(Y(v) + 4) << "' text-anchor='end'>" << tick(v)
      << "</text>\n";
  o << "<rect x='" << left << "' y='" << top << "' width='" << pw << "' height='" << ph
    << "' fill='none' stroke='#333'/>\n";
  o << "<text x='" << left + pw / 2 << "' y='" << spec.height - 12 << "' text-anchor='middle'>" << spec.xLabel
    << "</text>\n<text transform='translate(16," << top + ph / 2 << ") rotate(-90)' text-anchor='middle'>"
    << spec.yLabel << "</text>\n";
  int legend = 0;
  for (const auto& s : spec.series) {
    if (s.points) {
      for (size_t i = 0; i < s.x.size(); ++i)
        o << "<circle cx='" << num(X(s.x[i])) << "' cy='" << num(Y(s.y[i])) << "' r='3.5' fill='none' stroke='"
          << s.colour << "' stroke-width='1.5'/>\n";
    } else {
      o << "<polyline fill='none' stroke='" << s.colour << "' stroke-width='1.5' points='";
      for (size_t i = 0; i < s.x.size(); ++i) o << num(X(s.x[i])) << "," << num(Y(s.y[i])) << " ";
      o << "'/>\n";
    }
    const double ly = top + 14 + 16 * legend++;
    o << "<rect x='" << left + 10 << "' y='" << ly - 9 << "' width='14' height='3' fill='" << s.colour
      << "'/><text x='" << left + 30 << "' y='" << ly - 4 << "'>" << s.label << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace omnicam
