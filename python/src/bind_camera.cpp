// omnicam.Camera: the camera interface (camera/camera.h), vectorised over numpy arrays.
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "bindings.h"
#include "errors.h"
#include "input_limits.h"
#include "number_format.h"
#include "make_camera.h"
#include "placement.h"
#include "render_settings.h"
#include "shutter.h"
#include "timed_projection.h"

namespace omnicam::python {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct PyCamera {
  std::shared_ptr<const Camera> camera;
};

// An (N, k) array-like's rows (a numpy array of any number type, nested lists, …) as float64;
// InputError naming `what` for anything else.
py::array_t<double, py::array::c_style | py::array::forcecast> rowsOf(const py::object& a, int k, const std::string& what) {
  if (const py::array given = py::array::ensure(a))
    checkRealArray(given, what, "an array of shape (N, " + std::to_string(k) + ")");
  else
    PyErr_Clear();
  auto rows = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!rows) PyErr_Clear();
  if (!rows || rows.ndim() != 2 || rows.shape(1) != k)
    throw InputError(what + ": must be an array of shape (N, " + std::to_string(k) + ")");
  return rows;
}

// The robot's placement at `pose` (the exposure start) driving at `velocity`; nullopt without a
// pose (points and rays in the viewpoint frame).
std::optional<CameraPlacement> placementFrom(const py::object& pose, const py::object& velocity) {
  if (pose.is_none()) {
    if (!velocity.is_none()) throw InputError("velocity: needs a pose (the robot's at the exposure start)");
    return std::nullopt;
  }
  const CameraPlacement placement(poseFrom(pose, "pose"), velocity.is_none() ? BodyVelocity{} : velocityFrom(velocity, "velocity"));
  checkPlacement(placement);
  return placement;
}

// `time` as one number or one per row of `n`: seconds after the exposure start, within the
// exposure bound either side (the motion model holds a velocity that long). A time other than 0
// needs a velocity: a still robot is where its pose is at every time. In an array, NaN is a pixel
// without a time (pixel_times' off the image): its ray is NaN.
std::vector<double> timesOf(const py::object& time, size_t n, bool moving) {
  const std::string form = "a number or an array of one time per pixel, shape (" + std::to_string(n) + ",)";
  std::vector<double> times;
  bool perPixel = false;
  if (isRealNumber(time)) {
    try {
      times.assign(n, time.cast<double>());
    } catch (const std::exception&) {  // an int too large for a double (pybind11's cast_error or Python's OverflowError)
      throw InputError("time: must be " + form + " (got " + py::repr(time).cast<std::string>().substr(0, 40) + ")");
    }
  } else {
    const py::array given = py::array::ensure(time);
    if (!given) PyErr_Clear();
    if (!given || given.ndim() != 1 || static_cast<size_t>(given.shape(0)) != n) throw InputError("time: must be " + form);
    checkRealArray(given, "time", form);
    const auto rows = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(given);
    times.assign(rows.data(), rows.data() + n);
    perPixel = true;
  }
  for (double t : times) {
    if (perPixel && std::isnan(t)) continue;
    if (!(std::abs(t) <= limits::kMaxExposureS))
      throw InputError("time: must be within ±" + shortNumber(limits::kMaxExposureS) + " s of the exposure start (got " +
                       roundTrip(t) + ")");
    if (t != 0.0 && !moving)
      throw InputError("time: does nothing without a pose and a velocity (a still robot is where its pose puts it at every "
                       "time): give both, or leave time out");
  }
  return times;
}

py::array_t<double> project(const PyCamera& self, const py::object& points, const py::object& pose, const py::object& velocity) {
  const auto in = rowsOf(points, 3, "points");
  const std::optional<CameraPlacement> placement = placementFrom(pose, velocity);
  const Rigid viewpointFromInput = placement ? placement->worldFromViewpoint(self.camera->rig(), 0.0).inverse() : Rigid::Identity();
  const bool timed = placement && !velocity.is_none();
  const auto n = static_cast<size_t>(in.shape(0));
  std::vector<double> out(2 * n);
  const double* p = in.data();
  {
    py::gil_scoped_release release;
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      const Vec3 point(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
      // Moving: each point where the line that sees it sees it, at that line's time (as the
      // frame's landmarks are projected).
      std::optional<Vec2> q;
      if (timed) {
        if (const auto at = projectAtReadout(*self.camera, *placement, point)) q = at->raster;
      } else {
        q = self.camera->project(viewpointFromInput * point);
      }
      out[2 * i] = q ? q->x() : kNaN;
      out[2 * i + 1] = q ? q->y() : kNaN;
    });
  }
  return arrayTakingOver(std::move(out), {static_cast<py::ssize_t>(n), 2});
}

py::tuple rays(const PyCamera& self, const py::object& pixels, const py::object& pose, const py::object& velocity,
               const py::object& time) {
  const auto in = rowsOf(pixels, 2, "pixels");
  const auto n = static_cast<size_t>(in.shape(0));
  const std::optional<CameraPlacement> placement = placementFrom(pose, velocity);
  const std::vector<double> times = timesOf(time, n, placement && !velocity.is_none());
  std::vector<double> origins(3 * n), directions(3 * n);
  const double* p = in.data();
  {
    py::gil_scoped_release release;
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      const Rigid outputFromViewpoint =
          placement && !std::isnan(times[i]) ? placement->worldFromViewpoint(self.camera->rig(), times[i]) : Rigid::Identity();
      const auto ray = std::isnan(times[i]) ? std::nullopt : self.camera->generateRay({Vec2(p[2 * i], p[2 * i + 1])});
      const Vec3 o = ray ? Vec3(outputFromViewpoint * ray->origin) : Vec3::Constant(kNaN);
      const Vec3 d = ray ? Vec3(outputFromViewpoint.linear() * ray->direction) : Vec3::Constant(kNaN);
      for (int k = 0; k < 3; ++k) origins[3 * i + k] = o[k], directions[3 * i + k] = d[k];
    });
  }
  const auto shape = std::vector<py::ssize_t>{static_cast<py::ssize_t>(n), 3};
  return py::make_tuple(arrayTakingOver(std::move(origins), shape), arrayTakingOver(std::move(directions), shape));
}

