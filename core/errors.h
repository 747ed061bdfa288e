#pragma once
// Error kinds that map to the CLI's exit codes (spec §7): bad input → 2, external renderer → 3.
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

}  // namespace omnicam
