#include "request_fields.h"

#include <sstream>
#include <stdexcept>

#include "errors.h"
#include "input_limits.h"
#include "number_format.h"
#include "render_request.h"

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
       .python = "faces", .pythonPlace = PythonPlace::Renderer, .cliGroup = kModeFlags, .cliIntegerMax = INT32_MAX,
       .range = "5 or 6", .engines = "fast: cubemap, thesis-mesh", .help = "cubemap/thesis-mesh: 5 (the thesis) or 6 cube faces",
       .shown = [](const Request& r) { return std::to_string(r.modeOptions.faces); }},
      {.field = RequestField::FaceSize, .type = Type::Integer, .cli = "--face-size", .json = "mode_options.face_size",
       .python = "face_size", .pythonPlace = PythonPlace::Renderer, .cliGroup = kModeFlags, .cliIntegerMax = INT32_MAX,
       .range = "8–8192", .engines = "fast: cubemap, thesis-mesh", .help = "cubemap/thesis-mesh: texels per face edge",
       .shown = [](const Request& r) { return std::to_string(r.modeOptions.faceSize); }},
      {.field = RequestField::Polygons, .type = Type::Integer, .cli = "--polygons", .json = "mode_options.polygons",
       .python = "polygons", .pythonPlace = PythonPlace::Renderer, .cliGroup = kModeFlags, .cliIntegerMax = INT32_MAX,
       .range = "16, 64, 256, 1024", .engines = "fast: thesis-mesh", .help = "thesis-mesh: mirror polygons",
       .shown = [](const Request& r) { return std::to_string(r.modeOptions.polygons); }},
      {.field = RequestField::Spp, .type = Type::Integer, .cli = "--spp", .json = "spp", .python = "spp",
       .pythonPlace = PythonPlace::Render, .cliGroup = kSppFlag, .cliIntegerMax = INT32_MAX, .range = "n², up to " + maxSpp,
       .help = "Samples per pixel, n*n on a regular grid", .shown = [](const Request& r) { return std::to_string(r.spp); }},
      {.field = RequestField::Shading, .type = Type::Text, .cli = "--shading", .json = "shading", .python = "shading",
       .pythonPlace = PythonPlace::Render, .cliGroup = kShadingFlag, .range = "unlit, lit, path",
       .help = "unlit, lit (the thesis' model) or path (physically based, docs/conventions.md §3)",
       .shown = [](const Request& r) { return std::string(shadingName(r.shading)); }},
      {.field = RequestField::Traced, .type = Type::Switch, .python = "traced", .pythonPlace = PythonPlace::Render,
       .range = "on, off", .engines = "fast: exact", .help = "Trace the physical camera even for the ideal rig",
       .shown = [](const Request& r) { return onOff(r.traced); }},
      {.field = RequestField::Bounces, .type = Type::Integer, .cli = "--bounces", .json = "bounces", .python = "bounces",
       .pythonPlace = PythonPlace::Render, .cliGroup = kShadingFlag, .cliIntegerMax = kMaxBounces, .range = "0–" + maxBounces,
       .engines = "shading path", .help = "path: diffuse bounces per path, as Cycles' diffuse_bounces",
       .shown = [](const Request& r) { return std::to_string(r.bounces); }},
      {.field = RequestField::Seed, .type = Type::Integer, .cli = "--seed", .json = "seed", .python = "seed",
       .pythonPlace = PythonPlace::Render, .cliGroup = kShadingFlag, .cliIntegerMax = INT64_MAX,
       .range = "0–2^53", .engines = "shading path, blender", .help = "path and blender: the random stream's seed",
       .shown = [](const Request& r) { return std::to_string(r.seed); }},
      {.field = RequestField::Denoise, .type = Type::Switch, .cli = "--denoise", .json = "denoise", .python = "denoise",
       .pythonPlace = PythonPlace::Render, .cliGroup = kShadingFlag, .range = "on, off",
       .engines = "shading path, blender lit",
       .help = "Path-traced frames: filter the indirect light, guided by albedo, normal and depth (a small bias)",
       .shown = [](const Request& r) { return onOff(r.denoise); }},
      {.field = RequestField::Timeout, .type = Type::Number, .cli = "--timeout", .json = "timeout_s", .python = "timeout",
       .pythonPlace = PythonPlace::Renderer, .cliGroup = kTimeoutFlag, .cliNumberMax = limits::kMaxTimeoutSeconds,
       .range = "(0, " + shortNumber(limits::kMaxTimeoutSeconds) + "] s", .engines = "povray, blender",
       .help = "Seconds allowed per external render", .shown = [](const Request& r) { return shortNumber(r.timeoutSeconds); }},
      {.field = RequestField::Threads, .type = Type::Integer, .python = "threads", .pythonPlace = PythonPlace::Renderer,
       .range = "0–" + std::to_string(limits::kMaxThreads), .engines = "povray, blender",
       .help = "A ground truth's render threads; 0: every core (a dataset's --threads and threads set it)",
       .shown = [](const Request& r) { return std::to_string(r.threads); }},
  };
}

