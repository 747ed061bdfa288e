// omnicam.Renderer and omnicam.render: images and AOVs as numpy arrays.
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <set>

#include <tbb/task_arena.h>

#include "bindings.h"
#include "input_limits.h"
#include "engines.h"
#include "frame_planes.h"
#include "output_kinds.h"
#include "recording_camera_spec.h"
#include "errors.h"
#include "scene_ids.h"

namespace omnicam::python {

namespace {

// An optional integer as the request reads it (its range is the request's rule, not Python's).
std::optional<int64_t> wideInteger(const std::optional<PyInteger>& value, const std::string& name) {
  if (!value) return std::nullopt;
  if (!value->fitsInt64) {  // beyond any setting's range: say the setting's range, as for any value out of it
    std::string range = "a 64-bit integer";
    for (const RequestFieldRow& row : requestFieldRows())
      if (row.python && name == row.python) range = "an integer in " + row.range;
    throw InputError(name + ": must be " + range + " (got " + shownInteger(value->text) + ")");
  }
  return value->value;
}

// size=: 0 for the rig's own, else an image size in [8, 16384].
int optionalSize(const PyInteger& size) {
  return size.fitsInt64 && size.value == 0 ? 0 : narrowed(size, "size", limits::kMinImageSize, limits::kMaxImageSize);
}

// The image outputs a render returns, named as datasets name them (output_kinds.h); the old names
// "rgba" and "class" are refused with the new ones.
std::vector<OutputKind> imageOutputs(const std::vector<std::string>& names) {
  std::string choices;
  for (OutputKind kind : allOutputKinds())
    if (!isAnnotation(kind) && outputRow(kind).plane != OutputPlane::Frame)
      choices += (choices.empty() ? "" : ", ") + std::string(outputName(kind));
  if (names.empty()) throw InputError("outputs: name at least one of " + choices);  // else an empty dict, silently
  std::vector<OutputKind> kinds;
  for (const std::string& name : names) {
    const auto kind = outputNamed(name);
    if (name == "rgba" || name == "class")
      throw InputError("outputs: " + quote(name) + " is now " + (name == "rgba" ? "\"rgb\" (H, W, 4)" : "\"semantic\"") +
                       ", as datasets name it");
    if (!kind || isAnnotation(*kind) || outputRow(*kind).plane == OutputPlane::Frame)
      throw InputError("outputs: " + quote(name) + " is not one of " + choices);
    if (std::find(kinds.begin(), kinds.end(), *kind) == kinds.end()) kinds.push_back(*kind);
  }
  return kinds;
}

// One engine for one scene, reused render after render (the fast engine builds its ray-tracing
// scene once). Renders of engines that may run concurrently run so, the GIL released; the others
// take turns.
class PyRenderer {
 public:
  // The engine's part of the render request (render_request.h); spp, shading and traced come
  // with each render.
  PyRenderer(std::shared_ptr<const Scene> scene, const RequestFields& engineFields)
      : scene_(std::move(scene)), ids_(idTables(*scene_)), engineFields_(engineFields) {
    const RenderRequest request = readRenderRequest(engineFields_, {});
    // threads= caps the fast engine's TBB threads too (a ground truth passes it to its renderer):
    // its own arena, so that other renderers in the process keep theirs.
    if (request.threads > 0) arena_.emplace(request.threads);
    onThreads([&] { engine_ = makeEngine(request, *scene_); });
  }

