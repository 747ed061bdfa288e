#pragma once
// The render request's settings as rows, as output kinds are (outputs/output_kinds.h): each
// setting is declared once, in request_field_table.cpp — its names on the command line, in a dataset spec and in
// Python, its type, range, help text and the engines that take it; its default is
// RenderRequest's. The CLI flags, the spec reader and the docs' table are made from the rows;
// Python's keywords and the .pyi are checked against them (request_fields_test.cpp,
// python/tests/test_request_fields.py). A new setting is one row there plus its use in
// readRenderRequest (render_request.cpp).
#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace omnicam {

struct RenderRequest;

enum class RequestField {
  Engine, Mode, Faces, FaceSize, Polygons, Spp, Shading, Traced, Bounces, Seed, Denoise, AdaptiveSpp, TargetError, Timeout, Threads
};

// How a value is written: a word, an integer, a number, or a switch (a CLI flag without value).
enum class RequestFieldType { Text, Integer, Number, Switch };

// The CLI verbs register the request's flags in groups (a verb without modes has no --faces).
enum RequestFlagGroup : unsigned {
  kEngineFlag = 1u,   // --engine
  kModeFlags = 2u,    // --mode, --faces, --face-size, --polygons
  kSppFlag = 4u,      // --spp
  kShadingFlag = 8u,  // --shading
  kTimeoutFlag = 16u,  // --timeout
  kPathFlags = 32u     // --bounces, --seed, --denoise, --adaptive-spp, --target-error: what path shading takes
};

// Where Python takes a setting: when the Renderer is made (the engine's part), or per render.
enum class PythonPlace { None, Renderer, Render };

struct RequestFieldRow {
  RequestField field;
  RequestFieldType type;
  const char* cli = nullptr;     // "--face-size"; nullptr: no flag
  const char* json = nullptr;    // "mode_options.face_size" (a dotted path); nullptr: not in specs
  const char* python = nullptr;  // "face_size"; nullptr: not a keyword
  PythonPlace pythonPlace = PythonPlace::None;
  unsigned cliGroup = 0;         // the RequestFlagGroup that registers the flag
  // The CLI's syntax check of a number, (0, cliNumberMax]; an integer's is any 64-bit integer
  // (the request checks the rule itself, so a spec and Python get the same message).
  double cliNumberMax = 0.0;
  std::string range;             // the rule, as the docs' table states it
  const char* engines = "all";   // the engines (and modes) that take it
  std::string help;              // one line; the default is appended from RenderRequest
  // The value in `request`, as the docs and help show it ("600", "unlit", "off").
  std::string (*shown)(const RenderRequest& request) = nullptr;

  // The default, as shown: RenderRequest's, stated nowhere else.
  std::string defaultText() const;
};

const std::vector<RequestFieldRow>& requestFieldRows();
const RequestFieldRow& requestFieldRow(RequestField field);

// How a front end names each field in messages, and a prefix before them (a spec's file name).
struct RequestFieldNames {
  enum class Front { Library, Cli, Json };  // the library speaks Python's names
  std::string prefix;
  Front front = Front::Library;
  // The field's name as this front spells it (the library's: the Python keyword); a field the
  // front does not have is named as the library names it.
  std::string operator()(RequestField field) const;
  static RequestFieldNames cli();                         // --engine, --face-size, …
  static RequestFieldNames json(const std::string& file);  // "FILE: engine", "FILE: mode_options.faces", …
};

// One setting's value as a user gave it, typed as its row says.
using RequestValue = std::variant<std::string, int64_t, double, bool>;

// The settings as a user gave them: an absent one takes RenderRequest's default.
class RequestFields {
 public:
  RequestFields() = default;
  RequestFields(std::initializer_list<std::pair<const RequestField, RequestValue>> given);
  // std::logic_error for a value of another type than the row's (a programming error).
  void set(RequestField field, RequestValue value);
  // Sets the field when `value` holds one.
  template <typename T>
  void setIfGiven(RequestField field, const std::optional<T>& value) {
    if (value) set(field, RequestValue(*value));
  }
  bool has(RequestField field) const { return given_.count(field) > 0; }
  std::optional<std::string> text(RequestField field) const;
  std::optional<int64_t> integer(RequestField field) const;
  std::optional<double> number(RequestField field) const;
  std::optional<bool> isOn(RequestField field) const;

 private:
  std::map<RequestField, RequestValue> given_;
};

// The docs' table of the settings (docs/render-settings.md between its markers): made from the
// rows, checked by request_fields_test.
std::string requestFieldsMarkdown();

}  // namespace omnicam
