// The rows of the render request's settings (request_fields.h): here, beside nothing but the
// request whose defaults they show, so the generic machinery (request_fields.cpp) needs no request.
#include "input_limits.h"
#include "number_format.h"
#include "render_request.h"
#include "request_fields.h"

namespace omnicam {

namespace {

using Type = RequestFieldType;
using Request = RenderRequest;

std::string onOff(bool on) { return on ? "on" : "off"; }

std::vector<RequestFieldRow> makeRows() {
  const std::string maxBounces = std::to_string(kMaxBounces), maxSpp = std::to_string(limits::kMaxSpp);
  return {
      {.field = RequestField::Engine, .type = Type::Text, .cli = "--engine", .json = "engine", .python = "engine",
       .pythonPlace = PythonPlace::Renderer, .cliGroup = kEngineFlag, .range = "fast, povray, blender",
       .help = "fast, povray or blender (ground truth)", .shown = [](const Request& r) { return r.engine; }},
      {.field = RequestField::Mode, .type = Type::Text, .cli = "--mode", .json = "mode", .python = "mode",
       .pythonPlace = PythonPlace::Renderer, .cliGroup = kModeFlags, .range = "exact, cubemap, thesis-mesh",
       .engines = "fast", .help = "exact, cubemap (thesis' cube faces) or thesis-mesh (thesis' mirror mesh)",
       .shown = [](const Request& r) { return r.mode; }},
      {.field = RequestField::Faces, .type = Type::Integer, .cli = "--faces", .json = "mode_options.faces",
       .python = "faces", .pythonPlace = PythonPlace::Renderer, .cliGroup = kModeFlags,
       .range = "5 or 6", .engines = "fast: cubemap, thesis-mesh", .help = "cubemap/thesis-mesh: 5 (the thesis) or 6 cube faces",
       .shown = [](const Request& r) { return std::to_string(r.modeOptions.faces); }},
      {.field = RequestField::FaceSize, .type = Type::Integer, .cli = "--face-size", .json = "mode_options.face_size",
       .python = "face_size", .pythonPlace = PythonPlace::Renderer, .cliGroup = kModeFlags,
       .range = "8–8192", .engines = "fast: cubemap, thesis-mesh", .help = "cubemap/thesis-mesh: texels per face edge",
       .shown = [](const Request& r) { return std::to_string(r.modeOptions.faceSize); }},
      {.field = RequestField::Polygons, .type = Type::Integer, .cli = "--polygons", .json = "mode_options.polygons",
       .python = "polygons", .pythonPlace = PythonPlace::Renderer, .cliGroup = kModeFlags,
       .range = "16, 64, 256, 1024", .engines = "fast: thesis-mesh", .help = "thesis-mesh: mirror polygons",
       .shown = [](const Request& r) { return std::to_string(r.modeOptions.polygons); }},
      {.field = RequestField::Spp, .type = Type::Integer, .cli = "--spp", .json = "spp", .python = "spp",
       .pythonPlace = PythonPlace::Render, .cliGroup = kSppFlag, .range = "n², up to " + maxSpp,
       .help = "Samples per pixel, n*n on a regular grid", .shown = [](const Request& r) { return std::to_string(r.spp); }},
      {.field = RequestField::Shading, .type = Type::Text, .cli = "--shading", .json = "shading", .python = "shading",
       .pythonPlace = PythonPlace::Render, .cliGroup = kShadingFlag, .range = "unlit, lit, path",
       .engines = "all (path: fast exact, blender)",
       .help = "unlit, lit (the thesis' model) or path (physically based, docs/conventions.md §3)",
       .shown = [](const Request& r) { return std::string(shadingName(r.shading)); }},
      {.field = RequestField::Traced, .type = Type::Switch, .python = "traced", .pythonPlace = PythonPlace::Render,
       .range = "on, off", .engines = "fast: exact", .help = "Trace the physical camera even for the ideal rig",
       .shown = [](const Request& r) { return onOff(r.traced); }},
      {.field = RequestField::Bounces, .type = Type::Integer, .cli = "--bounces", .json = "bounces", .python = "bounces",
       .pythonPlace = PythonPlace::Render, .cliGroup = kPathFlags, .range = "0–" + maxBounces,
       .engines = "shading path", .help = "path: diffuse bounces per path, as Cycles' diffuse_bounces",
       .shown = [](const Request& r) { return std::to_string(r.bounces); }},
      {.field = RequestField::Seed, .type = Type::Integer, .cli = "--seed", .json = "seed", .python = "seed",
       .pythonPlace = PythonPlace::Render, .cliGroup = kPathFlags,
       .range = "0–2^53", .engines = "shading path, blender", .help = "path and blender: the random stream's seed",
       .shown = [](const Request& r) { return std::to_string(r.seed); }},
      {.field = RequestField::Denoise, .type = Type::Switch, .cli = "--denoise", .json = "denoise", .python = "denoise",
       .pythonPlace = PythonPlace::Render, .cliGroup = kPathFlags, .range = "on, off",
       .engines = "shading path, blender lit",
       .help = "Path-traced frames: filter the noise, guided by albedo, normal and depth (a small bias)",
       .shown = [](const Request& r) { return onOff(r.denoise); }},
      {.field = RequestField::AdaptiveSpp, .type = Type::Integer, .cli = "--adaptive-spp", .json = "adaptive_spp",
       .python = "adaptive_spp", .pythonPlace = PythonPlace::Render, .cliGroup = kPathFlags,
       .range = "0 (off), or spp·4^k (k ≥ 1; spp ≥ 4) up to " + maxSpp, .engines = "fast: exact, shading path",
       .help = "Adaptive sampling: pixels above --target-error are traced again on finer grids, up to this many samples "
               "(unfiltered still frames)",
       .shown = [](const Request& r) { return std::to_string(r.adaptiveSpp); }},
      {.field = RequestField::TargetError, .type = Type::Number, .cli = "--target-error", .json = "target_error",
       .python = "target_error", .pythonPlace = PythonPlace::Render, .cliGroup = kPathFlags, .cliNumberMax = 1.0,
       .range = "(0, 1]", .engines = "with adaptive_spp",
       .help = "Adaptive sampling: the relative error a pixel is refined to (std. error of luminance / sqrt(luminance))",
       .shown = [](const Request& r) { return shortNumber(r.targetError); }},
      {.field = RequestField::Timeout, .type = Type::Number, .cli = "--timeout", .json = "timeout_s", .python = "timeout",
       .pythonPlace = PythonPlace::Renderer, .cliGroup = kTimeoutFlag, .cliNumberMax = limits::kMaxTimeoutSeconds,
       .range = "(0, " + shortNumber(limits::kMaxTimeoutSeconds) + "] s", .engines = "povray, blender",
       .help = "Seconds allowed per external render", .shown = [](const Request& r) { return shortNumber(r.timeoutSeconds); }},
      {.field = RequestField::Threads, .type = Type::Integer, .python = "threads", .pythonPlace = PythonPlace::Renderer,
       .range = "0–" + std::to_string(limits::kMaxThreads), .engines = "all",
       .help = "Render threads: the fast engine's, a ground truth's renderer's; 0: every core (a dataset's --threads and threads set it)",
       .shown = [](const Request& r) { return std::to_string(r.threads); }},
  };
}

}  // namespace

std::string RequestFieldRow::defaultText() const { return shown(RenderRequest{}); }

const std::vector<RequestFieldRow>& requestFieldRows() {
  static const std::vector<RequestFieldRow> rows = makeRows();
  return rows;
}

}  // namespace omnicam
