// `import omnicam`: the library's own objects in Python (docs/python.md).
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <utility>

#include "bindings.h"

#include "errors.h"
#include "file_confinement.h"
#include "json_fields.h"
#include "malloc_tuning.h"
#include "memory_budget.h"
#include "render_settings.h"

namespace omnicam::python {

py::object toPython(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

namespace {

// Where in `object` a float is NaN or infinite ("mirror.k", "poses[2]"; "" for `object` itself),
// with its repr: JSON has no such number, and the message should name the field, as the library's
// own readers do.
std::optional<std::pair<std::string, std::string>> firstNonFinite(const py::handle& object, const std::string& path) {
  if (!PyFloat_Check(object.ptr()) && py::hasattr(object, "dtype") && py::hasattr(object, "tolist"))  // numpy's, as fromPython reads them
    return firstNonFinite(object.attr("tolist")(), path);
  if (PyFloat_Check(object.ptr())) {
    if (std::isfinite(PyFloat_AsDouble(object.ptr()))) return std::nullopt;
    return std::make_pair(path, py::repr(object).cast<std::string>());
  }
  if (PyDict_Check(object.ptr())) {
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(object)) {
      const std::string name = keySegment(py::isinstance<py::str>(key) ? key.cast<std::string>() : py::repr(key).cast<std::string>());
      if (auto found = firstNonFinite(value, path.empty() ? name : path + "." + name)) return found;
    }
  } else if (PyList_Check(object.ptr()) || PyTuple_Check(object.ptr())) {
    size_t index = 0;
    for (const py::handle item : py::reinterpret_borrow<py::sequence>(object))
      if (auto found = firstNonFinite(item, path + "[" + std::to_string(index++) + "]")) return found;
  }
  return std::nullopt;
}

}  // namespace

nlohmann::json fromPython(const py::handle& object, const std::string& what) {
  std::string text, refused;
  // numpy's scalars and arrays are numbers and lists (as everywhere else a number is taken); any
  // other type is named in the message.
  const py::cpp_function plain([&refused](const py::handle& value) -> py::object {
    if (py::hasattr(value, "dtype") && py::hasattr(value, "tolist")) return value.attr("tolist")();
    refused = py::str(py::type::of(value).attr("__name__")).cast<std::string>();
    throw py::type_error("not JSON-like");
  });
  try {
    text = py::module_::import("json").attr("dumps")(object, py::arg("default") = plain).cast<std::string>();
  } catch (const py::error_already_set&) {
    throw InputError(what + ": not JSON-like (dicts, lists, numbers, strings, booleans, None" +
                     (refused.empty() ? std::string(")") : std::string("; got a ") + quote(refused) + ")"));
  }
  // Python's json writes NaN and Infinity, which JSON (and the scene format) has not.
  const nlohmann::json parsed = nlohmann::json::parse(text, nullptr, false);
  if (parsed.is_discarded()) {
    if (const auto found = firstNonFinite(object, ""))
      throw InputError(what + ": " + (found->first.empty() ? "" : found->first + ": ") + "must be a finite number (got " +
                       found->second + ")");
    throw InputError(what + ": not a finite number, or not JSON-like");
  }
  return parsed;
}

std::string shownInteger(const std::string& text) {
  if (text.size() <= 40) return text;  // Python's digits (and a sign): nothing to escape
  return text.substr(0, 20) + "… (" + std::to_string(text.size() - (text[0] == '-' ? 1 : 0)) + " digits)";
}

int narrowed(const PyInteger& value, const std::string& name, int64_t lo, int64_t hi) {
  if (!value.fitsInt64 || value.value < lo || value.value > hi)
    throw InputError(name + ": must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                     shownInteger(value.text) + ")");
  return static_cast<int>(value.value);
}

uint64_t narrowedSeed(const PyInteger& value, const std::string& name) {
  if (!value.fitsUint64)
    throw InputError(name + ": must be an integer in [0, 18446744073709551615] (got " + shownInteger(value.text) + ")");
  return value.unsignedValue;
}

namespace {

// `count` real numbers from a sequence (a tuple, list or numpy array); InputError saying `form`.
std::vector<double> realNumbers(const py::handle& given, size_t count, const std::string& what, const std::string& form) {
  if (py::isinstance<py::str>(given) || py::isinstance<py::bytes>(given) ||
      (py::isinstance<py::array>(given) && py::array::ensure(given).ndim() != 1) ||
      (!py::isinstance<py::sequence>(given) && !py::isinstance<py::array>(given)))
    throw InputError(what + ": must be " + form);
  std::vector<double> v;
  bool tooMany = false;
  try {
    for (const py::handle item : given) {
      if (v.size() == count) {  // one more is already too many: the rest is not read
        tooMany = true;
        break;
      }
      if (!isRealNumber(item)) throw InputError(what + ": must be " + form + ", real numbers (not bools or complex numbers)");
      v.push_back(item.cast<double>());
    }
  } catch (const py::cast_error&) {
    throw InputError(what + ": must be " + form);
  } catch (const py::error_already_set&) {  // a number's own conversion failed (an int too large for a double)
    throw InputError(what + ": must be " + form + ", numbers a double holds");
  }
  if (tooMany || v.size() != count) throw InputError(what + ": must be " + form + ", " + std::to_string(count) + " numbers");
  return v;
}

}  // namespace

bool isRealNumber(const py::handle& item) {
  if (PyBool_Check(item.ptr()) || PyComplex_Check(item.ptr())) return false;
  if (py::isinstance<py::array>(item)) return false;  // an array, 0-d ones included: not one number
  if (PyObject_HasAttrString(item.ptr(), "dtype")) {  // a numpy scalar
    try {
      const std::string kind = item.attr("dtype").attr("kind").cast<std::string>();
      return kind == "i" || kind == "u" || kind == "f";
    } catch (const py::error_already_set&) {
      return false;
    }
  }
  return PyNumber_Check(item.ptr()) != 0;  // int, float, and numbers that convert to one (Fraction, Decimal)
}

void checkRealArray(const py::array& given, const std::string& what, const std::string& form) {
  const char kind = given.dtype().kind();
  if (kind != 'i' && kind != 'u' && kind != 'f')
    throw InputError(what + ": must be " + form + " of real numbers (got dtype " + py::str(given.dtype()).cast<std::string>() + ")");
}

RobotPose poseFrom(const py::handle& pose, const std::string& what) {
  const std::vector<double> v = realNumbers(pose, 3, what, "(x, y, yaw_deg)");
  const RobotPose p{v[0], v[1], v[2]};
  checkPose(p, what);
  return p;
}

BodyVelocity velocityFrom(const py::handle& velocity, const std::string& what) {
  const std::vector<double> v = realNumbers(velocity, 3, what, "(vx, vy, yaw_rate_deg_per_s)");
  return {v[0], v[1], v[2]};  // ranges: checkRenderSettings, with the CLI's message
}

}  // namespace omnicam::python

