#pragma once
// The ids a scene's objects carry in instance and class AOVs, datasets and their annotations:
// instance i + 1 is Scene::objects[i] (0: nothing); classes are numbered 1, 2, … in the name
// order of the semantic classes the scene uses (0: none).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "scene.h"

namespace omnicam {

struct IdTables {
  nlohmann::json classes;    // [{"id", "name"}], id 0 first (name null)
  nlohmann::json instances;  // [{"id", "name", "class", "class_id"}], id 0 first
  std::vector<uint16_t> classOfInstance;  // class id of instance id i
};

IdTables idTables(const Scene& scene);
// The class id image of an instance id image (classOfInstance indexed by instance id).
std::vector<uint16_t> classIdsOf(const std::vector<uint16_t>& instance, const std::vector<uint16_t>& classOfInstance);

}  // namespace omnicam
