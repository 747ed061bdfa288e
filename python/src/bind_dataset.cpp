// omnicam.run_dataset and the readers the Python Dataset class (omnicam/dataset.py) builds on.
#include <pybind11/stl/filesystem.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <set>
#include <type_traits>

#include "bindings.h"
#include "input_limits.h"
#include "coco.h"
#include "dataset_folder.h"
#include "dataset_reader.h"
#include "dataset_runner.h"
#include "dataset_spec.h"
#include "exr_channels.h"
#include "image.h"
#include "recording_camera_spec.h"
#include "scene_ids.h"

namespace omnicam::python {

namespace {

// Runs a dataset spec with the GIL released; `progress(done, total)` is called with the GIL when
// the run starts (the frames kept) and after every frame. An exception in it (Ctrl-C's KeyboardInterrupt too) stops the run once the frames
// in progress are written (the fast engine renders a window of 8 at once, Blender a batch) and is
// raised again once the run has stopped.
py::dict runDatasetFromPython(const PyPath& specPath, const PyPath& out, bool overwrite, const PyInteger& threadsArg,
                              const std::optional<py::function>& progress, bool allowOutsideFiles) {
  const int threads = narrowed(threadsArg, "threads", 0, limits::kMaxThreads);
  DatasetSpec spec = loadDatasetSpec(specPath.value.string());
  spec.allowOutsideFiles = allowOutsideFiles;  // the caller's word, never the spec's (as the CLI's flag)
  DatasetRunOptions options;
  options.dir = out.value.string();
  options.overwrite = overwrite;
  options.threads = threads;
  std::atomic<bool> stop{false};
  std::optional<py::error_already_set> raised;
  options.stopRequested = &stop;
  const auto report = [&](int done, int total) {
    py::gil_scoped_acquire acquire;
    if (raised) return;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (progress) (*progress)(done, total);
    } catch (py::error_already_set& e) {
      raised.emplace(std::move(e));
      stop = true;
    }
  };
  int reported = 0;
  options.onStart = [&](int kept, int total) { report(reported = kept, total); };
  // Python's progress is called for every frame, a window's one after another as they are listed.
  options.onFrame = [&](int done, int total) {
    while (reported < done) report(++reported, total);
  };
  DatasetRunResult result;
  try {
    py::gil_scoped_release release;
    result = runDataset(spec, options);
  } catch (const OtherDatasetError& e) {
    throw InputError(std::string(e.what()) + ": overwrite=True replaces it, or give another folder");
  } catch (...) {
    if (raised) throw std::move(*raised);  // the callback's exception first: it caused the stop
    throw;
  }
  if (raised) throw std::move(*raised);
  py::dict d;
  d["frames"] = result.frames;
  d["kept"] = result.kept;
  d["rendered"] = result.rendered;
  d["stopped"] = result.stopped;
  d["notes"] = result.notes;
  return d;
}

py::object poseTuple(const RobotPose& p) { return py::make_tuple(p.x, p.y, p.yawDeg); }

// A decoded frame file as numpy (rgb (H, W, 4) float32, depth (H, W) float32, normal (H, W, 3)
// float32, instance/semantic (H, W) uint16) or a dict (landmarks); the arrays take over the
// decoded buffers.
py::object outputToPython(DecodedOutput&& out) {
  const py::ssize_t h = out.height, w = out.width;
  if (out.image) return arrayTakingOver(std::move(out.image->pixels), {h, w, 4});
  if (out.data) {
    if (out.data->channels == 1) return arrayTakingOver(std::move(out.data->values), {h, w});
    return arrayTakingOver(std::move(out.data->values), {h, w, static_cast<py::ssize_t>(out.data->channels)});
  }
  if (!out.json.is_null()) return toPython(out.json);
  return arrayTakingOver(std::move(out.ids), {h, w});
}

void bindDatasetReader(py::module_& m) {
  // The outputs a frame may hold, from the one table of output kinds (outputs/output_kinds.h).
  py::list outputNames;
  for (OutputKind kind : allOutputKinds())
    if (kind != OutputKind::Multilayer) outputNames.append(outputName(kind));
  m.attr("OUTPUTS") = py::tuple(outputNames);
  py::class_<DatasetReader>(m, "_DatasetReader", "The C++ reader behind omnicam.Dataset (dataset/dataset_reader.h).")
      .def(py::init([](const PyPath& path) { return DatasetReader(path.value.string()); }), py::arg("path"))
      .def_property_readonly("header", [](const DatasetReader& r) { return toPython(r.manifest().header); })
      .def_property_readonly("cameras", &DatasetReader::cameras)
      .def_property_readonly("frames", &DatasetReader::frames)
      .def("frame", [](const DatasetReader& r, int index) {
        const FrameRecord& f = r.frame(index);
        // A recording camera that draws nothing is the spec's in every frame: its values, as a drawn
        // one's are (the manifest records per frame only what was drawn).
        std::optional<nlohmann::json> fixedRecording;
        const nlohmann::json& header = r.manifest().header;
        if (header.contains("spec") && header["spec"].is_object() && header["spec"].contains("recording")) {
          const RecordingCameraSpec spec = recordingCameraSpecFromJson(header["spec"]["recording"], r.dir() + "/manifest.json", "spec.recording");
          if (!spec.randomised()) fixedRecording = recordingCameraToJson(spec.draw(0));
        }
        py::dict cameras;
        for (const auto& [name, camera] : f.cameras) {
          py::dict files;
          for (const auto& [kind, file] : camera.files) files[py::str(kind)] = file.path;
          py::dict entry(py::arg("pose") = poseTuple(camera.pose), py::arg("files") = files);
          if (camera.rig) entry["rig"] = py::cast(*camera.rig);  // a vibrating robot's frame rig
          if (camera.recording) entry["recording"] = toPython(recordingCameraToJson(*camera.recording));  // drawn values
          else if (fixedRecording) entry["recording"] = toPython(*fixedRecording);
          cameras[py::str(name)] = entry;
        }
        const BodyVelocity& v = f.velocity;
        return py::dict(py::arg("index") = f.index, py::arg("timestamp") = f.timestamp,
                        py::arg("robot_pose") = poseTuple(f.robot), py::arg("cameras") = cameras,
                        py::arg("velocity") = py::make_tuple(v.vx, v.vy, v.yawRateDegPerS),
                        py::arg("robot_tilt_deg") = py::make_tuple(f.robotTiltDeg[0], f.robotTiltDeg[1]));
      }, py::arg("index"))
      .def("read", [](const DatasetReader& r, int index, const std::string& camera, const std::vector<std::string>& names,
                      bool checkHash) {
        std::vector<OutputKind> kinds;
        for (const std::string& name : names) {
          const auto kind = outputNamed(name);
          if (!kind || *kind == OutputKind::Multilayer) throw InputError("no output " + quote(name));
          kinds.push_back(*kind);
        }
        std::map<OutputKind, DecodedOutput> outputs;
        {
          py::gil_scoped_release release;
          outputs = r.readOutputs(index, camera, kinds, checkHash);
        }
        py::dict out;
        for (auto& [kind, decoded] : outputs) out[py::str(outputName(kind))] = outputToPython(std::move(decoded));
        return out;
      }, py::arg("index"), py::arg("camera"), py::arg("outputs"), py::arg("check_hash") = false,
      "Frame `index`'s outputs of `camera` by name, each file read once whatever the layout.")
      .def("camera_file", [](const DatasetReader& r, const std::string& camera, const std::string& kind, bool checkHash) {
        return py::bytes(r.fileBytes(std::nullopt, camera, kind, checkHash));
      }, py::arg("camera"), py::arg("kind"), py::arg("check_hash") = false);

  m.def("verify_dataset", [](const PyPath& path) {
    DatasetVerifyResult result;
    {
      py::gil_scoped_release release;
      result = verifyDataset(path.value.string());
    }
    return py::dict(py::arg("files") = result.files, py::arg("problems") = result.problems, py::arg("ok") = result.ok());
  }, py::arg("path"), "Re-hashes every file the dataset's manifest lists: {\"files\", \"problems\", \"ok\"}.");
}

// The class ids `classes` names: None (the default classes), or names and ids of the scene's
// classes; InputError for one it does not have.
std::set<uint16_t> chosenCocoClasses(const IdTables& tables, const py::object& classes) {
  if (classes.is_none()) return defaultCocoClasses(tables);
  if (py::isinstance<py::str>(classes)) throw InputError("classes: must be a list of class names or ids, not one string");
  std::vector<std::string> names;
  std::set<uint16_t> chosen;
  for (const py::handle item : classes) {
    if (py::isinstance<py::str>(item)) {
      names.push_back(item.cast<std::string>());
      continue;
    }
    if (!PyIndex_Check(item.ptr()))
      throw InputError("classes: each must be a class name or id (got " + std::string(py::str(py::type::of(item).attr("__name__"))) + ")");
    const int64_t id = narrowed(item.cast<PyInteger>(), "classes", 0, 65535);
    if (id == 0 || static_cast<size_t>(id) >= tables.classes.size())
      throw InputError("classes: " + std::to_string(id) + " is not a class id of the scene (its ids: 1 to " +
                       std::to_string(tables.classes.size() - 1) + ")");
    chosen.insert(static_cast<uint16_t>(id));
  }
  const std::set<uint16_t> named = cocoClassIds(tables, names, "classes");
  chosen.insert(named.begin(), named.end());
  return chosen;
}

}  // namespace