  py::dict render(const py::object& pose, const std::optional<RigSpec>& rig, const PyInteger& sizeArg,
                  const std::optional<PyInteger>& spp, const std::optional<std::string>& shading, bool traced,
                  const std::vector<std::string>& outputs, const py::object& velocity, const std::optional<PyInteger>& bounces,
                  const std::optional<PyInteger>& seed, bool denoise, const std::optional<PyInteger>& adaptiveSpp,
                  const std::optional<double>& targetError, const py::object& recording, const std::optional<PyInteger>& frameArg) {
    const int size = optionalSize(sizeArg);
    // The recording camera (recording_camera_spec.h): read before rendering, drawn for `frame`.
    std::optional<RecordingCamera> camera;
    // None, not 0, by default: frame=0 without recording= changes nothing, and is refused as any
    // other frame is.
    const uint64_t frame = frameArg ? static_cast<uint64_t>(narrowed(*frameArg, "frame", 0, INT64_MAX)) : 0;
    if (py::isinstance<py::str>(recording))  // a preset's name or a file, as --recording
      camera = recordingCameraSpecFromNameOrFile(recording.cast<std::string>(), "recording").draw(frame);
    else if (py::hasattr(recording, "__fspath__"))  // a path is a file, whatever its name
      camera = recordingCameraSpecFromFile(py::module_::import("os").attr("fspath")(recording).cast<std::string>(), "recording")
                   .draw(frame);
    else if (!recording.is_none())
      camera = recordingCameraSpecFromJson(fromPython(recording, "recording"), "", "recording").draw(frame);
    else if (frameArg)  // a setting that changes nothing is refused, as a flag would be
      throw InputError("frame: only with recording= (it picks the recording camera drawn for that frame)");
    RequestFields fields = engineFields_;
    fields.setIfGiven(RequestField::Spp, wideInteger(spp, "spp"));
    fields.setIfGiven(RequestField::Shading, shading);
    if (traced) fields.set(RequestField::Traced, true);
    fields.setIfGiven(RequestField::Bounces, wideInteger(bounces, "bounces"));
    fields.setIfGiven(RequestField::Seed, wideInteger(seed, "seed"));
    if (denoise) fields.set(RequestField::Denoise, true);
    fields.setIfGiven(RequestField::AdaptiveSpp, wideInteger(adaptiveSpp, "adaptive_spp"));
    fields.setIfGiven(RequestField::TargetError, targetError);
    const RenderRequest request = readRenderRequest(fields, {});
    RenderSettings settings = request.settings(rig.value_or(scene_->rig));
    if (size) settings.rig = settings.rig.resized(size, "size");
    checkRenderSettings(settings, {"spp", "size"});
    const CameraPlacement placement(pose.is_none() ? scene_->startPose : poseFrom(pose, "pose"),
                                    velocity.is_none() ? BodyVelocity{} : velocityFrom(velocity, "velocity"));
    checkPlacement(placement);
    checkMotionIsSeen(placement, settings.rig, "velocity");
    const std::vector<OutputKind> kinds = imageOutputs(outputs);
    bool aovs = false;
    for (OutputKind kind : kinds) aovs = aovs || needsAovs(kind);
    checkEngineRenders(engine_->kind(), settings.rig, placement);
    // Asked for by `outputs`: its message names the keyword, as every keyword's does.
    if (aovs && !engine_->capabilities().aovs) {
      try {
        checkEngineRenders(engine_->kind(), settings.rig, placement, true);
      } catch (const InputError& e) {
        throw InputError(std::string("outputs: ") + e.what());
      }
    }
    Film film = filmFor(settings, aovs);
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> turn(mutex_, std::defer_lock);
      if (!engine_->capabilities().concurrent) turn.lock();
      onThreads([&] {
        engine_->render(placement, settings, film);
        if (camera) film.setResolvedColour(recordFrame(*camera, film.image(), frame));
      });
    }
    return arrays(film, kinds);
  }