const char* typeName(RequestFieldType type) {
  switch (type) {
    case Type::Text: return "word";
    case Type::Integer: return "integer";
    case Type::Number: return "number";
    case Type::Switch: return "switch";
  }
  return "?";
}

// The variant alternative each type holds.
bool holds(RequestFieldType type, const RequestValue& value) {
  switch (type) {
    case Type::Text: return std::holds_alternative<std::string>(value);
    case Type::Integer: return std::holds_alternative<int64_t>(value);
    case Type::Number: return std::holds_alternative<double>(value);
    case Type::Switch: return std::holds_alternative<bool>(value);
  }
  return false;
}

template <typename T>
std::optional<T> valueOf(const std::map<RequestField, RequestValue>& given, RequestField field) {
  const auto it = given.find(field);
  if (it == given.end()) return std::nullopt;
  if (const T* v = std::get_if<T>(&it->second)) return *v;
  throw std::logic_error(std::string("request field ") + requestFieldRow(field).python + " read as another type");
}

std::string code(const char* name) { return name ? std::string("`") + name + "`" : "—"; }

}  // namespace

std::string RequestFieldRow::defaultText() const { return shown(RenderRequest{}); }

const std::vector<RequestFieldRow>& requestFieldRows() {
  static const std::vector<RequestFieldRow> rows = makeRows();
  return rows;
}

const RequestFieldRow& requestFieldRow(RequestField field) {
  for (const RequestFieldRow& row : requestFieldRows())
    if (row.field == field) return row;
  throw std::logic_error("request field without a row");
}

std::string RequestFieldNames::operator()(RequestField field) const {
  const RequestFieldRow& row = requestFieldRow(field);
  const char* own = front == Front::Cli ? row.cli : front == Front::Json ? row.json : row.python;
  return own ? own : row.python;
}

RequestFieldNames RequestFieldNames::cli() { return {"", Front::Cli}; }

RequestFieldNames RequestFieldNames::json(const std::string& file) { return {showPath(file) + ": ", Front::Json}; }

RequestFields::RequestFields(std::initializer_list<std::pair<const RequestField, RequestValue>> given) {
  for (const auto& [field, value] : given) set(field, value);
}

void RequestFields::set(RequestField field, RequestValue value) {
  const RequestFieldRow& row = requestFieldRow(field);
  if (!holds(row.type, value))
    throw std::logic_error(std::string("request field ") + row.python + " must be given as a " + typeName(row.type));
  given_[field] = std::move(value);
}

std::optional<std::string> RequestFields::text(RequestField field) const { return valueOf<std::string>(given_, field); }
std::optional<int64_t> RequestFields::integer(RequestField field) const { return valueOf<int64_t>(given_, field); }
std::optional<double> RequestFields::number(RequestField field) const { return valueOf<double>(given_, field); }
std::optional<bool> RequestFields::isOn(RequestField field) const { return valueOf<bool>(given_, field); }

std::string requestFieldsMarkdown() {
  std::ostringstream md;
  md << "| Python | CLI | dataset spec | type | default | range | engines | what it does |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const RequestFieldRow& row : requestFieldRows()) {
    const char* place = row.pythonPlace == PythonPlace::Renderer ? " (Renderer)" : row.pythonPlace == PythonPlace::Render ? " (render)" : "";
    md << "| " << code(row.python) << place << " | " << code(row.cli) << " | " << code(row.json) << " | " << typeName(row.type) << " | " << row.defaultText() << " | " << row.range << " | " << row.engines << " | "
       << row.help << " |\n";
  }
  return md.str();
}

}  // namespace omnicam
