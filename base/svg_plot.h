#pragma once
// A minimal line/scatter chart written as SVG: enough for the report's ring plots.
#include <string>
#include <vector>

namespace omnicam {

struct PlotSeries {
  std::string label, colour;
  std::vector<double> x, y;
  bool points = false;  // markers instead of a line
};

struct PlotSpec {
  std::string title, xLabel, yLabel;
  int width = 640, height = 400;
  std::vector<PlotSeries> series;
};

std::string svgPlot(const PlotSpec& spec);

}  // namespace omnicam
