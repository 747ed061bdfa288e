#pragma once
// The `mapping` arena (spec §6): a USARSim-like rescue maze — walls on a grid of cells carved by a
// seeded depth-first maze (plus a few extra openings, so there are loops as in real arenas),
// debris, a ramp and victims — written as an ordinary scene file. `omnicam arena mapping --seed S`.
//
// Victims carry the semantic class `victim` and a landmark each (colour_class "victim"), so a
// victim-detection dataset is one spec away (dataset landmark annotations, instance and class
// masks). The path "maze-tour" drives through every cell along the maze's passages.
//
// Generation uses a 64-bit Mersenne Twister turned into numbers by bit arithmetic only: a seed
// gives the same arena with any compiler or standard library.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace omnicam {

// Parameters (metres).
struct MappingOptions {
  uint64_t seed = 1;
  int cellsX = 5, cellsY = 4;   // the maze grid
  double cellSize = 1.6;
  double wallHeight = 1.0, wallThickness = 0.06;
  double extraOpenings = 0.15;  // fraction of the remaining inner walls also removed (loops)
  int victims = 4;
  int debris = 14;
};

struct MappingArena {
  nlohmann::json scene;  // the scene file's content (format omnicam-scene/1)
  // Passages between cells (cell index j·cellsX + i): the maze's graph, for tests and tours.
  std::vector<std::pair<int, int>> passages;
  std::vector<int> victimCells, rampCells, debrisCells;
};

// InputError for parameters out of range (grid 2–40 cells a side, cell 0.8–5 m, …).
MappingArena generateMappingArena(const MappingOptions& options);

}  // namespace omnicam
