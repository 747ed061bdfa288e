#include "free_space.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/Polygon_triangulation_decomposition_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "input_limits.h"
#include "floor_obstacles.h"

namespace omnicam {

namespace {

// Exact constructions: the differences and unions of many grown footprints meet at points no
// double can hold, and Polygon_set_2 needs them exact to stay valid.
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Kernel::Point_2;
using Polygon = CGAL::Polygon_2<Kernel>;
using PolygonWithHoles = CGAL::Polygon_with_holes_2<Kernel>;
using PolygonSet = CGAL::Polygon_set_2<Kernel>;

// The vertices of a regular polygon whose inscribed circle has radius r (centred at 0).
std::vector<Vec2> circumscribedDisc(double r) {
  const double vertexRadius = r / std::cos(M_PI / FreeSpace::kDiscSides);
  std::vector<Vec2> vertices;
  for (int k = 0; k < FreeSpace::kDiscSides; ++k) {
    const double angle = 2.0 * M_PI * k / FreeSpace::kDiscSides;
    vertices.emplace_back(vertexRadius * std::cos(angle), vertexRadius * std::sin(angle));
  }
  return vertices;
}

// A footprint triangle (possibly degenerate: a wall's side seen from above is a segment) grown by
// the disc: the convex hull of the Minkowski sum of two convex sets, counter-clockwise.
Polygon grownTriangle(const std::array<Vec2, 3>& triangle, const std::vector<Vec2>& disc) {
  std::vector<Point> sums;
  sums.reserve(3 * disc.size());
  for (const Vec2& corner : triangle)
    for (const Vec2& d : disc) sums.emplace_back(corner.x() + d.x(), corner.y() + d.y());
  std::vector<Point> hull;
  CGAL::convex_hull_2(sums.begin(), sums.end(), std::back_inserter(hull));  // counter-clockwise
  return Polygon(hull.begin(), hull.end());
}

Vec2 toVec2(const Point& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

}  // namespace

FreeSpace::FreeSpace(const Scene& scene, double topHeight, const FloorRegion& region, double clearance) {
  if (!(region.xMin < region.xMax && region.yMin < region.yMax))
    throw std::invalid_argument("FreeSpace: empty region");
  // Bounded like every length: a clearance of 1e200 overflows the exact constructions.
  if (!(clearance >= 0.0 && clearance <= limits::kMaxLength))
    throw std::invalid_argument("FreeSpace: clearance outside [0, limits::kMaxLength]");
  // Curved footprints are chords inside the true outline; growing by their tolerance too keeps
  // the clearance exact for them.
  const std::vector<Vec2> disc = circumscribedDisc(clearance + FloorObstacles::kChordTolerance);
  const FloorObstacles obstacles(scene, topHeight);
  std::vector<Polygon> grown;
  const Eigen::AlignedBox2d regionBox(Vec2(region.xMin, region.yMin), Vec2(region.xMax, region.yMax));
  const double reach = clearance + FloorObstacles::kChordTolerance;
  for (const FloorObstacles::Obstacle& obstacle : obstacles.obstacles()) {
    if (obstacle.bounds.exteriorDistance(regionBox) > 2.0 * reach) continue;  // cannot touch the region
    // Boxes and meshes repeat footprints (top and bottom faces); one copy is enough.
    std::vector<std::array<Vec2, 3>> triangles = obstacle.triangles;
    for (auto& t : triangles) std::sort(t.begin(), t.end(), [](const Vec2& a, const Vec2& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
      });
    const auto less = [](const std::array<Vec2, 3>& a, const std::array<Vec2, 3>& b) {
      for (int k = 0; k < 3; ++k) {
        if (a[k].x() != b[k].x()) return a[k].x() < b[k].x();
        if (a[k].y() != b[k].y()) return a[k].y() < b[k].y();
      }
      return false;
    };
    std::sort(triangles.begin(), triangles.end(), less);
    triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
    for (const auto& t : triangles) grown.push_back(grownTriangle(t, disc));
  }
  Polygon regionPolygon;
  regionPolygon.push_back(Point(region.xMin, region.yMin));
  regionPolygon.push_back(Point(region.xMax, region.yMin));
  regionPolygon.push_back(Point(region.xMax, region.yMax));
  regionPolygon.push_back(Point(region.xMin, region.yMax));
  PolygonSet free(regionPolygon);
  if (!grown.empty()) {
    PolygonSet blocked;
    blocked.join(grown.begin(), grown.end());
    free.difference(blocked);
  }
  std::vector<PolygonWithHoles> parts;
  free.polygons_with_holes(std::back_inserter(parts));
  components_ = static_cast<int>(parts.size());
  const CGAL::Polygon_triangulation_decomposition_2<Kernel> triangulate;
  for (const PolygonWithHoles& part : parts) {
    std::vector<Polygon> pieces;
    triangulate(part, std::back_inserter(pieces));
    for (const Polygon& piece : pieces) {
      std::array<Vec2, 3> t{toVec2(piece[0]), toVec2(piece[1]), toVec2(piece[2])};
      const double twiceArea = (t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x();
      if (twiceArea < 0.0) std::swap(t[1], t[2]);
      if (twiceArea == 0.0) continue;
      area_ += 0.5 * std::abs(twiceArea);
      triangles_.push_back(t);
      cumulativeArea_.push_back(area_);
    }
  }
}

Vec2 FreeSpace::pointFromDraws(double pickTriangle, double a, double b) const {
  const double target = pickTriangle * area_;
  const size_t k = std::min<size_t>(
      std::upper_bound(cumulativeArea_.begin(), cumulativeArea_.end(), target) - cumulativeArea_.begin(),
      triangles_.size() - 1);
  // Uniform in a triangle: reflect the unit square's upper half onto the lower one.
  if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
  const std::array<Vec2, 3>& t = triangles_[k];
  return t[0] + a * (t[1] - t[0]) + b * (t[2] - t[0]);
}

}  // namespace omnicam
