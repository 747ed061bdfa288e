#include "target_fields.h"

#include <cmath>
#include <string>

#include "errors.h"
#include "number_format.h"

namespace omnicam {

namespace {

TargetPattern readTargetPattern(JsonFields p) {
  const std::string kind = p.string("kind");
  TargetPattern pattern;
  if (kind == "checkerboard") {
    Checkerboard b;
    // At least 3 inner corners a side (Kalibr's and OpenCV's detectors need them).
    b.rows = static_cast<int>(p.integer("rows", 4, 1000));
    b.columns = static_cast<int>(p.integer("columns", 4, 1000));
    b.square = p.number("square", {1e-4, 10.0, false, "m"});
    // One odd and one even side: only then does the board look different turned half round, and
    // a detector can tell which corner is the first (OpenCV's advice).
    if ((b.rows + b.columns) % 2 == 0) p.fail("columns", "rows + columns must be odd (one side even, one odd: else the board has no first corner a detector can tell)");
    pattern = b;
  } else if (kind == "aprilgrid") {
    AprilGrid g;
    g.tagRows = static_cast<int>(p.integer("tag_rows", 1, 100));
    g.tagColumns = static_cast<int>(p.integer("tag_columns", 1, 100));
    g.tagSize = p.number("tag_size", {1e-3, 10.0, false, "m"});
    g.tagSpacing = p.number("tag_spacing", {0.0, 1.0, true});
    g.firstId = p.integer("first_id", 0, 0, aprilGridFamilySize() - 1);
    pattern = g;
  } else {
    p.fail("kind", "unknown pattern kind " + quote(kind) + " (checkerboard, aprilgrid)");
  }
  p.finish();
  return pattern;
}

}  // namespace

CalibrationTarget readCalibrationTarget(JsonFields& o, const std::string& name,
                                        const std::vector<CalibrationTarget>& others) {
  CalibrationTarget target;
  target.name = name;
  target.pattern = readTargetPattern(o.object("pattern"));
  const double texel = targetTexel(target.pattern);
  const double defaultMargin = std::holds_alternative<Checkerboard>(target.pattern)
                                   ? std::get<Checkerboard>(target.pattern).square
                                   : std::get<AprilGrid>(target.pattern).tagSize / 5.0;  // two tag bits
  target.margin = o.number("margin", defaultMargin, {0.0, 10.0, false, "m"});
  if (std::llround(target.margin / texel) < 1)
    o.fail("margin", "must be at least one texel of the pattern (" + shortNumber(texel) + " m; the texture repeats)");
  const std::string problem = targetPatternProblem(target.pattern, target.margin);
  if (!problem.empty()) o.fail("pattern", problem);
  int64_t texels = targetBoardTexels(target.pattern, target.margin);
  for (const CalibrationTarget& other : others) texels += targetBoardTexels(other.pattern, other.margin);
  if (texels > kMaxTargetTexelsInScene)
    o.fail("pattern", "the scene's boards need " + std::to_string(texels) + " texels in all (at most " +
                          std::to_string(kMaxTargetTexelsInScene) + ")");
  const Vec3 origin = o.vec3("origin"), xAxis = o.vec3("x_axis"), yAxis = o.vec3("y_axis");
  if (!(xAxis.norm() > 1e-9)) o.fail("x_axis", "must not be zero");
  if (!(yAxis.norm() > 1e-9)) o.fail("y_axis", "must not be zero");
  const Vec3 x = xAxis.normalized();
  if (std::abs(x.dot(yAxis.normalized())) > 1e-6) o.fail("y_axis", "must be perpendicular to x_axis");
  // Exactly orthonormal: y is the given one's part perpendicular to x.
  const Vec3 z = x.cross(yAxis).normalized();
  target.worldFromTarget.linear().col(0) = x;
  target.worldFromTarget.linear().col(1) = z.cross(x);
  target.worldFromTarget.linear().col(2) = z;
  target.worldFromTarget.translation() = origin;
  return target;
}

}  // namespace omnicam
