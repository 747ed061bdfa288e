#include "coco.h"

#include <algorithm>
#include <limits>

#include "errors.h"

namespace omnicam {

std::string cocoRleCounts(const std::vector<uint32_t>& runs) {
  std::string s;
  for (size_t i = 0; i < runs.size(); ++i) {
    int64_t x = runs[i];
    if (i > 2) x -= runs[i - 2];  // pycocotools' delta: runs of the same kind change slowly
    for (bool more = true; more;) {
      int64_t c = x & 0x1f;
      x >>= 5;  // arithmetic: a negative delta keeps its sign bits
      more = (c & 0x10) ? x != -1 : x != 0;
      if (more) c |= 0x20;
      s.push_back(static_cast<char>(c + 48));
    }
  }
  return s;
}

std::vector<uint32_t> cocoRunsFromCounts(const std::string& counts, const std::string& what) {
  std::vector<uint32_t> runs;
  size_t p = 0;
  while (p < counts.size()) {
    int64_t x = 0;
    int k = 0;
    for (bool more = true; more; ++p, ++k) {
      // 7 characters hold 35 bits, more than any run of a 32-bit pixel count: pycocotools writes no more.
      if (p >= counts.size() || k >= 7) throw InputError(what + ": RLE counts end inside a number, or hold one too long");
      const int c = static_cast<unsigned char>(counts[p]) - 48;
      if (c < 0 || c > 63) throw InputError(what + ": RLE counts hold a character outside '0'…'o'");
      x |= static_cast<int64_t>(c & 0x1f) << (5 * k);
      more = (c & 0x20) != 0;
      if (!more && (c & 0x10)) x |= -(int64_t{1} << (5 * (k + 1)));
    }
    if (runs.size() > 2) x += runs[runs.size() - 2];
    if (x < 0 || x > std::numeric_limits<uint32_t>::max()) throw InputError(what + ": RLE counts decode to a negative run");
    runs.push_back(static_cast<uint32_t>(x));
  }
  return runs;
}

std::vector<uint32_t> cocoMaskRuns(const std::vector<uint16_t>& instance, int width, int height, uint16_t id,
                                   const CocoBox& box) {
  std::vector<uint32_t> runs;
  bool inside = false;  // runs start with the 0s
  uint32_t run = 0;
  auto extend = [&](bool on, uint32_t count) {
    if (count == 0) return;
    if (on != inside) {
      runs.push_back(run);
      run = 0;
      inside = on;
    }
    run += count;
  };
  const auto rows = static_cast<uint32_t>(height);
  // Column-major like COCO; only the box is looked at, everything around it is 0.
  extend(false, static_cast<uint32_t>(box.x0) * rows);
  for (int i = box.x0; i <= box.x1; ++i) {
    extend(false, static_cast<uint32_t>(box.y0));
    for (int j = box.y0; j <= box.y1; ++j) extend(instance[static_cast<size_t>(j) * width + i] == id, 1);
    extend(false, static_cast<uint32_t>(height - 1 - box.y1));
  }
  extend(false, static_cast<uint32_t>(width - 1 - box.x1) * rows);
  runs.push_back(run);
  return runs;
}

std::vector<uint32_t> cocoMaskRuns(const std::vector<uint16_t>& instance, int width, int height, uint16_t id) {
  return cocoMaskRuns(instance, width, height, id, CocoBox{0, 0, width - 1, height - 1});
}

std::set<uint16_t> defaultCocoClasses(const IdTables& ids) {
  static const std::set<std::string> kStuff{"floor", "wall", "ceiling", "line"};
  std::set<uint16_t> classes;
  for (const auto& c : ids.classes)
    if (c["id"] != 0 && !kStuff.count(c["name"].get<std::string>())) classes.insert(c["id"].get<uint16_t>());
  return classes;
}

std::set<uint16_t> cocoClassIds(const IdTables& ids, const std::optional<std::vector<std::string>>& names,
                                const std::string& what) {
  if (!names) return defaultCocoClasses(ids);
  std::set<uint16_t> chosen;
  for (const std::string& name : *names) {
    bool found = false;
    for (const auto& c : ids.classes)
      if (c["name"].is_string() && c["name"] == name) chosen.insert(c["id"].get<uint16_t>()), found = true;
    if (!found) {
      std::string known;
      for (const auto& c : ids.classes)
        if (c["name"].is_string()) known += (known.empty() ? "" : ", ") + c["name"].get<std::string>();
      throw InputError(what + ": " + quote(name) + " is not a class of the scene (its classes: " + quote(known, 400) + ")");
    }
  }
  return chosen;
}

nlohmann::json cocoInstanceAnnotations(const std::vector<uint16_t>& instance, int width, int height,
                                       const std::vector<uint16_t>& classOfInstance, const std::set<uint16_t>& classes) {
  struct Bounds {
    CocoBox box{std::numeric_limits<int>::max(), std::numeric_limits<int>::max(), -1, -1};
    int64_t area = 0;
  };
  std::vector<Bounds> bounds(classOfInstance.size());
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const uint16_t id = instance[static_cast<size_t>(j) * width + i];
      if (id == 0 || id >= bounds.size() || !classes.count(classOfInstance[id])) continue;
      Bounds& b = bounds[id];
      b.box.x0 = std::min(b.box.x0, i), b.box.y0 = std::min(b.box.y0, j);
      b.box.x1 = std::max(b.box.x1, i), b.box.y1 = std::max(b.box.y1, j);
      ++b.area;
    }
  nlohmann::json annotations = nlohmann::json::array();
  for (size_t id = 1; id < bounds.size(); ++id) {
    const Bounds& b = bounds[id];
    if (b.area == 0) continue;
    const CocoBox& box = b.box;
    annotations.push_back(
        {{"instance_id", id},
         {"category_id", classOfInstance[id]},
         {"bbox", {box.x0, box.y0, box.x1 - box.x0 + 1, box.y1 - box.y0 + 1}},
         {"area", b.area},
         {"segmentation",
          {{"size", {height, width}}, {"counts", cocoRleCounts(cocoMaskRuns(instance, width, height, static_cast<uint16_t>(id), box))}}},
         {"iscrowd", 0}});
  }
  return annotations;
}

nlohmann::json cocoLandmarkKeypoints(const std::vector<LandmarkAnnotation>& landmarks, int width, int height) {
  nlohmann::json keypoints = nlohmann::json::array();
  int labelled = 0;
  double x0 = width, y0 = height, x1 = 0.0, y1 = 0.0;
  for (const LandmarkAnnotation& l : landmarks) {
    const bool inImage = l.centre && l.centre->x() >= 0.0 && l.centre->y() >= 0.0 && l.centre->x() < width &&
                         l.centre->y() < height && l.visibleFraction > 0.0;
    if (!inImage) {
      keypoints.insert(keypoints.end(), {0.0, 0.0, 0});
      continue;
    }
    keypoints.insert(keypoints.end(), {l.centre->x(), l.centre->y(), l.occluded ? 1 : 2});
    ++labelled;
    x0 = std::min(x0, l.centre->x()), y0 = std::min(y0, l.centre->y());
    x1 = std::max(x1, l.centre->x()), y1 = std::max(y1, l.centre->y());
  }
  const nlohmann::json bbox = labelled ? nlohmann::json{x0, y0, x1 - x0, y1 - y0} : nlohmann::json{0.0, 0.0, 0.0, 0.0};
  return {{"keypoints", keypoints}, {"num_keypoints", labelled}, {"bbox", bbox}, {"iscrowd", 0}};
}

}  // namespace omnicam