namespace {

// read_exr_channels: the channels as their file stores them, float32 or uint32 (ids read as
// floats would be scaled by 2^-32, as OpenImageIO reads them).
py::array readExrChannelsToPython(const PyPath& path, const std::vector<std::string>& channels) {
  if (channels.empty()) throw InputError("read_exr_channels: name at least one channel");
  ExrChannels decoded = readExrChannelsExactly(path.value.string(), channels);
  const size_t uints = static_cast<size_t>(std::count_if(channels.begin(), channels.end(),
                                                          [&](const std::string& c) { return decoded.uints.count(c) > 0; }));
  if (uints != 0 && uints != channels.size())
    throw InputError(showPath(path.value.string()) + ": channels of two kinds (uint32 ids and floats): read them apart");
  const py::ssize_t h = decoded.height, w = decoded.width, n = static_cast<py::ssize_t>(channels.size());
  const size_t pixels = static_cast<size_t>(h) * static_cast<size_t>(w);
  const auto interleave = [&](auto& planes, auto zero) {
    std::vector<decltype(zero)> values(pixels * channels.size());
    for (size_t c = 0; c < channels.size(); ++c) {
      const auto& plane = planes.at(channels[c]);
      for (size_t p = 0; p < pixels; ++p) values[p * channels.size() + c] = plane[p];
    }
    return arrayTakingOver(std::move(values), {h, w, n});
  };
  return uints ? py::array(interleave(decoded.uints, uint32_t{0})) : py::array(interleave(decoded.floats, 0.0f));
}

// An instance plane's ids as given, of any integer dtype (uint16 from a PNG, uint32 from an EXR):
// never converted from floats or bools, nor wrapped. An id the scene does not have is another
// scene's image: refused, not annotated as nothing.
template <class Id>
std::vector<uint16_t> idsOf(const py::array& instance, size_t instances) {
  const auto values = py::array_t<Id, py::array::c_style | py::array::forcecast>::ensure(instance);
  std::vector<uint16_t> ids(static_cast<size_t>(values.size()));
  for (size_t k = 0; k < ids.size(); ++k) {
    const Id id = values.data()[k];
    bool negative = false;
    if constexpr (std::is_signed_v<Id>) negative = id < 0;
    if (negative || static_cast<uint64_t>(id) >= instances)
      throw InputError("instance: id " + std::to_string(id) + " is not an instance of the scene (its ids: 0 to " +
                       std::to_string(instances - 1) + ")");
    ids[k] = static_cast<uint16_t>(id);
  }
  return ids;
}

std::vector<uint16_t> instanceIds(const py::array& instance, size_t instances) {
  const char kind = instance.dtype().kind();
  if (kind == 'u') return idsOf<uint64_t>(instance, instances);
  if (kind == 'i') return idsOf<int64_t>(instance, instances);
  throw InputError("instance: must hold integer ids, as the instance plane does (got an array of dtype " +
                   py::str(instance.dtype()).cast<std::string>() + ")");
}

}  // namespace