  // The benchmark's reference (bench/python_bench.py): `frames` renders of one pose in a C++ loop,
  // nothing handed to Python; seconds taken.
  double renderRepeatedly(const py::object& pose, const PyInteger& framesArg, const PyInteger& sizeArg, const PyInteger& sppArg) {
    const int frames = narrowed(framesArg, "frames", 0, 1000000), size = optionalSize(sizeArg),
              spp = narrowed(sppArg, "spp", 1, limits::kMaxSpp);
    const RenderRequest request = readRenderRequest({{RequestField::Spp, int64_t{spp}}}, {});
    const RenderSettings settings = request.settings(size ? scene_->rig.resized(size, "size") : scene_->rig);
    checkRenderSettings(settings);
    const RobotPose robot = pose.is_none() ? scene_->startPose : poseFrom(pose, "pose");
    py::gil_scoped_release release;
    std::unique_lock<std::mutex> turn(mutex_, std::defer_lock);
    if (!engine_->capabilities().concurrent) turn.lock();
    const auto start = std::chrono::steady_clock::now();
    onThreads([&] {
      for (int k = 0; k < frames; ++k) engine_->render(robot, settings);
    });
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  const Engine& engine() const { return *engine_; }
  const std::shared_ptr<const Scene>& scene() const { return scene_; }

 private:
  // `work` on the threads= arena, or on TBB's default threads.
  template <class Work>
  void onThreads(const Work& work) {
    if (arena_) arena_->execute(work);
    else work();
  }

  // Each kind's plane as its row says (output_kinds.h): the dataset's names and channels; the
  // colour and the float AOVs hand their buffers over, ids are made as the dataset stores them.
  py::dict arrays(Film& film, const std::vector<OutputKind>& kinds) const {
    const py::ssize_t h = film.height(), w = film.width();
    ImageRGBA rgb = film.takeImage();
    std::optional<AovFrame> aovFrame;
    if (film.wantsAovs()) aovFrame = film.takeAovs();
    AovFrame* aovs = aovFrame ? &*aovFrame : nullptr;
    const FramePlanes planes{rgb, aovs, ids_.classOfInstance};
    py::dict out;
    for (OutputKind kind : kinds) {
      const OutputKindRow& row = outputRow(kind);
      const auto c = static_cast<py::ssize_t>(row.valuesPerPixel());
      std::vector<py::ssize_t> shape = c == 1 ? std::vector<py::ssize_t>{h, w} : std::vector<py::ssize_t>{h, w, c};
      if (row.encoding == OutputEncoding::Uint16Png) {
        out[row.name] = arrayTakingOver(planes.ids(row.plane), shape);
      } else {
        out[row.name] = arrayTakingOver(std::move(floatBuffer(rgb, aovs, row.plane)), shape);
      }
    }
    return out;
  }

  std::shared_ptr<const Scene> scene_;
  IdTables ids_;
  RequestFields engineFields_;
  std::optional<tbb::task_arena> arena_;  // before the engine: it outlives the engine's renders
  std::unique_ptr<Engine> engine_;
  std::mutex mutex_;
};

// The render settings' defaults are their rows' (request_fields.h).
std::string renderDoc() {
  return R"(Renders the scene from a robot pose (x, y, yaw_deg; default the scene's start pose).

rig: another rig (default the scene's); size: the image size (default the rig's); spp: samples
per pixel, a perfect square; shading: "unlit", "lit" or "path" (physically based,
docs/conventions.md §3) with bounces (diffuse bounces, default )" +
         requestFieldRow(RequestField::Bounces).defaultText() + R"(), seed (the random stream) and
denoise (filter the noise); adaptive_spp (path, unfiltered: pixels whose error is above
target_error traced again on finer grids, up to this many samples; docs/path-tracing.md,
"Adaptive sampling"); traced: trace the physical camera even
for the ideal rig; velocity: (vx, vy, yaw_rate_deg_per_s), the robot's body velocity over the
rig's shutter (docs/motion.md; the pose is the exposure start's). outputs, named and shaped as
datasets name and store them: any of "rgb" (H, W, 4) float32 linear, premultiplied alpha;
"depth" (H, W) float32 metres along the viewing ray; "instance" and "semantic" (H, W) uint16 ids
(Scene.ids); "normal" (H, W, 3) float32 world-frame. AOVs (all but rgb) are point-sampled at
pixel centres, fast engine only. recording: what a real camera makes of the colour (AOVs stay
exact): a preset's name ("webcam", "machine_vision", "phone"), a dict in a dataset's
`recording` format (docs/experiments.md) or a JSON file of one (a path, as --recording takes), its distributions drawn for `frame` (None: frame 0; only with recording=) from
its seed, as a dataset draws frame × cameras + camera. Returns a dict
of numpy arrays that own the rendered buffers (no copy). The GIL is released while rendering.
Every setting's default and range: docs/render-settings.md.)";
}

std::string oneRenderDoc() {
  return "One render with a new Renderer (a loop over poses should keep one Renderer instead).\n\n" + renderDoc();
}

}  // namespace

