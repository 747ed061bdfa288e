#pragma once
// The scene format's calibration targets (docs/scene-format.md, "Calibration targets"): the
// pattern, its margin and where the board stands, read strictly.
#include <string>
#include <vector>

#include "calibration_target.h"
#include "json_fields.h"

namespace omnicam {

// The target `name` of the object `o` (its pattern, margin and pose; not its shades, class or
// board, which the loader reads after); fails on the field at fault. The boards of `others`
// count toward the scene's texel budget.
CalibrationTarget readCalibrationTarget(JsonFields& o, const std::string& name,
                                        const std::vector<CalibrationTarget>& others);

}  // namespace omnicam
