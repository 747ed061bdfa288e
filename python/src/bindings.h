#pragma once
// The pieces of the Python extension (module.cpp puts them together). Each binds one room of the
// library; the helpers here move C++ results into numpy arrays and JSON into Python objects.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "errors.h"
#include "motion.h"
#include "rig.h"

namespace omnicam::python {

namespace py = pybind11;

// An integer argument exactly as Python gave it, of any size: pybind's own int conversion raises
// TypeError for one beyond the C++ type, where the CLI and the scene reader say what range it
// must be in. Read by narrowed() below, with the library's words.
struct PyInteger {
  bool fitsInt64 = true, fitsUint64 = true;
  int64_t value = 0;           // when it fits int64
  uint64_t unsignedValue = 0;  // when it is ≥ 0 and fits 64 bits
  std::string text;            // as Python writes it, for messages
};
// `value` as an int when it lies in [lo, hi]; InputError("<name>: must be an integer in [lo, hi]
// (got …)") otherwise.
int narrowed(const PyInteger& value, const std::string& name, int64_t lo, int64_t hi);
// An integer's digits for a message, shortened past 40 characters.
std::string shownInteger(const std::string& text);
uint64_t narrowedSeed(const PyInteger& value, const std::string& name);

// A file or folder's name as Python gives one: str, bytes or os.PathLike. No file name holds a NUL
// character: a name with one is refused with InputError (a ValueError, as Python's own open()
// refuses it), not cut short at the NUL by the C library (Dataset("a\x00b") read folder "a"),
// nor blamed on its type as pybind's own conversion does.
struct PyPath {
  std::filesystem::path value;
};

void bindScene(py::module_& m);
void bindCamera(py::module_& m);
void bindRender(py::module_& m);
void bindDataset(py::module_& m);

// A numpy array that takes over `values` (no copy): the array owns them and frees them with itself.
template <class T>
py::array_t<T> arrayTakingOver(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  py::ssize_t elements = 1;
  for (py::ssize_t extent : shape) elements *= extent;
  if (static_cast<size_t>(elements) != values.size())
    throw std::logic_error("arrayTakingOver: " + std::to_string(values.size()) + " values for a shape of " +
                           std::to_string(elements));
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(std::move(shape), owned->data(), free);
}

// JSON in and out of Python (dicts, lists, numbers, strings, None), through Python's json module.
py::object toPython(const nlohmann::json& j);
nlohmann::json fromPython(const py::handle& object, const std::string& what);

// Whether `item` is one number meaning a real quantity: a Python int or float, or a numpy scalar of
// an integer or float dtype; not a bool (Python's or numpy's), a complex number or a 0-d array.
bool isRealNumber(const py::handle& item);
// InputError naming `what` unless the array holds real numbers (integer or float dtype): numpy
// would drop a complex array's imaginary part with only a warning, and bools are no quantities.
void checkRealArray(const py::array& given, const std::string& what, const std::string& form);
// A pose given as (x, y, yaw_deg); InputError naming `what` otherwise or out of range.
RobotPose poseFrom(const py::handle& pose, const std::string& what);
// (vx, vy, yaw_rate_deg_per_s) from a sequence of 3 numbers; InputError naming `what`.
BodyVelocity velocityFrom(const py::handle& velocity, const std::string& what);

}  // namespace omnicam::python

namespace pybind11::detail {
template <>
struct type_caster<omnicam::python::PyInteger> {
  PYBIND11_TYPE_CASTER(omnicam::python::PyInteger, const_name("int"));
  bool load(handle source, bool) {
    // Python's ints and what stands for one (numpy's integer scalars: __index__); never a bool,
    // Python's or numpy's, nor a float.
    if (!source || PyBool_Check(source.ptr()) || isNumpyBool(source)) return false;
    object integer;
    if (PyLong_Check(source.ptr())) {
      integer = reinterpret_borrow<object>(source);
    } else if (PyIndex_Check(source.ptr())) {
      integer = reinterpret_steal<object>(PyNumber_Index(source.ptr()));
      if (!integer) return PyErr_Clear(), false;
    } else {
      return false;
    }
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(integer.ptr(), &overflow);
    if (v == -1 && PyErr_Occurred()) return PyErr_Clear(), false;
    value.fitsInt64 = overflow == 0;
    value.value = overflow == 0 ? v : 0;
    value.fitsUint64 = overflow == 0 ? v >= 0 : overflow > 0;
    if (overflow == 0 && v >= 0) value.unsignedValue = static_cast<unsigned long long>(v);
    if (overflow > 0) {
      const unsigned long long u = PyLong_AsUnsignedLongLong(integer.ptr());
      if (PyErr_Occurred()) PyErr_Clear(), value.fitsUint64 = false;
      else value.unsignedValue = u;
    }
    value.text = str(integer).cast<std::string>();
    return true;
  }
  // numpy's bool (numpy.bool_, numpy 2's numpy.bool), by its dtype's kind, not its type's name.
  static bool isNumpyBool(handle source) {
    if (!PyObject_HasAttrString(source.ptr(), "dtype")) return false;
    try {
      return source.attr("dtype").attr("kind").cast<std::string>() == "b";
    } catch (const error_already_set&) {
      return false;
    } catch (const cast_error&) {
      return false;
    }
  }
  static handle cast(const omnicam::python::PyInteger& v, return_value_policy, handle) {
    return PyLong_FromLongLong(v.value);
  }
};

template <>
struct type_caster<omnicam::python::PyPath> {
  PYBIND11_TYPE_CASTER(omnicam::python::PyPath, const_name("os.PathLike"));
  bool load(handle source, bool convert) {
    make_caster<std::filesystem::path> fileName;
    if (fileName.load(source, convert)) {
      value.value = cast_op<std::filesystem::path&&>(std::move(fileName));
      return true;
    }
    // Refused: a str, bytes or os.PathLike may be refused for a NUL in it; anything else is no path.
    object named = reinterpret_steal<object>(PyOS_FSPath(source.ptr()));
    if (!named) return PyErr_Clear(), false;
    std::string text;
    if (PyBytes_Check(named.ptr())) {
      text = named.cast<bytes>();
    } else {
      object encoded = reinterpret_steal<object>(PyUnicode_AsEncodedString(named.ptr(), "utf-8", "surrogateescape"));
      if (!encoded) return PyErr_Clear(), false;
      text = encoded.cast<bytes>();
    }
    if (text.find('\0') == std::string::npos) return false;
    throw omnicam::InputError(omnicam::showPath(text) + ": a file name cannot hold a NUL character");
  }
  static handle cast(const omnicam::python::PyPath& path, return_value_policy policy, handle parent) {
    return make_caster<std::filesystem::path>::cast(path.value, policy, parent);
  }
};
}  // namespace pybind11::detail
