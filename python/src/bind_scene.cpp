// omnicam.load_scene, omnicam.Scene and omnicam.Rig.
#include <pybind11/stl/filesystem.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include <functional>
#include <memory>

#include "bindings.h"
#include "data_files.h"
#include "errors.h"
#include "input_limits.h"
#include "mapping_arena.h"
#include "scene_ids.h"
#include "scene_loader.h"
#include "sidecar.h"

namespace omnicam::python {

namespace {

using json = nlohmann::json;

// Every change to a rig goes through the scene format's own reader: the same checks and the same
// one-line messages as a scene file ("omnicam.Rig: rig.camera.offset_mm: …").
RigSpec rigFromDict(const json& j) { return rigFromJson(j, "omnicam.Rig", "rig"); }

RigSpec edited(const RigSpec& rig, const std::function<void(json&)>& edit) {
  json j = rigToJson(rig);
  edit(j);
  // Another mirror shape frames its image by its rim: the hyperboloid's framing goes with it.
  // (find, not operator[]: a lens rig has no mirror, and operator[] would add a null one)
  const auto mirror = j.find("mirror");
  const auto image = j.find("image");
  if (mirror != j.end() && mirror->is_object() && mirror->contains("shape") && (*mirror)["shape"] != "hyperboloid" &&
      image != j.end() && image->is_object())
    image->erase("framing_elevation_deg");
  return rigFromDict(j);
}

// A read/write property of the rig at a JSON path of the scene format's "rig" block.
void rigProperty(py::class_<RigSpec>& rig, const char* name, std::vector<std::string> path, const char* doc) {
  rig.def_property(
      name,
      [path](const RigSpec& r) {
        json j = rigToJson(r);
        for (const std::string& key : path) {
          if (!j.contains(key)) return toPython(json());
          j = j[key];
        }
        return toPython(j);
      },
      [path](RigSpec& r, const py::object& value) {
        // None puts the default back: the field is left out of the block.
        const json v = value.is_none() ? json() : fromPython(value, "omnicam.Rig: " + path.back());
        r = edited(r, [&](json& j) {
          json* at = &j;
          for (size_t k = 0; k + 1 < path.size(); ++k) at = &(*at)[path[k]];
          if (v.is_null()) {
            if (at->is_object()) at->erase(path.back());
          } else {
            (*at)[path.back()] = v;
          }
        });
      },
      doc);
}

void bindRig(py::module_& m) {
  py::class_<RigSpec> rig(m, "Rig", R"(The camera rig: mirror, camera as mounted, image (docs/scene-format.md, "rig").

Rig() (or Rig(None)) is the ideal rig; Rig(dict) reads the scene format's "rig" block strictly. Every property
set is checked the same way: a bad value raises omnicam.InputError and leaves the rig unchanged.)");
  rig.def(py::init([](const std::optional<py::dict>& d) { return d ? rigFromDict(fromPython(*d, "omnicam.Rig")) : RigSpec{}; }),
          py::arg("rig") = py::none(), "rig: the scene format's \"rig\" block (dict), or None for the ideal rig.")
      .def("to_dict", [](const RigSpec& r) { return toPython(rigToJson(r)); }, "The rig as the scene format's \"rig\" block.")
      .def("resized", [](const RigSpec& r, const PyInteger& size) {
             return r.resized(narrowed(size, "image size", limits::kMinImageSize, limits::kMaxImageSize));
           }, py::arg("size"), "The same rig imaging size × size pixels (a lens camera: size wide, keeping its aspect).")
      .def_property_readonly("ideal", &RigSpec::ideal, "The ideal hyperboloid rig, whose camera is the closed-form (Mei) model.")
      .def_property_readonly("shape", [](const RigSpec& r) {
             return std::visit(Overloaded{[](const MirrorRig& mirror) -> py::object { return py::str(mirrorShapeName(mirror.shape)); },
                                         [](const LensCameraSpec&) -> py::object { return py::none(); }},
                               r.kind);
           }, "The mirror shape: hyperboloid, paraboloid, sphere or cone; None for a lens camera.")
      .def_property_readonly("lens", [](const RigSpec& r) {
             return std::visit(Overloaded{[](const MirrorRig&) -> py::object { return py::none(); },
                                          [&](const LensCameraSpec&) -> py::object { return toPython(rigToJson(r)["lens"]); }},
                               r.kind);
           }, "A lens camera's \"lens\" block (docs/lens-cameras.md), or None for a mirror rig.")
      .def(py::self == py::self)
      // Pickled as its "rig" block, read back strictly: a Dataset item (which holds its frame's rig)
      // travels from a DataLoader worker to the main process.
      .def(py::pickle([](const RigSpec& r) { return py::dict(toPython(rigToJson(r))); },
                      [](const py::dict& state) { return rigFromDict(fromPython(state, "omnicam.Rig")); }))
      .def("__repr__", [](const RigSpec& r) { return "omnicam.Rig(" + rigToJson(r).dump() + ")"; });
  rigProperty(rig, "height", {"height"}, "The design point's height above the floor, metres.");
  rigProperty(rig, "image_size", {"image", "size"}, "Image width and height, pixels (None for a lens camera: see lens).");
  rigProperty(rig, "mirror", {"mirror"}, "The mirror block: shape and its parameters (dict; None for a lens camera).");
  rigProperty(rig, "camera_offset_mm", {"camera", "offset_mm"}, "The pinhole minus its ideal position, robot axes, mm.");
  rigProperty(rig, "camera_rotation_deg", {"camera", "rotation_deg"}, "The camera turned about its pinhole, degrees.");
  rigProperty(rig, "distortion", {"camera", "distortion"}, "OpenCV radial-tangential lens distortion {k1, k2, p1, p2, k3}.");
  rigProperty(rig, "principal_point_offset_px", {"camera", "principal_point_offset_px"}, "Principal point offset, pixels.");
  rigProperty(rig, "tilt_deg", {"tilt_deg"}, "The whole rig tilted on the robot: [roll, pitch], degrees (None: level).");
  rigProperty(rig, "shutter", {"shutter"},
              "The shutter (docs/motion.md): {exposure_s, rolling: {line_time_us, readout}, time_samples} (None: an instant).");
}

}  // namespace

void bindScene(py::module_& m) {
  bindRig(m);

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", "A loaded scene file (docs/scene-format.md).")
      .def_property_readonly("path", [](const Scene& s) { return s.path; }, "The scene file it was loaded from.")
      .def_property_readonly("name", [](const Scene& s) { return s.name; }, "The scene's name: its file's name without .json.")
      .def_property_readonly("sha256", [](const Scene& s) { return s.sha256; }, "The SHA-256 of the scene file's bytes (hex), as manifests record it.")
      .def_property_readonly(
          "inputs",
          [](const Scene& s) {
            py::list inputs;
            for (const SceneInputFile& input : s.inputDigests) inputs.append(py::make_tuple(input.path, input.sha256));
            return inputs;
          },
          "The files the scene reads beyond its own text (textures, environment map, glTF files), as (path from the "
          "scene's folder, SHA-256), by path, as manifests and sidecars record them.")
      .def_property("rig", [](const Scene& s) { return s.rig; }, [](Scene& s, const RigSpec& r) { s.rig = r; },
                    "The scene's rig (a copy: change it and assign it back, or pass it to a render).")
      .def_property_readonly("start_pose", [](const Scene& s) { return py::make_tuple(s.startPose.x, s.startPose.y, s.startPose.yawDeg); },
                             "The robot pose renders take by default: (x, y, yaw_deg).")
      .def_property_readonly("objects", [](const Scene& s) {
        std::vector<std::string> names;
        for (const SceneObject& o : s.objects) names.push_back(o.name);
        return names;
      }, "Object names; object i has instance id i + 1.")
      .def_property_readonly("ids", [](const Scene& s) {
        const IdTables ids = idTables(s);
        return toPython({{"classes", ids.classes}, {"instances", ids.instances}});
      }, "The instance and class ids of the AOVs: {\"classes\": [{id, name}], \"instances\": [{id, name, class, class_id}]}.")
      .def_property_readonly("paths", [](const Scene& s) {
        py::dict paths;
        for (const CameraPath& p : s.paths) {
          py::list poses;
          for (const RobotPose& q : p.poses) poses.append(py::make_tuple(q.x, q.y, q.yawDeg));
          paths[py::str(p.name)] = poses;
        }
        return paths;
      }, "The scene's named camera paths: {name: [(x, y, yaw_deg), …]}.")
      .def("__repr__", [](const Scene& s) { return "<omnicam.Scene " + json(s.name).dump() + " from " + json(s.path).dump() + ">"; });

  m.def("mapping_arena", [](const PyInteger& seed, const PyInteger& victims, const PyInteger& debris) {
    MappingOptions options;
    options.seed = narrowedSeed(seed, "seed");
    options.victims = narrowed(victims, "victims", 0, 1598);
    options.debris = narrowed(debris, "debris", 0, 16000);
    return toPython(generateMappingArena(options).scene);
  }, py::arg("seed") = 1, py::arg("victims") = 4, py::arg("debris") = 14,
  R"(The rescue maze of `omnicam arena mapping` (RoboCup Rescue's mapping arena: walls, ramps,
debris, victims as landmarks) as a scene file's content (dict): write it with json.dump and load it.)");

  m.def("data_path", [](const std::string& relative) {
    if (relative.find('\0') != std::string::npos) throw InputError("data_path: " + quote(relative) + ": a file name cannot hold a NUL character");
    const std::filesystem::path wanted(relative);
    for (const auto& part : wanted)
      if (wanted.is_absolute() || part == "..") throw InputError("data_path: " + quote(relative) + " must be a path inside omnicam's files");
    const std::filesystem::path file = relative.empty() ? dataRoot() : dataFile(relative);
    std::error_code ec;
    if (!std::filesystem::exists(file, ec))
      throw InputError("data_path: " + quote(relative) + " is not among omnicam's files (scenes/ holds the scenes it comes with)");
    return file;
  }, py::arg("relative") = "",
        R"(The files omnicam comes with (scenes/, docs/examples/ (the docs' specs), examples/recording/ (test
cameras), ...), in a build tree or an installed package:
data_path() is their folder, data_path("scenes/robocup2006.json") one of them. omnicam.InputError
for a name that is not among them.)");
  m.def("load_scene", [](const PyPath& path, bool allowOutsideFiles) {
    SceneLoadOptions options;
    options.allowOutsideFolder = allowOutsideFiles;
    return std::make_shared<Scene>(loadScene(path.value.string(), options));
  }, py::arg("path"), py::arg("allow_outside_files") = false,
        R"(Loads and checks a scene file. Anything wrong raises omnicam.InputError with one line
"<file>: <field>: <what is wrong>". Files the scene pulls in must lie inside its folder unless
allow_outside_files.)");
}

}  // namespace omnicam::python
