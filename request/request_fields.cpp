#include "request_fields.h"

#include <sstream>
#include <stdexcept>

#include "errors.h"

namespace omnicam {

namespace {

using Type = RequestFieldType;

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
