#pragma once
// Error kinds that map to the CLI's exit codes (docs/conventions.md, "Exit codes"):
// bad input → 2, external renderer → 3, anything else (a bug) → 4, output not written → 5.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace omnicam {

// Invalid scene, image or argument. The message is one line: "<file or flag>: <field>: <what>".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An external program (POV-Ray, Blender) failed or is missing.
class ExternalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output could not be written (disk full, file-size limit, permissions, I/O error): not the
// user's input at fault. Nothing is left under the final name.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// User text echoed in a message (names, values, JSON keys, paths, arguments) goes through
// these, so that a message stays one readable line whatever the user wrote.
inline constexpr size_t kEchoedTextChars = 60;   // names, values, keys
inline constexpr size_t kEchoedPathChars = 200;  // paths: their file name is at the end

// `text` in double quotes, escaped: \\, \", \n, \t, \r, and \xNN for other control characters,
// DEL, C1 controls and bytes that are not UTF-8 (valid UTF-8 stays readable). Text longer than
// `maxChars` (an escape counts its length) is cut between characters: "abc…" (300 bytes).
std::string quote(std::string_view text, size_t maxChars = kEchoedTextChars);
// Whether `text` is UTF-8 throughout: what JSON (sidecars, manifests, job files) can record.
bool isValidUtf8(std::string_view text);
// A path as messages show it: as is when it needs no escaping and fits in kEchoedPathChars,
// otherwise quote(path, kEchoedPathChars) — the quotes mark that it was escaped.
std::string showPath(std::string_view path);
// A whole message made one line: control characters and bytes that are not UTF-8 escaped as in
// quote(), nothing else touched. The CLI's last defence; each echoed string is quoted first.
std::string oneLine(std::string_view message);

}  // namespace omnicam
