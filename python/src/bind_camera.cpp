// omnicam.Camera: the camera interface (camera/camera.h), vectorised over numpy arrays.
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <memory>

#include "bindings.h"
#include "errors.h"
#include "input_limits.h"
#include "number_format.h"
#include "make_camera.h"
#include "placement.h"
#include "render_settings.h"

namespace omnicam::python {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct PyCamera {
  std::shared_ptr<const Camera> camera;
};

// An (N, k) array-like's rows (a numpy array of any number type, nested lists, …) as float64;
// InputError naming `what` for anything else.
py::array_t<double, py::array::c_style | py::array::forcecast> rowsOf(const py::object& a, int k, const std::string& what) {
  auto rows = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!rows) PyErr_Clear();
  if (!rows || rows.ndim() != 2 || rows.shape(1) != k)
    throw InputError(what + ": must be an array of shape (N, " + std::to_string(k) + ")");
  return rows;
}

// Viewpoint frame from world frame at `pose` (the exposure start), `seconds` later with the robot
// driving at `velocity`; the identity without a pose.
Rigid viewpointFrom(const Camera& camera, const py::object& pose, const py::object& velocity = py::none(),
                    double seconds = 0.0) {
  if (pose.is_none()) {
    if (!velocity.is_none()) throw InputError("velocity: needs a pose (the robot's at the exposure start)");
    if (seconds != 0.0) throw InputError("time: needs a pose (rays without one are in the viewpoint frame, at no time)");
    return Rigid::Identity();
  }
  const CameraPlacement placement(poseFrom(pose, "pose"), velocity.is_none() ? BodyVelocity{} : velocityFrom(velocity, "velocity"));
  checkPlacement(placement);
  return placement.worldFromViewpoint(camera.rig(), seconds).inverse();
}

py::array_t<double> project(const PyCamera& self, const py::object& points, const py::object& pose) {
  const auto in = rowsOf(points, 3, "points");
  const Rigid viewpointFromInput = viewpointFrom(*self.camera, pose);
  const auto n = static_cast<size_t>(in.shape(0));
  std::vector<double> out(2 * n);
  const double* p = in.data();
  {
    py::gil_scoped_release release;
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      const auto q = self.camera->project(viewpointFromInput * Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]));
      out[2 * i] = q ? q->x() : kNaN;
      out[2 * i + 1] = q ? q->y() : kNaN;
    });
  }
  return arrayTakingOver(std::move(out), {static_cast<py::ssize_t>(n), 2});
}

py::tuple rays(const PyCamera& self, const py::object& pixels, const py::object& pose, const py::object& velocity, double time) {
  const auto in = rowsOf(pixels, 2, "pixels");
  // Times within an exposure (and as far before it): the motion model holds a velocity that long.
  if (!(std::abs(time) <= limits::kMaxExposureS))
    throw InputError("time: must be within ±" + shortNumber(limits::kMaxExposureS) + " s of the exposure start (got " +
                     roundTrip(time) + ")");
  const Rigid outputFromViewpoint = viewpointFrom(*self.camera, pose, velocity, time).inverse();
  const auto n = static_cast<size_t>(in.shape(0));
  std::vector<double> origins(3 * n), directions(3 * n);
  const double* p = in.data();
  {
    py::gil_scoped_release release;
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      const auto ray = self.camera->generateRay({Vec2(p[2 * i], p[2 * i + 1])});
      const Vec3 o = ray ? Vec3(outputFromViewpoint * ray->origin) : Vec3::Constant(kNaN);
      const Vec3 d = ray ? Vec3(outputFromViewpoint.linear() * ray->direction) : Vec3::Constant(kNaN);
      for (int k = 0; k < 3; ++k) origins[3 * i + k] = o[k], directions[3 * i + k] = d[k];
    });
  }
  const auto shape = std::vector<py::ssize_t>{static_cast<py::ssize_t>(n), 3};
  return py::make_tuple(arrayTakingOver(std::move(origins), shape), arrayTakingOver(std::move(directions), shape));
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
      .def("project", &project, py::arg("points"), py::arg("pose") = py::none(),
           "points (N, 3) → raster points (N, 2) float64, NaN where not imaged. The GIL is released.")
      .def("rays", &rays, py::arg("pixels"), py::arg("pose") = py::none(), py::arg("velocity") = py::none(),
           py::arg("time") = 0.0,
           "raster points (N, 2) → (origins (N, 3), unit directions (N, 3)), NaN where nothing is imaged. With a "
           "pose, in the world: `time` seconds after the exposure start, the robot driving from `pose` at `velocity` "
           "(vx, vy, yaw_rate_deg_per_s; docs/motion.md), still without one.")
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
