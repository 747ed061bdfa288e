#include "scene_ids.h"

#include <map>
#include <string>

namespace omnicam {

using json = nlohmann::json;

IdTables idTables(const Scene& scene) {
  std::map<std::string, uint16_t> classIds;
  for (const SceneObject& object : scene.objects)
    if (const std::string& c = semanticClassOf(scene, object); !c.empty()) classIds[c] = 0;
  IdTables ids;
  uint16_t nextClass = 1;
  ids.classes = json::array({{{"id", 0}, {"name", nullptr}}});
  for (auto& [name, id] : classIds) {
    id = nextClass++;
    ids.classes.push_back({{"id", id}, {"name", name}});
  }
  ids.classOfInstance.assign(scene.objects.size() + 1, 0);
  ids.instances = json::array({{{"id", 0}, {"name", nullptr}, {"class_id", 0}}});
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const std::string& c = semanticClassOf(scene, scene.objects[i]);
    ids.classOfInstance[i + 1] = c.empty() ? 0 : classIds.at(c);
    ids.instances.push_back({{"id", i + 1}, {"name", scene.objects[i].name},
                             {"class", c.empty() ? json(nullptr) : json(c)}, {"class_id", ids.classOfInstance[i + 1]}});
  }
  return ids;
}

std::vector<uint16_t> classIdsOf(const std::vector<uint16_t>& instance, const std::vector<uint16_t>& classOfInstance) {
  std::vector<uint16_t> classes(instance.size());
  for (size_t p = 0; p < classes.size(); ++p) classes[p] = classOfInstance[instance[p]];
  return classes;
}

}  // namespace omnicam