void bindRender(py::module_& m) {
  py::class_<PyRenderer>(m, "Renderer", R"(A renderer of one scene, reused across renders (docs/python.md).

engine: "fast", "povray" or "blender" (ground truths: colour only); mode: "exact", "cubemap" or
"thesis-mesh" (fast engine only) with faces, face_size and polygons; timeout: seconds per
ground-truth frame; threads: 0 for every core. Defaults and ranges: docs/render-settings.md.)")
      .def(py::init([](std::shared_ptr<Scene> scene, const std::optional<std::string>& engine, const std::optional<std::string>& mode,
                       const std::optional<PyInteger>& faces, const std::optional<PyInteger>& faceSize,
                       const std::optional<PyInteger>& polygons, const std::optional<double>& timeout,
                       const std::optional<PyInteger>& threads) {
             RequestFields fields;
             fields.setIfGiven(RequestField::Engine, engine);
             fields.setIfGiven(RequestField::Mode, mode);
             fields.setIfGiven(RequestField::Faces, wideInteger(faces, "faces"));
             fields.setIfGiven(RequestField::FaceSize, wideInteger(faceSize, "face_size"));
             fields.setIfGiven(RequestField::Polygons, wideInteger(polygons, "polygons"));
             fields.setIfGiven(RequestField::Timeout, timeout);
             if (threads) fields.set(RequestField::Threads, int64_t{narrowed(*threads, "threads", 0, limits::kMaxThreads)});
             // The renderer keeps its own copy: changing the Python scene later does not change it.
             return std::make_unique<PyRenderer>(std::make_shared<const Scene>(*scene), fields);
           }),
           py::arg("scene").none(false), py::arg("engine") = py::none(), py::arg("mode") = py::none(),
           py::arg("faces") = py::none(), py::arg("face_size") = py::none(), py::arg("polygons") = py::none(),
           py::arg("timeout") = py::none(), py::arg("threads") = py::none(),
           "Makes the engine for the scene (a copy of it): the class's text says each setting.")
      .def("render", &PyRenderer::render, py::arg("pose") = py::none(), py::kw_only(), py::arg("rig") = py::none(),
           py::arg("size") = 0, py::arg("spp") = py::none(), py::arg("shading") = py::none(), py::arg("traced") = false,
           py::arg("outputs") = std::vector<std::string>{"rgb"}, py::arg("velocity") = py::none(),
           py::arg("bounces") = py::none(), py::arg("seed") = py::none(), py::arg("denoise") = false,
           py::arg("adaptive_spp") = py::none(), py::arg("target_error") = py::none(), py::arg("recording") = py::none(),
           py::arg("frame") = py::none(), renderDoc().c_str())
      .def("_render_repeatedly", &PyRenderer::renderRepeatedly, py::arg("pose"), py::arg("frames"), py::arg("size") = 0,
           py::arg("spp") = 1, "Benchmark reference: seconds for `frames` renders in a C++ loop, nothing returned.")
      .def_property_readonly("engine", [](const PyRenderer& r) { return r.engine().name(); }, "The engine's name: fast, povray or blender.")
      .def_property_readonly("concurrent", [](const PyRenderer& r) { return r.engine().capabilities().concurrent; },
                             "Whether renders from several threads run at once.");

  m.def(
      "_request_fields",
      [] {
        py::list rows;
        for (const RequestFieldRow& row : requestFieldRows()) {
          py::dict d;
          d["python"] = row.python;
          d["place"] = row.pythonPlace == PythonPlace::Renderer ? "Renderer" : row.pythonPlace == PythonPlace::Render ? "render" : "";
          d["cli"] = row.cli ? py::object(py::str(row.cli)) : py::object(py::none());
          d["json"] = row.json ? py::object(py::str(row.json)) : py::object(py::none());
          d["default"] = row.defaultText();
          rows.append(d);
        }
        return rows;
      },
      "The render request's settings as rows (docs/render-settings.md): each keyword's place and names.");
  m.def(
      "render",
      [](std::shared_ptr<Scene> scene, const py::object& pose, const std::optional<std::string>& engine, const std::optional<RigSpec>& rig,
         const PyInteger& size, const std::optional<PyInteger>& spp, const std::optional<std::string>& shading, bool traced,
         const std::vector<std::string>& outputs, const py::object& velocity, const std::optional<PyInteger>& bounces,
         const std::optional<PyInteger>& seed, bool denoise, const std::optional<PyInteger>& adaptiveSpp,
         const std::optional<double>& targetError, const py::object& recording, const std::optional<PyInteger>& frame) {
        RequestFields fields;
        fields.setIfGiven(RequestField::Engine, engine);
        PyRenderer renderer(std::make_shared<const Scene>(*scene), fields);
        return renderer.render(pose, rig, size, spp, shading, traced, outputs, velocity, bounces, seed, denoise, adaptiveSpp,
                               targetError, recording, frame);
      },
      py::arg("scene").none(false), py::arg("pose") = py::none(), py::kw_only(), py::arg("engine") = py::none(), py::arg("rig") = py::none(),
      py::arg("size") = 0, py::arg("spp") = py::none(), py::arg("shading") = py::none(), py::arg("traced") = false,
      py::arg("outputs") = std::vector<std::string>{"rgb"}, py::arg("velocity") = py::none(), py::arg("bounces") = py::none(),
      py::arg("seed") = py::none(), py::arg("denoise") = false, py::arg("adaptive_spp") = py::none(),
      py::arg("target_error") = py::none(), py::arg("recording") = py::none(), py::arg("frame") = py::none(), oneRenderDoc().c_str());
}

}  // namespace omnicam::python
