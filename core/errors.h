#pragma once
// Error kinds that map to the CLI's exit codes (docs/conventions.md, "Exit codes"):
// bad input → 2, external renderer → 3, anything else (a bug) → 4, output not written → 5.
#include <stdexcept>
#include <string>

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

}  // namespace omnicam
