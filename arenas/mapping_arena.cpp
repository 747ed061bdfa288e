#include "mapping_arena.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "errors.h"

namespace omnicam {

namespace {

using nlohmann::json;

class Random {
 public:
  explicit Random(uint64_t seed) : engine_(seed) {}
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  size_t below(size_t n) { return static_cast<size_t>(engine_() % n); }

 private:
  std::mt19937_64 engine_;
};

json box(const std::string& name, const std::string& material, double cx, double cy, double cz, double sx, double sy,
         double sz, double yawDeg = 0.0) {
  json j = {{"name", name}, {"type", "box"}, {"material", material}, {"center", {cx, cy, cz}}, {"size", {sx, sy, sz}}};
  if (yawDeg != 0.0) j["yaw_deg"] = yawDeg;
  return j;
}

void checkMappingOptions(const MappingOptions& o) {
  if (o.cellsX < 2 || o.cellsY < 2 || o.cellsX > 40 || o.cellsY > 40)
    throw InputError("arena mapping: the maze needs 2-40 cells a side");
  if (!(o.cellSize >= 0.8 && o.cellSize <= 5.0 && o.wallHeight > 0.1 && o.wallHeight <= 5.0 && o.wallThickness > 0.005 &&
        o.wallThickness < 0.3 && o.extraOpenings >= 0.0 && o.extraOpenings <= 1.0))
    throw InputError("arena mapping: cell 0.8-5 m, walls 0.1-5 m high and 5-300 mm thick, extra openings 0-1");
  const int cells = o.cellsX * o.cellsY;
  if (o.victims < 0 || o.debris < 0 || o.victims + 2 > cells || o.debris > 10 * cells)
    throw InputError("arena mapping: at most cells - 2 victims and 10 debris a cell, and no negative counts");
}

// The maze's graph: passages between neighbouring cells, and the tour that walks every passage
// from cell 0 (the depth-first search's own path, walking back along passages).
struct Maze {
  std::set<std::pair<int, int>> open;
  std::vector<int> tour{0};
};

std::vector<int> neighboursOf(const MappingOptions& o, int c) {
  std::vector<int> n;
  const int i = c % o.cellsX, j = c / o.cellsX;
  if (i > 0) n.push_back(c - 1);
  if (i + 1 < o.cellsX) n.push_back(c + 1);
  if (j > 0) n.push_back(c - o.cellsX);
  if (j + 1 < o.cellsY) n.push_back(c + o.cellsX);
  return n;
}

// Depth-first maze: carve passages from cell 0; each cell's unvisited neighbours in random order.
// Then extra openings: loops, as real arenas have.
Maze carveMaze(const MappingOptions& o, Random& random) {
  const int cells = o.cellsX * o.cellsY;
  Maze maze;
  std::vector<bool> visited(static_cast<size_t>(cells), false);
  std::vector<int> stack{0};
  visited[0] = true;
  while (!stack.empty()) {
    std::vector<int> fresh;
    for (int n : neighboursOf(o, stack.back()))
      if (!visited[static_cast<size_t>(n)]) fresh.push_back(n);
    if (fresh.empty()) {
      stack.pop_back();
      if (!stack.empty()) maze.tour.push_back(stack.back());  // walking back along the passage
      continue;
    }
    const int next = fresh[random.below(fresh.size())];
    maze.open.insert({std::min(stack.back(), next), std::max(stack.back(), next)});
    visited[static_cast<size_t>(next)] = true;
    stack.push_back(next);
    maze.tour.push_back(next);
  }
  for (int c = 0; c < cells; ++c)
    for (int n : neighboursOf(o, c))
      if (n > c && !maze.open.count({c, n}) && random.unit() < o.extraOpenings) maze.open.insert({c, n});
  return maze;
}

// The floor, the outer walls, then every inner wall that is not a passage (walls overlap at the
// corners by half a thickness, so no light leaks through).
json floorAndWalls(const MappingOptions& o, const Maze& maze) {
  const double width = o.cellsX * o.cellSize, depth = o.cellsY * o.cellSize, t = o.wallThickness, h = o.wallHeight;
  json objects = json::array();
  objects.push_back({{"name", "floor"}, {"type", "quad"}, {"material", "floor"}, {"origin", {-0.5, -0.5, 0.0}},
                     {"edge_u", {width + 1.0, 0, 0}}, {"edge_v", {0, depth + 1.0, 0}}});
  objects.push_back(box("wall_south", "wall", width / 2, 0, h / 2, width + t, t, h));
  objects.push_back(box("wall_north", "wall", width / 2, depth, h / 2, width + t, t, h));
  objects.push_back(box("wall_west", "wall", 0, depth / 2, h / 2, t, depth + t, h));
  objects.push_back(box("wall_east", "wall", width, depth / 2, h / 2, t, depth + t, h));
  for (int c = 0; c < o.cellsX * o.cellsY; ++c) {
    const int i = c % o.cellsX, j = c / o.cellsX;
    if (i + 1 < o.cellsX && !maze.open.count({c, c + 1}))
      objects.push_back(box("wall_x" + std::to_string(i + 1) + "_y" + std::to_string(j), "wall", (i + 1) * o.cellSize,
                            (j + 0.5) * o.cellSize, h / 2, t, o.cellSize + t, h));
    if (j + 1 < o.cellsY && !maze.open.count({c, c + o.cellsX}))
      objects.push_back(box("wall_y" + std::to_string(j + 1) + "_x" + std::to_string(i), "wall", (i + 0.5) * o.cellSize,
                            (j + 1) * o.cellSize, h / 2, o.cellSize + t, t, h));
  }
  return objects;
}

std::pair<double, double> centreOf(const MappingOptions& o, int c) {
  return {(c % o.cellsX + 0.5) * o.cellSize, (c / o.cellsX + 0.5) * o.cellSize};
}

json ramp(const MappingOptions& o, int cell, Random& random) {
  const auto [cx, cy] = centreOf(o, cell);
  const double run = 0.6 * o.cellSize, rise = 0.2, wide = 0.5 * o.cellSize;
  const bool alongX = random.unit() < 0.5;
  const json origin = alongX ? json{cx - run / 2, cy - wide / 2, 0.0} : json{cx - wide / 2, cy - run / 2, 0.0};
  const json up = alongX ? json{run, 0, rise} : json{0, run, rise};
  const json across = alongX ? json{0, wide, 0} : json{wide, 0, 0};
  return {{"name", "ramp"}, {"type", "quad"}, {"material", "ramp"}, {"origin", origin},
          {"edge_u", alongX ? across : up}, {"edge_v", alongX ? up : across}};
}

// A victim lying in its cell: a body box and a head sphere (objects), and its landmark.
void addVictim(const MappingOptions& o, int v, int cell, Random& random, json& objects, json& landmarks) {
  const auto [cx, cy] = centreOf(o, cell);
  const double yaw = random.uniform(0.0, 180.0), x = cx + random.uniform(-0.2, 0.2) * o.cellSize,
               y = cy + random.uniform(-0.2, 0.2) * o.cellSize;
  const double ux = std::cos(yaw * M_PI / 180.0), uy = std::sin(yaw * M_PI / 180.0);
  const std::string name = "victim_" + std::to_string(v);
  objects.push_back(box(name + "_body", "victim_clothes", x, y, 0.08, 0.55, 0.25, 0.16, yaw));
  objects.push_back({{"name", name + "_head"}, {"type", "sphere"}, {"material", "victim_skin"},
                     {"center", {x + 0.37 * ux, y + 0.37 * uy, 0.09}}, {"radius", 0.09}});
  landmarks.push_back({{"name", name}, {"position", {x + 0.05 * ux, y + 0.05 * uy, 0.09}}, {"diameter", 0.75},
                       {"height", 0.18}, {"colour_class", "victim"}});
}

// A piece of debris in its cell: a box, or a pipe lying on the floor.
json debris(const MappingOptions& o, int d, int cell, Random& random) {
  const auto [cx, cy] = centreOf(o, cell);
  const double x = cx + random.uniform(-0.3, 0.3) * o.cellSize, y = cy + random.uniform(-0.3, 0.3) * o.cellSize;
  const std::string name = "debris_" + std::to_string(d);
  if (random.unit() < 0.6) {
    const double sx = random.uniform(0.1, 0.45), sy = random.uniform(0.05, 0.3), sz = random.uniform(0.03, 0.2);
    return box(name, "debris", x, y, sz / 2, sx, sy, sz, random.uniform(0.0, 180.0));
  }
  const double yaw = random.uniform(0.0, M_PI), half = random.uniform(0.2, 0.5), r = random.uniform(0.03, 0.08);
  return {{"name", name}, {"type", "cylinder"}, {"material", "pipe"},
          {"base", {x - half * std::cos(yaw), y - half * std::sin(yaw), r}},
          {"top", {x + half * std::cos(yaw), y + half * std::sin(yaw), r}}, {"radius", r}};
}

// The scene file around the objects: materials, lamps, the start pose and the tour as a path.
json mappingScene(const MappingOptions& o, const Maze& maze, json objects, json landmarks) {
  const double width = o.cellsX * o.cellSize, depth = o.cellsY * o.cellSize, h = o.wallHeight;
  json waypoints = json::array();
  for (int c : maze.tour) {
    const auto [x, y] = centreOf(o, c);
    waypoints.push_back({x, y});
  }
  const auto [startX, startY] = centreOf(o, 0);
  json lights = json::array();
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      lights.push_back({{"name", "lamp_" + std::to_string(2 * j + i)},
                        {"position", {(i + 0.5) * width / 2, (j + 0.5) * depth / 2, h + 1.5}},
                        {"intensity", 0.35}});
  return {
      {"format", "omnicam-scene/1"},
      {"name", "mapping"},
      {"description", "USARSim-like rescue maze (spec §6), generated by `omnicam arena mapping --seed " +
                          std::to_string(o.seed) + "` (arenas/mapping_arena.h). Origin at the maze's south-west "
                          "corner, +Z up, floor at Z = 0, metres."},
      {"comment", {{"cells", {o.cellsX, o.cellsY}}, {"cell_m", o.cellSize}, {"wall_height_m", h},
                   {"wall_thickness_m", o.wallThickness}, {"seed", o.seed}, {"ramp", "a 0.2 m rise over 0.6 cell"},
                   {"victims", "body box 0.55 x 0.25 x 0.16 m and a head sphere r 0.09 m, class victim"}}},
      {"background", {0.0, 0.0, 0.0}},
      {"start_pose", {startX, startY, 0.0}},
      {"materials",
       {{"floor", {{"color", {0.45, 0.43, 0.4}}, {"ambient", 0.3}, {"diffuse", 0.7}, {"class", "floor"}}},
        {"wall", {{"color", {0.72, 0.62, 0.45}}, {"ambient", 0.3}, {"diffuse", 0.7}, {"class", "wall"}}},
        {"ramp", {{"color", {0.5, 0.5, 0.55}}, {"ambient", 0.3}, {"diffuse", 0.7}, {"class", "ramp"}}},
        {"debris", {{"color", {0.35, 0.3, 0.25}}, {"ambient", 0.3}, {"diffuse", 0.7}, {"class", "debris"}}},
        {"pipe", {{"color", {0.6, 0.6, 0.62}}, {"ambient", 0.3}, {"diffuse", 0.7}, {"class", "debris"}}},
        {"victim_clothes", {{"color", {0.15, 0.25, 0.6}}, {"ambient", 0.3}, {"diffuse", 0.7}, {"class", "victim"}}},
        {"victim_skin", {{"color", {0.85, 0.62, 0.5}}, {"ambient", 0.3}, {"diffuse", 0.7}, {"class", "victim"}}}}},
      {"objects", std::move(objects)},
      {"lights", lights},
      {"landmarks", std::move(landmarks)},
      {"paths", json::array({{{"name", "maze-tour"}, {"waypoints", waypoints}, {"frames", 200}}})}};
}

}  // namespace

MappingArena generateMappingArena(const MappingOptions& o) {
  checkMappingOptions(o);
  // One random stream, drawn in a fixed order (maze, openings, cells, ramp, victims, debris): the
  // same seed gives the same arena with any library.
  Random random(o.seed);
  MappingArena arena;
  const Maze maze = carveMaze(o, random);
  arena.passages.assign(maze.open.begin(), maze.open.end());
  json objects = floorAndWalls(o, maze);
  // Cells for the ramp, the victims and the debris: never the start cell.
  std::vector<int> free;
  for (int c = 1; c < o.cellsX * o.cellsY; ++c) free.push_back(c);
  for (size_t k = free.size(); k > 1; --k) std::swap(free[k - 1], free[random.below(k)]);
  size_t nextFree = 0;
  arena.rampCells.push_back(free[nextFree++]);
  objects.push_back(ramp(o, arena.rampCells.back(), random));
  json landmarks = json::array();
  for (int v = 0; v < o.victims; ++v) {
    arena.victimCells.push_back(free[nextFree++]);
    addVictim(o, v, arena.victimCells.back(), random, objects, landmarks);
  }
  for (int d = 0; d < o.debris; ++d) {
    arena.debrisCells.push_back(nextFree < free.size() ? free[nextFree++] : free[random.below(free.size())]);
    objects.push_back(debris(o, d, arena.debrisCells.back(), random));
  }
  arena.scene = mappingScene(o, maze, std::move(objects), std::move(landmarks));
  return arena;
}

}  // namespace omnicam
