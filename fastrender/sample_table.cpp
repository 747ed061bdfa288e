#include "sample_table.h"

#include <algorithm>
#include <cmath>

#include "film.h"

namespace omnicam {

StoredRay storedRay(const CameraRay& ray, bool central) {
  StoredRay stored{ray.direction.cast<float>()};
  if (central) return stored;
  const double start = std::max(0.0, ray.origin.dot(ray.direction));
  stored.origin = (ray.origin - start * ray.direction).cast<float>();
  stored.start = static_cast<float>(start);
  return stored;
}

std::shared_ptr<const SampleTable> buildSampleTable(const std::shared_ptr<const Camera>& camera, int n) {
  auto table = std::make_shared<SampleTable>();
  table->camera = camera;
  table->samplesPerAxis = n;
  const bool central = camera->central();
  const size_t pixels = static_cast<size_t>(camera->width()) * camera->height();
  table->firstSample.reserve(pixels + 1);
  table->centreDirections.reserve(pixels);
  table->centreSample.reserve(pixels);
  const auto record = [&](const CameraRay& ray, std::vector<Eigen::Vector3f>& directions,
                          std::vector<Eigen::Vector3f>& origins, std::vector<float>& starts) {
    const StoredRay stored = storedRay(ray, central);
    directions.push_back(stored.direction);
    if (central) return;
    origins.push_back(stored.origin);
    starts.push_back(stored.start);
  };
  for (int j = 0; j < camera->height(); ++j)
    for (int i = 0; i < camera->width(); ++i) {
      table->firstSample.push_back(static_cast<uint32_t>(table->directions.size()));
      uint32_t centre = SampleTable::kNoSample;
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          const auto ray = camera->generateRay({Film::sample(i, j, a, b, n)});
          if (!ray) continue;
          if (2 * a + 1 == n && 2 * b + 1 == n) centre = static_cast<uint32_t>(table->directions.size());
          record(*ray, table->directions, table->origins, table->starts);
          table->gridIndex.push_back(static_cast<uint16_t>(b * n + a));
        }
      const auto middle = camera->generateRay({pixelCentre(i, j)});
      if (middle) {
        record(*middle, table->centreDirections, table->centreOrigins, table->centreStarts);
      } else {
        table->centreDirections.push_back(Eigen::Vector3f::Constant(NAN));
        if (!central) {
          table->centreOrigins.push_back(Eigen::Vector3f::Zero());
          table->centreStarts.push_back(0.0f);
        }
      }
      table->centreSample.push_back(centre);
    }
  table->firstSample.push_back(static_cast<uint32_t>(table->directions.size()));
  return table;
}

bool addGridRays(const Camera& camera, int i, int j, int n, std::vector<StoredRay>& rays, std::vector<uint16_t>& grid) {
  const size_t before = rays.size();
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < n; ++a) {
      const auto ray = camera.generateRay({Film::sample(i, j, a, b, n)});
      if (!ray) {
        rays.resize(before);
        grid.resize(before);
        return false;
      }
      rays.push_back(storedRay(*ray, camera.central()));
      grid.push_back(static_cast<uint16_t>(b * n + a));
    }
  return true;
}

}  // namespace omnicam
