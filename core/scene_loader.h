#pragma once
#include <string>

#include "scene.h"

namespace omnicam {

// Loads and validates a scene file. Anything wrong — unknown field, wrong type, out-of-range
// value, missing texture — throws InputError with one line "<file>: <field>: <what is wrong>".
Scene loadScene(const std::string& path);

}  // namespace omnicam