PYBIND11_MODULE(_omnicam, m) {
  namespace py = pybind11;
  using namespace omnicam;
  m.doc() = "omnicam: catadioptric omnidirectional camera simulation with exact ground truth (docs/python.md)";
  m.attr("__version__") = OMNICAM_VERSION;  // the file VERSION, as the installed package's metadata
  // As the CLI: frames' large buffers stay in the heap for the next frame instead of being faulted
  // in anew (a denoised 360-px path frame took 0.42 s instead of 0.28 s). Process-wide: glibc's
  // mmap and trim thresholds (base/malloc_tuning.h).
  keepFreedMemoryInTheHeap();
  // The library's errors keep their one-line messages. Bad input is a ValueError, a file that
  // cannot be written an OSError, a failing external tool (POV-Ray, Blender) a RuntimeError.
  static py::exception<InputError>& inputError = py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  inputError.doc() = "Bad input (a value, a spec, a scene, a file's contents): its message names what and where, on one line.";
  // Tried before register_exception's own translator: a file outside the scene's folder is allowed
  // by this front's keyword, not by the CLI's flag.
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const InputError& e) {
      const std::string message = withOutsideFilesHint(e.what(), "pass allow_outside_files=True to permit it");
      PyErr_SetString(inputError.ptr(), message.c_str());
    }
  });
  py::register_exception<OutputError>(m, "OutputError", PyExc_OSError).doc() =
      "A file or folder could not be written (or would be written where it must not be); nothing is left half-written.";
  py::register_exception<MemoryShortage>(m, "MemoryShortage", PyExc_MemoryError).doc() =
      "A render or dataset needs more memory than the machine gives.";
  py::register_exception<ExternalError>(m, "ExternalError", PyExc_RuntimeError).doc() =
      "An external tool (POV-Ray, Blender, Slurm) failed or is missing; the message says which and why.";
  python::bindScene(m);
  python::bindCamera(m);
  python::bindRender(m);
  python::bindDataset(m);
  // Named as users import them, however the module is loaded: omnicam.Rig, not omnicam._omnicam.Rig
  // (messages, reprs, pickles).
  for (const char* name : {"Camera", "ExternalError", "InputError", "MemoryShortage", "OutputError", "Renderer", "Rig", "Scene"})
    m.attr(name).attr("__module__") = "omnicam";
  // A mistyped keyword names itself and the one meant (omnicam/__init__.py, _check_keywords).
  py::module_::import("omnicam").attr("_check_keywords")(m);
}
