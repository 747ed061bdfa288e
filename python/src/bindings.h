#pragma once
// The pieces of the Python extension (module.cpp puts them together). Each binds one room of the
// library; the helpers here move C++ results into numpy arrays and JSON into Python objects.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "motion.h"
#include "rig.h"

namespace omnicam::python {

namespace py = pybind11;

void bindScene(py::module_& m);
void bindCamera(py::module_& m);
void bindRender(py::module_& m);
void bindDataset(py::module_& m);

// A numpy array that takes over `values` (no copy): the array owns them and frees them with itself.
template <class T>
py::array_t<T> arrayTakingOver(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(std::move(shape), owned->data(), free);
}

// JSON in and out of Python (dicts, lists, numbers, strings, None), through Python's json module.
py::object toPython(const nlohmann::json& j);
nlohmann::json fromPython(const py::handle& object, const std::string& what);

// A pose given as (x, y, yaw_deg); InputError naming `what` otherwise or out of range.
RobotPose poseFrom(const py::handle& pose, const std::string& what);
// (vx, vy, yaw_rate_deg_per_s) from a sequence of 3 numbers; InputError naming `what`.
BodyVelocity velocityFrom(const py::handle& velocity, const std::string& what);

}  // namespace omnicam::python