// Each raster point's time: mid-exposure of its pixel's readout line (shutter.h's pixelTime, the
// instant the frame's AOVs and annotations are taken at there); NaN off the image.
py::array_t<double> pixelTimes(const PyCamera& self, const py::object& pixels) {
  const auto in = rowsOf(pixels, 2, "pixels");
  const auto n = static_cast<size_t>(in.shape(0));
  const int width = self.camera->width(), height = self.camera->height();
  const Shutter& shutter = self.camera->rig().shutter;
  std::vector<double> out(n);
  const double* p = in.data();
  for (size_t k = 0; k < n; ++k) {
    const double u = p[2 * k], v = p[2 * k + 1];
    const bool inside = u >= 0.0 && u < width && v >= 0.0 && v < height;  // NaN is outside
    out[k] = inside ? pixelTime(shutter, static_cast<int>(u), static_cast<int>(v), width, height) : kNaN;
  }
  return arrayTakingOver(std::move(out), {static_cast<py::ssize_t>(n)});
}

py::array_t<bool> images(const PyCamera& self, const py::object& pixels) {
  const auto in = rowsOf(pixels, 2, "pixels");
  const auto n = static_cast<size_t>(in.shape(0));
  py::array_t<bool> out(static_cast<py::ssize_t>(n));
  bool* o = out.mutable_data();
  const double* p = in.data();
  for (size_t i = 0; i < n; ++i) o[i] = self.camera->images(Vec2(p[2 * i], p[2 * i + 1]));
  return out;
}

}  // namespace

void bindCamera(py::module_& m) {
  py::class_<PyCamera>(m, "Camera", R"(The camera of a rig (camera/camera.h): the closed-form central (Mei) model for the
ideal rig, else the physical camera traced through the exact mirror.

Raster coordinates are continuous: pixel (i, j) covers [i, i+1) × [j, j+1), its centre is
(i + 0.5, j + 0.5); u right, v down. Points and rays are in the rig's viewpoint frame (origin at
the mirror's design point, robot axes: x forward, y left, z up, turned by the rig's tilt_deg), or
in the world frame when a robot pose (x, y, yaw_deg) is given.)")
      .def(py::init([](const RigSpec& rig, bool traced) { return PyCamera{makeCamera(rig, traced)}; }), py::arg("rig"),
           py::arg("traced") = false, "traced: the physical camera even for the ideal rig.")
      .def("project", &project, py::arg("points"), py::arg("pose") = py::none(), py::arg("velocity") = py::none(),
           "points (N, 3) → raster points (N, 2) float64, NaN where not imaged. With a pose, world points; with a "
           "velocity too, each point where the frame images it: at the time of the readout line that sees it "
           "(docs/motion.md), as the frame's landmarks are projected. The GIL is released.")
      .def("rays", &rays, py::arg("pixels"), py::arg("pose") = py::none(), py::arg("velocity") = py::none(),
           py::arg("time") = 0.0,
           "raster points (N, 2) → (origins (N, 3), unit directions (N, 3)), NaN where nothing is imaged. With a "
           "pose, in the world; with a velocity (vx, vy, yaw_rate_deg_per_s; docs/motion.md) too, `time` seconds "
           "after the exposure start: one number, or one per pixel (pixel_times(pixels): the instants a rolling "
           "shutter's AOVs are taken at).")
      .def("pixel_times", &pixelTimes, py::arg("pixels"),
           "raster points (N, 2) → seconds (N,) after the exposure start: mid-exposure of each pixel's readout line, "
           "the instant the frame's depth, instance, normal and landmarks are taken at there; NaN off the image.")
      .def("images", &images, py::arg("pixels"), "raster points (N, 2) → bool (N,): inside the mirror's rim.")
      .def("describe", [](const PyCamera& c) { return toPython(c.camera->describe()); },
           "The camera model as sidecars and intrinsics files state it (dict).")
      .def_property_readonly("model", [](const PyCamera& c) { return std::string(c.camera->model()); },
                             "The camera model's name, as describe() states it.")
      .def_property_readonly("central", [](const PyCamera& c) { return c.camera->central(); },
                             "Whether every ray starts at one viewpoint (False: a misaligned or non-central rig).")
      .def_property_readonly("width", [](const PyCamera& c) { return c.camera->width(); }, "Image width, pixels.")
      .def_property_readonly("height", [](const PyCamera& c) { return c.camera->height(); }, "Image height, pixels.")
      .def_property_readonly("rig", [](const PyCamera& c) { return c.camera->rig(); }, "The rig this camera images (a copy).")
      .def("__repr__", [](const PyCamera& c) {
        return "<omnicam.Camera " + std::string(c.camera->model()) + " " + std::to_string(c.camera->width()) + "x" +
               std::to_string(c.camera->height()) + ">";
      });
}

}  // namespace omnicam::python