void bindDataset(py::module_& m) {
  bindDatasetReader(m);
  m.def("coco_annotations", [](const py::object& given, const Scene& scene, const py::object& classes) {
    const py::array instance = py::array::ensure(given);  // any array-like: a list of lists too
    if (!instance || instance.ndim() != 2) throw InputError("instance: must be an array of shape (H, W)");
    const int h = static_cast<int>(instance.shape(0)), w = static_cast<int>(instance.shape(1));
    const IdTables tables = idTables(scene);
    const std::vector<uint16_t> ids = instanceIds(instance, tables.classOfInstance.size());
    return toPython(cocoInstanceAnnotations(ids, w, h, tables.classOfInstance, chosenCocoClasses(tables, classes)));
  }, py::arg("instance"), py::arg("scene"), py::arg("classes") = py::none(),
  R"(COCO annotations of one frame's instance ids (H, W), of any integer dtype, of `scene`: one per visible instance of
the chosen classes, given by name (as a spec's outputs.coco.classes) or class id (default: every
class but floor, wall, ceiling and line) with "instance_id", "category_id", "bbox" [x, y, w, h],
"area", "segmentation" (COCO compressed RLE) and "iscrowd". InputError for a class or instance id
the scene does not have.)");
  m.def("run_dataset", &runDatasetFromPython, py::arg("spec"), py::arg("out"), py::kw_only(), py::arg("overwrite") = false,
        py::arg("threads") = 0, py::arg("progress") = py::none(), py::arg("allow_outside_files") = false,
        R"(Renders the dataset a spec file describes into the folder `out`, as `omnicam dataset` does
(docs/dataset-format.md): resumes a partial run, keeps verified frames. progress(done, total) is
called when the run starts (done: the frames kept) and after every frame; an exception in it stops the run once the frames in progress (up to 8
at once) are written, and is raised again. allow_outside_files lets the scene read files outside its folder (the
CLI's --allow-outside-files; a spec cannot ask for it). Returns {"frames", "kept", "rendered", "stopped", "notes"}.)");

  m.def("read_image", [](const PyPath& path) {
    ImageRGBA image = readImage(path.value.string());
    const py::ssize_t h = image.height, w = image.width;
    return arrayTakingOver(std::move(image.pixels), {h, w, 4});
  }, py::arg("path"), "Any image file as linear, premultiplied RGBA float32 (H, W, 4).");
  m.def("read_exr_channels", &readExrChannelsToPython, py::arg("path"), py::arg("channels"),
        "The named channels of an OpenEXR, exactly, (H, W, len(channels)): float32 for half and float "
        "channels (depth, normals, rays, colour), uint32 for uint ones (instance and class ids). "
        "InputError for a channel the file lacks (naming those it has) and for channels of both kinds "
        "at once (read them apart).");
  m.def("srgb8", [](const py::array_t<float, py::array::c_style | py::array::forcecast>& rgba) {
    if (rgba.ndim() != 3 || rgba.shape(2) != 4) throw InputError("srgb8: the image must be (H, W, 4) RGBA");
    ImageRGBA image(static_cast<int>(rgba.shape(1)), static_cast<int>(rgba.shape(0)));
    std::copy(rgba.data(), rgba.data() + image.pixels.size(), image.pixels.begin());
    std::vector<unsigned char> codes = srgb8Codes(image);
    return arrayTakingOver(std::move(codes), {rgba.shape(0), rgba.shape(1), 4});
  }, py::arg("rgba"),
        "A frame's colour (linear, premultiplied RGBA float32, (H, W, 4)) as the 8-bit sRGB codes a PNG of it "
        "holds (straight alpha, uint8 (H, W, 4)): omnicam's own encoding, for ROS images and the like.");
  m.def("read_uint16_png", [](const PyPath& path) {
    int w = 0, h = 0;
    std::vector<uint16_t> values = readUint16Png(path.value.string(), w, h);
    return arrayTakingOver(std::move(values), {h, w});
  }, py::arg("path"), "A 16-bit single-channel PNG (instance and class ids) as uint16 (H, W).");
}

}  // namespace omnicam::python
